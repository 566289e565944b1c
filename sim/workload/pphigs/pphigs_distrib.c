/* pphigs_distrib.c — distribute-by-primitive of a hierarchical display list
 * (see distrib.h).  Seed 001 §2.2-2.3 (distribution), §3 (editing),
 * §4 (order-dependent primitives).
 *
 * Bookkeeping: for every host element a 64-bit mask of the GPs holding a
 * copy; a GP's position of host element i is the number of elements
 * before i whose mask has that GP (O(n) to find, which keeps the GP
 * lists exact subsequences of the host's).  Per structure: nominal load
 * of each GP (for least-loaded choices), the open cluster, and the
 * pending edit region.  Global load per GP breaks ties.
 * Costs: distributing a structure is O(n * ngp) plus O(n) per element
 * sent; a backward scan is bounded as §3.5 says.
 */
#include "sim/workload/pphigs/pphigs_distrib.h"
#include <string.h>

#define NONE (-1)

typedef struct {
    GArray *mask;     /* uint64_t per host element */
    double *load;     /* ngp nominal loads of this structure */
    gint cur;         /* open cluster's GP, NONE */
    double run;       /* nominal weight in the open cluster */
    gint first, last; /* pending edit region, NONE */
} StructMeta;

struct WlPphigsDist {
    SceneDb *host;
    SceneDb **gp;
    guint ngp;
    WlPphigsAlgo algo;
    WlPphigsWeights w;
    double maxw;     /* largest primitive weight seen */
    GPtrArray *meta; /* StructMeta * per structure */
    double *gload;   /* global nominal load per GP */
    uint64_t next_id;
    WlPphigsTraffic traffic;
};

/* The host's current attribute elements known at a point (positions). */
typedef struct {
    gint colour, replace;
    GArray *concats; /* gint, in host order */
} AttrState;

static uint64_t all_mask(const WlPphigsDist *d)
{
    return d->ngp == 64 ? ~(uint64_t)0 : (((uint64_t)1 << d->ngp) - 1);
}

static StructMeta *meta(const WlPphigsDist *d, guint sid)
{
    return g_ptr_array_index(d->meta, sid);
}

static uint64_t *mask_at(const WlPphigsDist *d, guint sid, guint pos)
{
    return &g_array_index(meta(d, sid)->mask, uint64_t, pos);
}

static const SceneElem *hel(const WlPphigsDist *d, guint sid, guint pos)
{
    return scene_db_elem(d->host, sid, pos);
}

static gboolean is_prim_struct(const WlPphigsDist *d, guint sid)
{
    return d->algo == WL_PPHIGS_COMPLEX && scene_db_is_primitive(d->host, sid);
}

/* Dealt like a primitive: primitives and primitive-structure executes. */
static gboolean is_dealt(const WlPphigsDist *d, const SceneElem *e)
{
    return scene_elem_is_prim(e->kind) ||
           (e->kind == SCENE_EL_EXECUTE && is_prim_struct(d, e->child));
}

double wl_pphigs_dist_weight(const WlPphigsDist *d, const SceneElem *e)
{
    double w = d->w.w[e->kind];
    if (scene_elem_is_prim(e->kind))
        return w + d->w.w_vertex * e->nverts;
    if (e->kind == SCENE_EL_EXECUTE && is_prim_struct(d, e->child))
        for (guint i = 0; i < scene_db_len(d->host, e->child); i++)
            w += wl_pphigs_dist_weight(d, hel(d, e->child, i));
    return w;
}

/* ---- GP copies -------------------------------------------------------- */

static guint gp_pos(const WlPphigsDist *d, guint sid, guint pos, guint g)
{
    guint n = 0;
    for (guint i = 0; i < pos; i++)
        n += (*mask_at(d, sid, i) >> g) & 1;
    return n;
}

static void gp_put(WlPphigsDist *d, guint sid, guint pos, guint g)
{
    uint64_t *m = mask_at(d, sid, pos);
    if ((*m >> g) & 1)
        return;
    gboolean ok = scene_db_insert(d->gp[g], sid, gp_pos(d, sid, pos, g),
                                  hel(d, sid, pos), NULL);
    g_assert(ok);
    *m |= (uint64_t)1 << g;
    d->traffic.elements_sent++;
    d->traffic.sent_to[g]++;
}

static void gp_put_all(WlPphigsDist *d, guint sid, guint pos)
{
    for (guint g = 0; g < d->ngp; g++)
        gp_put(d, sid, pos, g);
}

