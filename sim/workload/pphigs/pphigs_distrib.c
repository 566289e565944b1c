/* pphigs_distrib.c — distribute-by-primitive of a hierarchical display list
 * (see pphigs_distrib.h): bookkeeping of the GP copies, dealing (§2.2-2.3),
 * the forward walk of the initial distribution and of step 2, ODP deltas
 * (§4), strip splitting (§2.3.2), lifecycle, moves and nominal loads.
 * Editing is in pphigs_edit.c, the backward scan in pphigs_attrstate.c,
 * distribute-by-structure in pphigs_bystruct.c (pphigs_dist_internal.h).
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
#include "sim/workload/pphigs/pphigs_dist_internal.h"
#include <string.h>

double wl_pphigs_dist_weight(const WlPphigsDist *d, const SceneElem *e)
{
    double w = d->w.w[e->kind];
    if (scene_elem_is_prim(e->kind))
        return w + d->w.w_vertex * e->nverts;
    if (e->kind == SCENE_EL_EXECUTE && dist_is_prim_struct(d, e->child))
        for (guint i = 0; i < scene_db_len(d->host, e->child); i++)
            w += wl_pphigs_dist_weight(d, dist_hel(d, e->child, i));
    return w;
}

/* ---- GP copies -------------------------------------------------------- */

guint wl_pphigs_dist_gp_pos(const WlPphigsDist *d, guint sid, guint pos,
                            guint g)
{
    guint n = 0;
    for (guint i = 0; i < pos; i++)
        n += (*dist_mask_at(d, sid, i) >> g) & 1;
    return n;
}

void wl_pphigs_dist_put(WlPphigsDist *d, guint sid, guint pos, guint g)
{
    uint64_t *m = dist_mask_at(d, sid, pos);
    if ((*m >> g) & 1)
        return;
    gboolean ok =
        scene_db_insert(d->gp[g], sid, wl_pphigs_dist_gp_pos(d, sid, pos, g),
                        dist_hel(d, sid, pos), NULL);
    g_assert(ok);
    *m |= (uint64_t)1 << g;
    d->traffic.elements_sent++;
    d->traffic.attrs_sent += scene_elem_is_attr(dist_hel(d, sid, pos)->kind);
    d->traffic.sent_to[g]++;
}

void wl_pphigs_dist_put_all(WlPphigsDist *d, guint sid, guint pos)
{
    for (guint g = 0; g < d->ngp; g++)
        wl_pphigs_dist_put(d, sid, pos, g);
}

