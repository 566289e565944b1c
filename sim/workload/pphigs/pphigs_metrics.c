/* pphigs_metrics.c — traversal cost of display lists and seed 001's metrics
 * (see metrics.h).  One walk per structure instance: O(max-set size).
 * Sums are exact SimTime picoseconds.
 * Seed 001 §2.3.4 (nominal weights), §5.2 (invalidated weights), §6.
 */
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/scene/pphigs_db.h"

typedef struct {
    const WlPphigsCosts *c;
    Mat4 vp;
    SimTime t;
} Walk;

SimTime wl_pphigs_elem_cost(const WlPphigsCosts *c, const SceneElem *e)
{
    if (scene_elem_is_color(e->kind))
        return c->color;
    switch (e->kind) {
    case SCENE_EL_MATRIX:
        return e->mode == SCENE_MAT_REPLACE ? c->matrix : c->concat;
    case SCENE_EL_EXECUTE:
        return c->execute;
    default:
        return sim_time_add_sat(e->kind == SCENE_EL_LINE     ? c->line
                                : e->kind == SCENE_EL_SPHERE ? c->sphere
                                                             : c->poly,
                                sim_time_mul_sat(c->vertex, e->nverts));
    }
}

void wl_pphigs_elem_ops(const SceneElem *e, MachOps *o)
{
    if (scene_elem_is_color(e->kind)) {
        mach_ops_add(o, "color", 1);
        return;
    }
    switch (e->kind) {
    case SCENE_EL_MATRIX:
        mach_ops_add(o,
                     e->mode == SCENE_MAT_REPLACE ? "matrix_replace"
                                                  : "matrix_concat",
                     1);
        return;
    case SCENE_EL_EXECUTE:
        mach_ops_add(o, "execute", 1);
        return;
    default:
        mach_ops_add(o,
                     e->kind == SCENE_EL_LINE     ? "line"
                     : e->kind == SCENE_EL_SPHERE ? "sphere"
                                                  : "polygon",
                     1);
        mach_ops_add(o, "vertex", e->nverts);
    }
}

void wl_pphigs_prim_ops(const SceneElem *e, gboolean offscreen, MachOps *o)
{
    if (offscreen)
        mach_ops_add(o, "reject_vertex", e->nverts);
    else
        wl_pphigs_elem_ops(e, o);
}

/* Calls fn(e, ud) on every attribute and execute of every structure
 * instance of db's max-set, in traversal order: the one walk behind
 * wl_pphigs_nonprim_ops() and wl_pphigs_nonprim_cost(). */
static void nonprim_each(const SceneDb *db,
                         void (*fn)(const SceneElem *e, void *ud), void *ud)
{
    GArray *mx = scene_db_maxset(db);
    for (guint k = 0; k < mx->len; k++) {
        guint sid = g_array_index(mx, SceneMaxNode, k).sid;
        for (guint i = 0; i < scene_db_len(db, sid); i++) {
            const SceneElem *e = scene_db_elem(db, sid, i);
            if (!scene_elem_is_prim(e->kind))
                fn(e, ud);
        }
    }
    g_array_unref(mx);
}

static void nonprim_op(const SceneElem *e, void *ud)
{
    wl_pphigs_elem_ops(e, ud);
}

void wl_pphigs_nonprim_ops(const SceneDb *db, MachOps *o)
{
    nonprim_each(db, nonprim_op, o);
}

SimTime wl_pphigs_prim_cost(const WlPphigsCosts *c, const SceneElem *e,
                            gboolean offscreen)
{
    return offscreen ? sim_time_mul_sat(c->reject_vertex, e->nverts)
                     : wl_pphigs_elem_cost(c, e);
}

static void prim_fn(const ScenePrimInst *pi, void *ud)
{
    Walk *w = ud;
    gboolean off =
        scene_pphigs_prim_offscreen(mat4_mul(w->vp, pi->matrix), pi->el);
    w->t += wl_pphigs_prim_cost(w->c, pi->el, off);
}

static void nonprim_add(const SceneElem *e, void *ud)
{
    Walk *w = ud;
    w->t += wl_pphigs_elem_cost(w->c, e);
}

SimTime wl_pphigs_nonprim_cost(const SceneDb *db, const WlPphigsCosts *c)
{
    Walk w = {.c = c, .t = 0};
    nonprim_each(db, nonprim_add, &w);
    return w.t;
}

SimTime wl_pphigs_traversal_cost(const SceneDb *db, Mat4 vp,
                                 const WlPphigsCosts *c)
{
    Walk w = {c, vp, 0};
    scene_db_traverse(db, prim_fn, &w); /* primitives, with visibility */
    return w.t + wl_pphigs_nonprim_cost(db, c);
}

void wl_pphigs_metrics_from(double t1, const double *gp_us, guint ngp,
                            WlPphigsMetrics *m)
{
    m->t1 = t1;
    m->sum = m->max = 0;
    for (guint g = 0; g < ngp; g++) {
        m->sum += gp_us[g];
        m->max = MAX(m->max, gp_us[g]);
    }
    m->efficiency = m->sum > 0 ? m->t1 / m->sum : 0;
    m->utilisation = m->max > 0 ? m->sum / (ngp * m->max) : 0;
    m->speedup = ngp * m->efficiency * m->utilisation;
}

void wl_pphigs_metrics(const WlPphigsDist *d, Mat4 vp, const WlPphigsCosts *c,
                       double *gp_us, WlPphigsMetrics *m)
{
    guint n = wl_pphigs_dist_ngp(d);
    SimTime t1 = wl_pphigs_traversal_cost(wl_pphigs_dist_host(d), vp, c);
    for (guint g = 0; g < n; g++)
        gp_us[g] = sim_time_to_us(
            wl_pphigs_traversal_cost(wl_pphigs_dist_gp(d, g), vp, c));
    wl_pphigs_metrics_from(sim_time_to_us(t1), gp_us, n, m);
}

void wl_pphigs_weights_from_costs(const WlPphigsCosts *c, double cluster,
                                  WlPphigsWeights *w)
{
    for (int k = 0; k < SCENE_EL_NKINDS; k++)
        w->w[k] =
            scene_elem_is_prim((SceneElemKind)k) ? sim_time_to_us(c->poly) : 0;
    w->w[SCENE_EL_COLOR] = sim_time_to_us(c->color);
    w->w[SCENE_EL_LINE_COLOR] = sim_time_to_us(c->color);
    w->w[SCENE_EL_SPHERE_COLOR] = sim_time_to_us(c->color);
    w->w[SCENE_EL_LINE] = sim_time_to_us(c->line);
    w->w[SCENE_EL_SPHERE] = sim_time_to_us(c->sphere);
    w->w[SCENE_EL_MATRIX] = sim_time_to_us(c->matrix);
    w->w[SCENE_EL_EXECUTE] = sim_time_to_us(c->execute);
    w->w_vertex = sim_time_to_us(c->vertex);
    w->cluster = cluster;
    w->strip_split = 0; /* the caller's choice (frame.yaml strip_split) */
    w->attr_cache = 0;  /* the caller's (attr_cache_every) */
    w->inherit = WL_PPHIGS_INHERIT_SKELETON; /* the caller's (inheritance) */
    w->attr_send = WL_PPHIGS_SEND_ALL; /* the caller's (attribute_send) */
}