static void gp_drop(WlPphigsDist *d, guint sid, guint pos, guint g)
{
    uint64_t *m = mask_at(d, sid, pos);
    if (!((*m >> g) & 1))
        return;
    scene_db_delete(d->gp[g], sid, gp_pos(d, sid, pos, g));
    *m &= ~((uint64_t)1 << g);
    d->traffic.elements_removed++;
}

/* ---- attribute states ------------------------------------------------- */

static void state_init(AttrState *s)
{
    s->colour = s->replace = NONE;
    s->concats = g_array_new(FALSE, FALSE, sizeof(gint));
}

static void state_clear(AttrState *s)
{
    g_array_unref(s->concats);
}

/* The host state after element i (forward direction). */
static void state_step(AttrState *s, const SceneElem *e, gint i)
{
    if (e->kind == SCENE_EL_COLOR) {
        s->colour = i;
    } else if (e->kind == SCENE_EL_MATRIX && e->mode == SCENE_MAT_REPLACE) {
        s->replace = i;
        g_array_set_size(s->concats, 0);
    } else if (e->kind == SCENE_EL_MATRIX) {
        g_array_append_val(s->concats, i);
    }
}

/* Sends GP g every known current attribute it lacks. */
static void ensure(WlPphigsDist *d, guint sid, const AttrState *s, guint g)
{
    if (s->colour != NONE)
        gp_put(d, sid, (guint)s->colour, g);
    if (s->replace != NONE)
        gp_put(d, sid, (guint)s->replace, g);
    for (guint k = 0; k < s->concats->len; k++)
        gp_put(d, sid, (guint)g_array_index(s->concats, gint, k), g);
}

static void ensure_matrices_all(WlPphigsDist *d, guint sid, const AttrState *s)
{
    for (guint g = 0; g < d->ngp; g++) {
        if (s->replace != NONE)
            gp_put(d, sid, (guint)s->replace, g);
        for (guint k = 0; k < s->concats->len; k++)
            gp_put(d, sid, (guint)g_array_index(s->concats, gint, k), g);
    }
}

/* ---- choosing a GP ---------------------------------------------------- */

static guint least_loaded(const WlPphigsDist *d, const StructMeta *m)
{
    guint best = 0;
    for (guint g = 1; g < d->ngp; g++) {
        double a = m->load[g], b = m->load[best];
        if (a < b - 1e-12 ||
            (fabs(a - b) <= 1e-12 && d->gload[g] < d->gload[best] - 1e-12))
            best = g;
    }
    return best;
}

/* §2.3.2: stay on the open cluster while it holds at most c * maxw. */
static guint choose(WlPphigsDist *d, guint sid, double w)
{
    StructMeta *m = meta(d, sid);
    double budget = d->algo == WL_PPHIGS_COMPLEX ? d->w.cluster * d->maxw : 0;
    if (m->cur == NONE || m->run + w > budget + 1e-12) {
        m->cur = (gint)least_loaded(d, m);
        m->run = 0;
    }
    m->run += w;
    return (guint)m->cur;
}

static void add_load(WlPphigsDist *d, guint sid, guint g, double w)
{
    meta(d, sid)->load[g] += w;
    d->gload[g] += w;
}

/* ---- the forward walk (initial distribution, append, step 2) ---------- */

static void simple_elem(WlPphigsDist *d, guint sid, guint i)
{
    const SceneElem *e = hel(d, sid, i);
    uint64_t *m = mask_at(d, sid, i);
    if (!is_dealt(d, e)) {
        gp_put_all(d, sid, i);
    } else if (*m == 0) {
        double w = wl_pphigs_dist_weight(d, e);
        guint g = choose(d, sid, w);
        add_load(d, sid, g, w);
        gp_put(d, sid, i, g);
    }
}

/* Deals element i (complex); returns the GPs it checked. */
static uint64_t complex_elem(WlPphigsDist *d, guint sid, guint i, AttrState *s)
{
    const SceneElem *e = hel(d, sid, i);
    uint64_t *m = mask_at(d, sid, i);
    if (scene_elem_is_attr(e->kind)) {
        state_step(s, e, (gint)i);
        if (e->kind == SCENE_EL_MATRIX && e->mode == SCENE_MAT_CONCAT)
            ensure_matrices_all(d, sid, s);
        return 0;
    }
    if (!is_dealt(d, e)) { /* ordinary execute: flush, then to all */
        for (guint g = 0; g < d->ngp; g++)
            ensure(d, sid, s, g);
        gp_put_all(d, sid, i);
        return all_mask(d);
    }
    guint g;
    if (*m == 0) {
        double w = wl_pphigs_dist_weight(d, e);
        g = choose(d, sid, w);
        add_load(d, sid, g, w);
    } else {
        g = (guint)__builtin_ctzll(*m);
    }
    ensure(d, sid, s, g);
    gp_put(d, sid, i, g);
    return (uint64_t)1 << g;
}