void wl_pphigs_dist_drop(WlPphigsDist *d, guint sid, guint pos, guint g)
{
    uint64_t *m = dist_mask_at(d, sid, pos);
    if (!((*m >> g) & 1))
        return;
    scene_db_delete(d->gp[g], sid, wl_pphigs_dist_gp_pos(d, sid, pos, g));
    *m &= ~((uint64_t)1 << g);
    d->traffic.elements_removed++;
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
guint wl_pphigs_dist_choose(WlPphigsDist *d, guint sid, double w)
{
    StructMeta *m = dist_meta(d, sid);
    double budget = d->algo == WL_PPHIGS_COMPLEX ? d->w.cluster * d->maxw : 0;
    if (m->cur == NONE || m->run + w > budget + 1e-12) {
        m->cur = (gint)least_loaded(d, m);
        m->run = 0;
    }
    m->run += w;
    return (guint)m->cur;
}

void wl_pphigs_dist_add_load(WlPphigsDist *d, guint sid, guint g, double w)
{
    dist_meta(d, sid)->load[g] += w;
    d->gload[g] += w;
}

/* ---- the forward walk (initial distribution, append, step 2) ---------- */

static void simple_elem(WlPphigsDist *d, guint sid, guint i)
{
    const SceneElem *e = dist_hel(d, sid, i);
    uint64_t *m = dist_mask_at(d, sid, i);
    if (!dist_is_dealt(d, e)) {
        wl_pphigs_dist_put_all(d, sid, i);
    } else if (*m == 0) {
        double w = wl_pphigs_dist_weight(d, e);
        guint g = wl_pphigs_dist_choose(d, sid, w);
        wl_pphigs_dist_add_load(d, sid, g, w);
        wl_pphigs_dist_put(d, sid, i, g);
    }
}

/* Deals element i (complex); returns the GPs it checked. */
static uint64_t complex_elem(WlPphigsDist *d, guint sid, guint i, AttrState *s)
{
    const SceneElem *e = dist_hel(d, sid, i);
    uint64_t *m = dist_mask_at(d, sid, i);
    if (scene_elem_is_attr(e->kind)) {
        wl_pphigs_attr_step(s, e, (gint)i);
        if (e->kind == SCENE_EL_MATRIX && e->mode == SCENE_MAT_CONCAT)
            wl_pphigs_attr_ensure_matrices(d, sid, s);
        return 0;
    }
    if (!dist_is_dealt(d, e)) { /* ordinary execute: flush, then to all */
        for (guint g = 0; g < d->ngp; g++)
            wl_pphigs_attr_ensure(d, sid, s, g, NULL);
        wl_pphigs_dist_put_all(d, sid, i);
        return dist_all_mask(d);
    }
    guint g;
    if (*m == 0) {
        double w = wl_pphigs_dist_weight(d, e);
        g = wl_pphigs_dist_choose(d, sid, w);
        wl_pphigs_dist_add_load(d, sid, g, w);
    } else {
        g = (guint)__builtin_ctzll(*m);
    }
    wl_pphigs_attr_ensure(d, sid, s, g, e);
    wl_pphigs_dist_put(d, sid, i, g);
    /* by kind, one primitive brings its GP only its own type's colour:
     * the walk after an edit checks on to an ordinary execute or the end */
    if (d->w.attr_send == WL_PPHIGS_SEND_BY_KIND &&
        e->kind != SCENE_EL_EXECUTE)
        return 0;
    return (uint64_t)1 << g;
}

/* Walks from `from`, past `last` until every GP has been checked. */
void wl_pphigs_dist_forward(WlPphigsDist *d, guint sid, guint from, gint last,
                            AttrState *s)
{
    uint64_t checked = 0;
    guint n = scene_db_len(d->host, sid);
    for (guint i = from; i < n; i++) {
        gboolean plain =
            d->algo == WL_PPHIGS_SIMPLE || dist_is_prim_struct(d, sid);
        if ((gint)i > last && (plain || checked == dist_all_mask(d)))
            break;
        if (dist_is_prim_struct(d, sid))
            wl_pphigs_dist_put_all(d, sid, i);
        else if (d->algo == WL_PPHIGS_SIMPLE)
            simple_elem(d, sid, i);
        else if ((gint)i > last) /* only checks after the region count */
            checked |= complex_elem(d, sid, i, s);
        else
            (void)complex_elem(d, sid, i, s);
    }
}

void wl_pphigs_dist_step2(WlPphigsDist *d, guint sid, guint first, gint last)
{
    AttrState s;
    wl_pphigs_attr_init(&s);
    if (!dist_is_prim_struct(d, sid) && d->algo == WL_PPHIGS_COMPLEX)
        wl_pphigs_attr_backward(d, sid, first, &s);
    wl_pphigs_dist_forward(d, sid, first, last, &s);
    wl_pphigs_attr_clear(&s);
}

/* ---- ODP deltas (§4) -------------------------------------------------- */

static int64_t odp_total(const WlPphigsDist *d, guint sid, int64_t *memo)
{
    if (memo[sid] >= 0)
        return memo[sid];
    int64_t t = 0;
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = dist_hel(d, sid, i);
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
        const SceneElem *e = dist_hel(d, sid, i);
        gboolean odp = e->kind == SCENE_EL_POLYGON2D;
        int64_t adv = odp ? 1
                      : e->kind == SCENE_EL_EXECUTE
                          ? odp_total(d, e->child, memo)
                          : 0;
        uint64_t m = *dist_mask_at(d, sid, i);
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

void wl_pphigs_dist_deltas(WlPphigsDist *d)
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
    wl_pphigs_attr_cache_free(m->cache);
    g_free(m->load);
    g_free(m);
}

static void retag(WlPphigsDist *d)
{
    for (guint s = 0; s < scene_db_struct_count(d->host); s++)
        for (guint i = 0; i < scene_db_len(d->host, s); i++) {
            SceneElem e = *dist_hel(d, s, i);
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
    for (guint s = 0; s < n && algo == WL_PPHIGS_COMPLEX && w->attr_cache; s++)
        if (!dist_is_prim_struct(d, s))
            dist_meta(d, s)->cache = wl_pphigs_attr_cache_new(d, s);
    if (algo == WL_PPHIGS_BY_STRUCTURE && !wl_pphigs_dist_by_structure(d))
        d->algo = WL_PPHIGS_SIMPLE; /* see bystruct_possible() */
    if (d->algo != WL_PPHIGS_BY_STRUCTURE)
        for (guint s = 0; s < n; s++)
            wl_pphigs_dist_step2(d, s, 0, (gint)scene_db_len(d->host, s) - 1);
    wl_pphigs_dist_deltas(d);
    wl_pphigs_dist_by_structure_state(d);
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
    g_free(d->broken);
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

gint wl_pphigs_dist_owner(const WlPphigsDist *d, guint sid, guint pos)
{
    const SceneElem *e = dist_hel(d, sid, pos);
    uint64_t m = *dist_mask_at(d, sid, pos);
    if (!dist_is_dealt(d, e) || dist_is_prim_struct(d, sid) || !m)
        return NONE;
    return __builtin_ctzll(m);
}

gboolean wl_pphigs_dist_move(WlPphigsDist *d, guint sid, guint pos, guint to)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    gint from = wl_pphigs_dist_owner(d, sid, pos);
    if (from == NONE || (guint)from == to)
        return FALSE;
    double w = wl_pphigs_dist_weight(d, dist_hel(d, sid, pos));
    wl_pphigs_dist_drop(d, sid, pos, (guint)from);
    wl_pphigs_dist_add_load(d, sid, (guint)from, -w);
    wl_pphigs_dist_add_load(d, sid, to, w);
    AttrState s;
    wl_pphigs_attr_init(&s);
    if (d->algo == WL_PPHIGS_COMPLEX)
        wl_pphigs_attr_backward(d, sid, pos, &s);
    wl_pphigs_attr_ensure(d, sid, &s, to, dist_hel(d, sid, pos));
    wl_pphigs_dist_put(d, sid, pos, to);
    wl_pphigs_attr_clear(&s);
    wl_pphigs_dist_deltas(d);
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