/* pphigs_rebalance.c — display-list rebalancing of seed 001 §5 (see
 * rebalance.h).  Candidates are the dealt elements of the host list,
 * grouped by owning GP, with their nominal weight (times the number of
 * instances of their structure) and their actual weight under the view
 * (from a host traversal, §5.2).  Invariant: a candidate sits in the list
 * of the GP that owns it, before and after every move.
 */
#include "sim/workload/pphigs/pphigs_rebalance.h"
#include "sim/core/rng.h"
#include "sim/scene/pphigs_db.h"
#include <string.h>

#define ON_SCREEN 0.999 /* actual / nominal at or above: not invalidated */

struct WlPphigsRebal {
    WlPphigsRebalParams p;
    SimRng rng;
    guint over;
    uint64_t total;
};

typedef struct {
    guint sid, pos;
    double nominal, actual;
} Cand;

typedef struct {
    WlPphigsDist *d;
    guint ngp;
    GArray **by_gp; /* Cand, per GP */
    double *est;    /* load estimate per GP, updated by moves */
    guint *off;     /* per structure: index of its first element */
    double *actual; /* per host element: actual cost, all instances */
    guint *inst;    /* per structure: max-set instances */
} Pool;

WlPphigsRebal *wl_pphigs_rebal_new(const WlPphigsRebalParams *p)
{
    g_assert(p->threshold > 0 && p->frames >= 1 && p->fraction > 0);
    WlPphigsRebal *rb = g_new0(WlPphigsRebal, 1);
    rb->p = *p;
    sim_rng_init(&rb->rng, p->seed, 0x5eba1);
    return rb;
}

void wl_pphigs_rebal_free(WlPphigsRebal *rb)
{
    g_free(rb);
}

const char *wl_pphigs_rebal_cause_name(WlPphigsRebalCause c)
{
    static const char *const names[] = {"none", "imperfect", "invalidated"};
    return names[c];
}

double wl_pphigs_imbalance(const double *v, guint n)
{
    double max = 0, sum = 0;
    for (guint i = 0; i < n; i++) {
        max = MAX(max, v[i]);
        sum += v[i];
    }
    return max > 0 ? (max - sum / n) / max : 0;
}

static void argmax_min(const double *v, guint n, guint *hi, guint *lo)
{
    *hi = *lo = 0;
    for (guint i = 1; i < n; i++) {
        if (v[i] > v[*hi])
            *hi = i;
        if (v[i] < v[*lo])
            *lo = i;
    }
}

/* ---- the candidate pool ----------------------------------------------- */

typedef struct {
    Pool *pl;
    const WlPphigsCosts *c;
    Mat4 vp;
} Measure;

static void measure_prim(const ScenePrimInst *pi, void *ud)
{
    Measure *m = ud;
    gboolean off =
        scene_pphigs_prim_offscreen(mat4_mul(m->vp, pi->matrix), pi->el);
    m->pl->actual[m->pl->off[pi->sid] + pi->pos] +=
        sim_time_to_us(wl_pphigs_prim_cost(m->c, pi->el, off));
}

static void pool_index(Pool *pl, const SceneDb *h)
{
    guint ns = scene_db_struct_count(h), total = 0;
    pl->off = g_new0(guint, ns + 1);
    pl->inst = g_new0(guint, ns + 1);
    for (guint s = 0; s < ns; s++) {
        pl->off[s] = total;
        total += scene_db_len(h, s);
    }
    pl->actual = g_new0(double, MAX(total, 1));
    GArray *mx = scene_db_maxset(h);
    for (guint k = 0; k < mx->len; k++)
        pl->inst[g_array_index(mx, SceneMaxNode, k).sid]++;
    g_array_unref(mx);
}

static void pool_init(Pool *pl, WlPphigsDist *d, Mat4 vp,
                      const WlPphigsCosts *c)
{
    const SceneDb *h = wl_pphigs_dist_host(d);
    pl->d = d;
    pl->ngp = wl_pphigs_dist_ngp(d);
    pool_index(pl, h);
    Measure m = {pl, c, vp};
    scene_db_traverse(h, measure_prim, &m);
    pl->est = g_new0(double, pl->ngp);
    pl->by_gp = g_new0(GArray *, pl->ngp);
    for (guint g = 0; g < pl->ngp; g++)
        pl->by_gp[g] = g_array_new(FALSE, FALSE, sizeof(Cand));
    for (guint s = 0; s < scene_db_struct_count(h); s++)
        for (guint i = 0; i < scene_db_len(h, s); i++) {
            gint g = wl_pphigs_dist_owner(d, s, i);
            if (g < 0 || !pl->inst[s])
                continue;
            const SceneElem *e = scene_db_elem(h, s, i);
            Cand cd = {s, i, pl->inst[s] * wl_pphigs_dist_weight(d, e), 0};
            cd.actual = scene_elem_is_prim(e->kind)
                            ? pl->actual[pl->off[s] + i]
                            : cd.nominal; /* not measured: assume valid */
            g_array_append_val(pl->by_gp[g], cd);
        }
}

static void pool_clear(Pool *pl)
{
    for (guint g = 0; g < pl->ngp; g++)
        g_array_unref(pl->by_gp[g]);
    g_free(pl->by_gp);
    g_free(pl->est);
    g_free(pl->off);
    g_free(pl->actual);
    g_free(pl->inst);
}