/* Walks from `from`, past `last` until every GP has been checked. */
static void forward(WlPphigsDist *d, guint sid, guint from, gint last,
                    AttrState *s)
{
    uint64_t checked = 0;
    guint n = scene_db_len(d->host, sid);
    for (guint i = from; i < n; i++) {
        gboolean plain = d->algo == WL_PPHIGS_SIMPLE || is_prim_struct(d, sid);
        if ((gint)i > last && (plain || checked == all_mask(d)))
            break;
        if (is_prim_struct(d, sid))
            gp_put_all(d, sid, i);
        else if (d->algo == WL_PPHIGS_SIMPLE)
            simple_elem(d, sid, i);
        else if ((gint)i > last) /* only checks after the region count */
            checked |= complex_elem(d, sid, i, s);
        else
            (void)complex_elem(d, sid, i, s);
    }
}

/* §3.4-3.5: steps back from `first` collecting the host's current
 * attributes until every GP is known current. */
static void backward(WlPphigsDist *d, guint sid, guint first, AttrState *s)
{
    uint64_t cur = 0, examined = 0;
    gboolean replace_found = FALSE;
    for (gint j = (gint)first - 1; j >= 0 && cur != all_mask(d); j--) {
        const SceneElem *e = hel(d, sid, (guint)j);
        examined++;
        if (e->kind == SCENE_EL_COLOR) {
            if (s->colour == NONE)
                s->colour = j;
        } else if (e->kind == SCENE_EL_MATRIX) {
            if (replace_found)
                continue;
            if (e->mode == SCENE_MAT_REPLACE) {
                s->replace = j;
                replace_found = TRUE;
            } else {
                g_array_prepend_val(s->concats, j);
            }
        } else if (!is_dealt(d, e)) {
            break; /* every GP was flushed before this execute */
        } else {
            cur |= *mask_at(d, sid, (guint)j);
        }
    }
    d->traffic.last_scan = examined;
    d->traffic.max_scan = MAX(d->traffic.max_scan, examined);
}

static void step2(WlPphigsDist *d, guint sid, guint first, gint last)
{
    AttrState s;
    state_init(&s);
    if (!is_prim_struct(d, sid) && d->algo == WL_PPHIGS_COMPLEX)
        backward(d, sid, first, &s);
    forward(d, sid, first, last, &s);
    state_clear(&s);
}

/* ---- ODP deltas (§4) -------------------------------------------------- */

static int64_t odp_total(const WlPphigsDist *d, guint sid, int64_t *memo)
{
    if (memo[sid] >= 0)
        return memo[sid];
    int64_t t = 0;
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = hel(d, sid, i);
        if (e->kind == SCENE_EL_POLYGON2D)
            t++;
        else if (e->kind == SCENE_EL_EXECUTE)
            t += odp_total(d, e->child, memo);
    }
    return memo[sid] = t;
}

static void struct_deltas(WlPphigsDist *d, guint sid, int64_t *memo,
                          int64_t *last, guint *idx)
{
    int64_t acc = 0;
    memset(last, 0, d->ngp * sizeof *last);
    memset(idx, 0, d->ngp * sizeof *idx);
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = hel(d, sid, i);
        gboolean odp = e->kind == SCENE_EL_POLYGON2D;
        int64_t adv = odp ? 1
                      : e->kind == SCENE_EL_EXECUTE
                          ? odp_total(d, e->child, memo)
                          : 0;
        uint64_t m = *mask_at(d, sid, i);
        for (guint g = 0; g < d->ngp; g++) {
            if (!((m >> g) & 1))
                continue;
            int64_t dl = 0;
            if (odp || e->kind == SCENE_EL_EXECUTE) {
                dl = acc + odp - last[g];
                last[g] = acc + adv;
            }
            scene_db_set_delta(d->gp[g], sid, idx[g]++, dl);
        }
        acc += adv;
    }
    for (guint g = 0; g < d->ngp; g++)
        scene_db_set_end_delta(d->gp[g], sid, acc - last[g]);
}

