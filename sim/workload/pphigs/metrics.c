/* metrics.c — traversal cost of display lists and seed 001's metrics
 * (see metrics.h).  One walk per structure instance: O(max-set size).
 * Seed 001 §2.3.4 (nominal weights), §5.2 (invalidated weights), §6.
 */
#include "sim/workload/pphigs/metrics.h"
#include "sim/scene/pphigs_db.h"

typedef struct {
    const WlPphigsCosts *c;
    Mat4 vp;
    double us;
} Walk;

double wl_pphigs_elem_us(const WlPphigsCosts *c, const SceneElem *e)
{
    switch (e->kind) {
    case SCENE_EL_COLOR:
        return c->color;
    case SCENE_EL_MATRIX:
        return e->mode == SCENE_MAT_REPLACE ? c->matrix : c->concat;
    case SCENE_EL_EXECUTE:
        return c->execute;
    default:
        return c->poly + c->vertex * e->nverts;
    }
}

static void prim_fn(const ScenePrimInst *pi, void *ud)
{
    Walk *w = ud;
    double t = wl_pphigs_elem_us(w->c, pi->el);
    if (scene_pphigs_prim_offscreen(mat4_mul(w->vp, pi->matrix), pi->el))
        t *= w->c->offscreen;
    w->us += t;
}

double wl_pphigs_traversal_us(const SceneDb *db, Mat4 vp,
                              const WlPphigsCosts *c)
{
    Walk w = {c, vp, 0};
    scene_db_traverse(db, prim_fn, &w); /* primitives, with visibility */
    GArray *mx = scene_db_maxset(db);   /* attributes and executes */
    for (guint k = 0; k < mx->len; k++) {
        guint sid = g_array_index(mx, SceneMaxNode, k).sid;
        for (guint i = 0; i < scene_db_len(db, sid); i++) {
            const SceneElem *e = scene_db_elem(db, sid, i);
            if (!scene_elem_is_prim(e->kind))
                w.us += wl_pphigs_elem_us(c, e);
        }
    }
    g_array_unref(mx);
    return w.us;
}

void wl_pphigs_metrics(const WlPphigsDist *d, Mat4 vp,
                       const WlPphigsCosts *c, double *gp_us,
                       WlPphigsMetrics *m)
{
    guint n = wl_pphigs_dist_ngp(d);
    m->t1 = wl_pphigs_traversal_us(wl_pphigs_dist_host(d), vp, c);
    m->sum = m->max = 0;
    for (guint g = 0; g < n; g++) {
        gp_us[g] = wl_pphigs_traversal_us(wl_pphigs_dist_gp(d, g), vp, c);
        m->sum += gp_us[g];
        m->max = MAX(m->max, gp_us[g]);
    }
    m->efficiency = m->sum > 0 ? m->t1 / m->sum : 0;
    m->utilisation = m->max > 0 ? m->sum / (n * m->max) : 0;
    m->speedup = n * m->efficiency * m->utilisation;
}

void wl_pphigs_weights_from_costs(const WlPphigsCosts *c, double cluster,
                                  WlPphigsWeights *w)
{
    for (int k = 0; k < SCENE_EL_NKINDS; k++)
        w->w[k] = scene_elem_is_prim((SceneElemKind)k) ? c->poly : 0;
    w->w[SCENE_EL_COLOR] = c->color;
    w->w[SCENE_EL_MATRIX] = c->matrix;
    w->w[SCENE_EL_EXECUTE] = c->execute;
    w->w_vertex = c->vertex;
    w->cluster = cluster;
}