/* Moves candidate i of GP `from` to GP `to`, in the pool and in d. */
static void pool_move(Pool *pl, guint from, guint i, guint to)
{
    Cand cd = g_array_index(pl->by_gp[from], Cand, i);
    gboolean ok = wl_pphigs_dist_move(pl->d, cd.sid, cd.pos, to);
    g_assert(ok);
    g_array_remove_index_fast(pl->by_gp[from], i);
    g_array_append_val(pl->by_gp[to], cd);
}

/* ---- §5.1 imperfect distribution -------------------------------------- */

static gint pick_lighter(WlPphigsRebal *rb, GArray *a, double gap)
{
    if (!a->len)
        return -1;
    guint start = (guint)sim_rng_below(&rb->rng, a->len);
    for (guint k = 0; k < a->len; k++) {
        guint i = (start + k) % a->len;
        if (g_array_index(a, Cand, i).nominal < gap)
            return (gint)i;
    }
    return -1;
}

static guint fix_imperfect(WlPphigsRebal *rb, Pool *pl, double budget)
{
    wl_pphigs_dist_loads(pl->d, pl->est);
    guint moves = 0;
    double moved = 0;
    while (moves < rb->p.max_moves && (moves == 0 || moved < budget)) {
        guint h, l;
        argmax_min(pl->est, pl->ngp, &h, &l);
        gint i = pick_lighter(rb, pl->by_gp[h], pl->est[h] - pl->est[l]);
        if (i < 0)
            break;
        double w = g_array_index(pl->by_gp[h], Cand, i).nominal;
        pool_move(pl, h, (guint)i, l);
        pl->est[h] -= w;
        pl->est[l] += w;
        moved += w;
        moves++;
    }
    return moves;
}

/* ---- §5.2 invalidated weights ----------------------------------------- */

static gint find_partner(GArray *a, const Cand *x, double gap)
{
    for (guint i = 0; i < a->len; i++) {
        const Cand *y = &g_array_index(a, Cand, i);
        double gain = x->actual - y->actual;
        if (fabs(y->nominal - x->nominal) <= 1e-9 * x->nominal &&
            y->actual < ON_SCREEN * y->nominal && gain > 0 && gain < gap)
            return (gint)i;
    }
    return -1;
}

/* One exchange between h and l; returns the gain, 0 if none found. */
static double exchange(WlPphigsRebal *rb, Pool *pl, guint h, guint l)
{
    GArray *a = pl->by_gp[h];
    double gap = pl->est[h] - pl->est[l];
    guint start = a->len ? (guint)sim_rng_below(&rb->rng, a->len) : 0;
    for (guint k = 0; k < a->len; k++) {
        guint i = (start + k) % a->len;
        Cand x = g_array_index(a, Cand, i);
        if (x.actual < ON_SCREEN * x.nominal)
            continue;
        gint j = find_partner(pl->by_gp[l], &x, gap);
        if (j < 0)
            continue;
        double gain = x.actual - g_array_index(pl->by_gp[l], Cand, j).actual;
        pool_move(pl, l, (guint)j, h); /* first: i stays valid */
        pool_move(pl, h, i, l);
        pl->est[h] -= gain;
        pl->est[l] += gain;
        return gain;
    }
    return 0;
}

static guint fix_invalidated(WlPphigsRebal *rb, Pool *pl, const double *gp_us,
                             double budget)
{
    memcpy(pl->est, gp_us, pl->ngp * sizeof *pl->est);
    guint moves = 0;
    double moved = 0;
    while (moves + 2 <= rb->p.max_moves && (moves == 0 || moved < budget)) {
        guint h, l;
        argmax_min(pl->est, pl->ngp, &h, &l);
        double gain = exchange(rb, pl, h, l);
        if (gain <= 0)
            break;
        moved += gain;
        moves += 2;
    }
    return moves;
}

/* ---- per frame -------------------------------------------------------- */

void wl_pphigs_rebal_frame(WlPphigsRebal *rb, WlPphigsDist *d, Mat4 vp,
                           const WlPphigsCosts *c, const double *gp_us,
                           WlPphigsRebalStep *out)
{
    guint n = wl_pphigs_dist_ngp(d);
    double *nom = g_new0(double, n);
    wl_pphigs_dist_loads(d, nom);
    out->imbalance = wl_pphigs_imbalance(gp_us, n);
    out->nominal_imbalance = wl_pphigs_imbalance(nom, n);
    g_free(nom);
    rb->over = out->imbalance > rb->p.threshold ? rb->over + 1 : 0;
    out->over = rb->over;
    out->cause = WL_PPHIGS_REBAL_NONE;
    out->moves = 0;
    if (rb->over >= rb->p.frames) {
        double max = 0, sum = 0;
        for (guint g = 0; g < n; g++) {
            max = MAX(max, gp_us[g]);
            sum += gp_us[g];
        }
        double budget = rb->p.fraction * (max - sum / n);
        Pool pl;
        pool_init(&pl, d, vp, c);
        if (out->nominal_imbalance > rb->p.threshold) {
            out->cause = WL_PPHIGS_REBAL_IMPERFECT;
            out->moves = fix_imperfect(rb, &pl, budget);
        } else {
            out->cause = WL_PPHIGS_REBAL_INVALIDATED;
            out->moves = fix_invalidated(rb, &pl, gp_us, budget);
        }
        pool_clear(&pl);
    }
    rb->total += out->moves;
    out->total_moves = rb->total;
}