static void refresh_deltas(WlPphigsDist *d)
{
    guint n = scene_db_struct_count(d->host);
    int64_t *memo = g_new(int64_t, n), *last = g_new(int64_t, d->ngp);
    guint *idx = g_new(guint, d->ngp);
    for (guint s = 0; s < n; s++)
        memo[s] = -1;
    for (guint s = 0; s < n; s++)
        struct_deltas(d, s, memo, last, idx);
    g_free(idx);
    g_free(last);
    g_free(memo);
}

/* ---- lifecycle -------------------------------------------------------- */

/* ---- distribute-by-structure (§2.1) ----------------------------------- */

/* Nominal weight of a structure with everything it executes (max-set). */
static double subtree_weight(const WlPphigsDist *d, guint sid, double *memo)
{
    if (memo[sid] >= 0)
        return memo[sid];
    double w = 0;
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = hel(d, sid, i);
        w += wl_pphigs_dist_weight(d, e);
        if (e->kind == SCENE_EL_EXECUTE)
            w += subtree_weight(d, e->child, memo);
    }
    return memo[sid] = w;
}

/* A structure and everything it executes, whole, to GP g. */
static void put_whole(WlPphigsDist *d, guint sid, guint g)
{
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        gp_put(d, sid, i, g);
        if (hel(d, sid, i)->kind == SCENE_EL_EXECUTE)
            put_whole(d, hel(d, sid, i)->child, g);
    }
}

static guint least_global(const WlPphigsDist *d)
{
    guint best = 0;
    for (guint g = 1; g < d->ngp; g++)
        if (d->gload[g] < d->gload[best] - 1e-12)
            best = g;
    return best;
}

typedef struct {
    double *memo;  /* subtree weights, -1 unknown */
    guint *uses;   /* executes of each structure in the host list */
    double share;  /* the whole list's weight / GPs */
} ByStruct;

/* Attributes to every GP; each primitive and each structure instance
 * whole to the least-loaded GP; a structure instanced once whose weight
 * exceeds one GP's share is broken up (§2.1: "the structures can be
 * broken up"): its execute to every GP, its elements dealt in turn. */
static void bystruct_walk(WlPphigsDist *d, guint sid, ByStruct *b)
{
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = hel(d, sid, i);
        if (scene_elem_is_attr(e->kind)) {
            gp_put_all(d, sid, i);
            continue;
        }
        double w = wl_pphigs_dist_weight(d, e);
        gboolean exec = e->kind == SCENE_EL_EXECUTE;
        if (exec)
            w += subtree_weight(d, e->child, b->memo);
        if (exec && w > b->share && b->uses[e->child] == 1 &&
            !scene_db_is_posted(d->host, e->child)) {
            gp_put_all(d, sid, i);
            bystruct_walk(d, e->child, b);
            continue;
        }
        guint g = least_global(d);
        add_load(d, sid, g, w);
        gp_put(d, sid, i, g);
        if (exec)
            put_whole(d, e->child, g);
    }
}

/* FALSE when a posted structure is also executed: its posted instance
 * and the others would share one portion per GP, so it cannot be dealt
 * by instance. */
static gboolean bystruct_possible(const WlPphigsDist *d, const guint *uses)
{
    for (guint i = 0; i < scene_db_posted_count(d->host); i++)
        if (uses[scene_db_posted_at(d->host, i)])
            return FALSE;
    return TRUE;
}

/* Distributes by structure; FALSE (nothing dealt) when the list cannot
 * be, see bystruct_possible(). */
static gboolean distribute_by_structure(WlPphigsDist *d)
{
    guint n = scene_db_struct_count(d->host);
    ByStruct b = {g_new(double, n), g_new0(guint, n), 0};
    for (guint s = 0; s < n; s++) {
        b.memo[s] = -1;
        for (guint i = 0; i < scene_db_len(d->host, s); i++)
            if (hel(d, s, i)->kind == SCENE_EL_EXECUTE)
                b.uses[hel(d, s, i)->child]++;
    }
    gboolean ok = bystruct_possible(d, b.uses);
    for (guint i = 0; i < scene_db_posted_count(d->host); i++)
        b.share += subtree_weight(d, scene_db_posted_at(d->host, i), b.memo);
    b.share /= d->ngp;
    for (guint i = 0; ok && i < scene_db_posted_count(d->host); i++)
        bystruct_walk(d, scene_db_posted_at(d->host, i), &b);
    g_free(b.memo);
    g_free(b.uses);
    return ok;
}

static StructMeta *meta_new(guint ngp, guint len)
{
    StructMeta *m = g_new0(StructMeta, 1);
    m->mask = g_array_new(FALSE, TRUE, sizeof(uint64_t));
    g_array_set_size(m->mask, len);
    m->load = g_new0(double, ngp);
    m->cur = m->first = m->last = NONE;
    return m;
}

static void meta_free(gpointer p)
{
    StructMeta *m = p;
    g_array_unref(m->mask);
    g_free(m->load);
    g_free(m);
}

static void retag(WlPphigsDist *d)
{
    for (guint s = 0; s < scene_db_struct_count(d->host); s++)
        for (guint i = 0; i < scene_db_len(d->host, s); i++) {
            SceneElem e = *hel(d, s, i);
            e.tag = d->next_id++;
            gboolean ok = scene_db_modify(d->host, s, i, &e, NULL);
            g_assert(ok);
            if (scene_elem_is_prim(e.kind))
                d->maxw = MAX(d->maxw, wl_pphigs_dist_weight(d, &e));
        }
}

/* §2.3.2: strip (sid, pos) of n vertices as pieces of at most k
 * triangles (k even), in place. */
static void split_strip(SceneDb *db, guint sid, guint pos, guint k)
{
    SceneElem e = *scene_db_elem(db, sid, pos);
    Vec3 *v = g_memdup2(e.verts, e.nverts * sizeof *v);
    guint n = e.nverts, at = pos;
    scene_db_delete(db, sid, pos);
    for (guint j = 0; j + 2 < n; j += k) {
        SceneElem piece = e;
        piece.verts = v + j;
        piece.nverts = MIN(k + 2, n - j);
        gboolean ok = scene_db_insert(db, sid, at++, &piece, NULL);
        g_assert(ok);
    }
    g_free(v);
}

static void split_strips(SceneDb *db, guint k)
{
    k += k & 1;
    for (guint s = 0; s < scene_db_struct_count(db); s++)
        for (guint i = 0; i < scene_db_len(db, s); i++) {
            const SceneElem *e = scene_db_elem(db, s, i);
            if (e->kind == SCENE_EL_TRISTRIP && e->nverts > k + 2) {
                guint pieces = (e->nverts - 2 + k - 1) / k;
                split_strip(db, s, i, k);
                i += pieces - 1;
            }
        }
}

WlPphigsDist *wl_pphigs_dist_new(const SceneDb *src, guint ngp,
                                 WlPphigsAlgo algo, const WlPphigsWeights *w)
{
    g_assert(ngp >= 1 && ngp <= 64);
    WlPphigsDist *d = g_new0(WlPphigsDist, 1);
    d->host = scene_db_copy(src);
    d->ngp = ngp;
    d->algo = algo;
    d->w = *w;
    d->next_id = 1;
    d->gload = g_new0(double, ngp);
    d->meta = g_ptr_array_new_with_free_func(meta_free);
    d->gp = g_new0(SceneDb *, ngp);
    if (w->strip_split)
        split_strips(d->host, w->strip_split);
    retag(d);
    guint n = scene_db_struct_count(d->host);
    for (guint g = 0; g < ngp; g++) {
        d->gp[g] = scene_db_new();
        for (guint s = 0; s < n; s++) {
            scene_db_add_struct(d->gp[g], scene_db_struct_name(d->host, s));
            scene_db_set_primitive(d->gp[g], s,
                                   scene_db_is_primitive(d->host, s));
        }
        for (guint i = 0; i < scene_db_posted_count(d->host); i++)
            scene_db_post(d->gp[g], scene_db_posted_at(d->host, i));
    }
    for (guint s = 0; s < n; s++)
        g_ptr_array_add(d->meta, meta_new(ngp, scene_db_len(d->host, s)));
    if (algo == WL_PPHIGS_BY_STRUCTURE && !distribute_by_structure(d))
        d->algo = WL_PPHIGS_SIMPLE; /* see bystruct_possible() */
    if (d->algo != WL_PPHIGS_BY_STRUCTURE)
        for (guint s = 0; s < n; s++)
            step2(d, s, 0, (gint)scene_db_len(d->host, s) - 1);
    refresh_deltas(d);
    return d;
}

void wl_pphigs_dist_free(WlPphigsDist *d)
{
    if (!d)
        return;
    for (guint g = 0; g < d->ngp; g++)
        scene_db_free(d->gp[g]);
    g_free(d->gp);
    scene_db_free(d->host);
    g_ptr_array_unref(d->meta);
    g_free(d->gload);
    g_free(d);
}

WlPphigsAlgo wl_pphigs_dist_algo(const WlPphigsDist *d)
{
    return d->algo;
}

guint wl_pphigs_dist_ngp(const WlPphigsDist *d)
{
    return d->ngp;
}

const SceneDb *wl_pphigs_dist_host(const WlPphigsDist *d)
{
    return d->host;
}

const SceneDb *wl_pphigs_dist_gp(const WlPphigsDist *d, guint g)
{
    g_assert(g < d->ngp);
    return d->gp[g];
}

const WlPphigsTraffic *wl_pphigs_dist_traffic(const WlPphigsDist *d)
{
    return &d->traffic;
}

/* ---- edits ------------------------------------------------------------ */

static void region_add(StructMeta *m, gint p)
{
    if (m->first == NONE) {
        m->first = m->last = p;
        return;
    }
    m->first = MIN(m->first, p);
    m->last = MAX(m->last, p);
}

/* Sends a new element as step 1 says: dealt elements and executes at
 * once, attributes only to the host (complex); everything (simple). */
static void step1_send(WlPphigsDist *d, guint sid, guint pos)
{
    const SceneElem *e = hel(d, sid, pos);
    if (is_prim_struct(d, sid) || d->algo == WL_PPHIGS_SIMPLE) {
        forward(d, sid, pos, (gint)pos, NULL);
        return;
    }
    if (!is_dealt(d, e)) {
        if (!scene_elem_is_attr(e->kind))
            gp_put_all(d, sid, pos);
        return;
    }
    double w = wl_pphigs_dist_weight(d, e);
    meta(d, sid)->cur = NONE;
    guint g = choose(d, sid, w);
    add_load(d, sid, g, w);
    gp_put(d, sid, pos, g);
}

gboolean wl_pphigs_dist_insert(WlPphigsDist *d, guint sid, guint pos,
                               const SceneElem *e, GError **err)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    SceneElem c = *e;
    c.tag = d->next_id;
    if (!scene_db_insert(d->host, sid, pos, &c, err))
        return FALSE;
    d->next_id++;
    if (scene_elem_is_prim(c.kind))
        d->maxw = MAX(d->maxw, wl_pphigs_dist_weight(d, &c));
    StructMeta *m = meta(d, sid);
    uint64_t zero = 0;
    g_array_insert_val(m->mask, pos, zero);
    if (m->first != NONE && m->first >= (gint)pos)
        m->first++;
    if (m->last != NONE && m->last >= (gint)pos)
        m->last++;
    region_add(m, (gint)pos);
    step1_send(d, sid, pos);
    return TRUE;
}

void wl_pphigs_dist_delete(WlPphigsDist *d, guint sid, guint pos)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    const SceneElem *e = hel(d, sid, pos);
    uint64_t msk = *mask_at(d, sid, pos);
    if (is_dealt(d, e) && !is_prim_struct(d, sid) && msk)
        add_load(d, sid, (guint)__builtin_ctzll(msk),
                 -wl_pphigs_dist_weight(d, e));
    for (guint g = 0; g < d->ngp; g++)
        gp_drop(d, sid, pos, g);
    scene_db_delete(d->host, sid, pos);
    StructMeta *m = meta(d, sid);
    g_array_remove_index(m->mask, pos);
    if (m->first != NONE && m->first > (gint)pos)
        m->first--;
    if (m->last != NONE && m->last >= (gint)pos)
        m->last--;
    region_add(m, (gint)pos);
}

gboolean wl_pphigs_dist_append(WlPphigsDist *d, guint sid, const SceneElem *e,
                               GError **err)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    if (!wl_pphigs_dist_insert(d, sid, scene_db_len(d->host, sid), e, err))
        return FALSE;
    wl_pphigs_dist_finish(d);
    return TRUE;
}

gboolean wl_pphigs_dist_modify(WlPphigsDist *d, guint sid, guint pos,
                               const SceneElem *e, GError **err)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    const SceneElem *old = hel(d, sid, pos);
    if (old->kind == e->kind && is_dealt(d, old) != is_dealt(d, e)) {
        /* an execute changing between ordinary and primitive structure */
        if (!wl_pphigs_dist_insert(d, sid, pos, e, err))
            return FALSE;
        wl_pphigs_dist_delete(d, sid, pos + 1);
        wl_pphigs_dist_finish(d);
        return TRUE;
    }
    SceneElem c = *e;
    c.tag = old->tag;
    double dw = is_dealt(d, old) ? wl_pphigs_dist_weight(d, &c) -
                                       wl_pphigs_dist_weight(d, old)
                                 : 0;
    if (!scene_db_modify(d->host, sid, pos, &c, err))
        return FALSE;
    c = *hel(d, sid, pos); /* e's vertices may have been the old host's */
    uint64_t m = *mask_at(d, sid, pos);
    for (guint g = 0; g < d->ngp; g++)
        if ((m >> g) & 1) {
            gboolean ok = scene_db_modify(d->gp[g], sid, gp_pos(d, sid, pos, g),
                                          &c, NULL);
            g_assert(ok);
            d->traffic.elements_sent++; /* §3.1: new data to each holder */
            d->traffic.sent_to[g]++;
        }
    if (dw != 0 && m && !is_prim_struct(d, sid))
        add_load(d, sid, (guint)__builtin_ctzll(m), dw);
    refresh_deltas(d); /* an execute's child may change the ODP counts */
    return TRUE;
}

void wl_pphigs_dist_finish(WlPphigsDist *d)
{
    for (guint s = 0; s < d->meta->len; s++) {
        StructMeta *m = meta(d, s);
        if (m->first == NONE)
            continue;
        guint len = scene_db_len(d->host, s);
        guint first = MIN((guint)m->first, len);
        gint last = MIN(m->last, (gint)len - 1);
        m->first = m->last = NONE;
        step2(d, s, first, last);
    }
    refresh_deltas(d);
}

void wl_pphigs_dist_post(WlPphigsDist *d, guint sid)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    scene_db_post(d->host, sid);
    for (guint g = 0; g < d->ngp; g++)
        scene_db_post(d->gp[g], sid);
}

void wl_pphigs_dist_unpost(WlPphigsDist *d, guint sid)
{
    scene_db_unpost(d->host, sid);
    for (guint g = 0; g < d->ngp; g++)
        scene_db_unpost(d->gp[g], sid);
}

gint wl_pphigs_dist_owner(const WlPphigsDist *d, guint sid, guint pos)
{
    const SceneElem *e = hel(d, sid, pos);
    uint64_t m = *mask_at(d, sid, pos);
    if (!is_dealt(d, e) || is_prim_struct(d, sid) || !m)
        return NONE;
    return __builtin_ctzll(m);
}

gboolean wl_pphigs_dist_move(WlPphigsDist *d, guint sid, guint pos, guint to)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    gint from = wl_pphigs_dist_owner(d, sid, pos);
    if (from == NONE || (guint)from == to)
        return FALSE;
    double w = wl_pphigs_dist_weight(d, hel(d, sid, pos));
    gp_drop(d, sid, pos, (guint)from);
    add_load(d, sid, (guint)from, -w);
    add_load(d, sid, to, w);
    AttrState s;
    state_init(&s);
    if (d->algo == WL_PPHIGS_COMPLEX)
        backward(d, sid, pos, &s);
    ensure(d, sid, &s, to);
    gp_put(d, sid, pos, to);
    state_clear(&s);
    refresh_deltas(d);
    return TRUE;
}

/* ---- nominal loads (§5.1) --------------------------------------------- */

static double flat_weight(const WlPphigsDist *d, const SceneElem *e)
{
    double w = d->w.w[e->kind];
    return scene_elem_is_prim(e->kind) ? w + d->w.w_vertex * e->nverts : w;
}

void wl_pphigs_dist_loads(const WlPphigsDist *d, double *out)
{
    for (guint g = 0; g < d->ngp; g++) {
        GArray *mx = scene_db_maxset(d->gp[g]);
        out[g] = 0;
        for (guint k = 0; k < mx->len; k++) {
            guint sid = g_array_index(mx, SceneMaxNode, k).sid;
            for (guint i = 0; i < scene_db_len(d->gp[g], sid); i++)
                out[g] += flat_weight(d, scene_db_elem(d->gp[g], sid, i));
        }
        g_array_unref(mx);
    }
}
