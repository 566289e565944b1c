/* ellsworth90.c — seed 001's table from the simulator (see
 * ellsworth90.h).  Each cell is a fresh distribution of a generated
 * database followed by one traversal per GP under the database's
 * standard view; nothing is read from the published table here.
 * Cost: 4 distributions per database, O(n * P) each.
 */
#include "sim/workload/pphigs/ellsworth90.h"
#include "sim/app/reproduce.h"
#include <string.h>

static const guint gp_counts[] = {4, 16};

double wl_pphigs_cluster_factor(double cluster_scale, guint ngp)
{
    return MAX(1.0, cluster_scale / ngp);
}

/* Per-GP traverse times of one event-driven frame (frame.h). */
static void frame_gp_us(const WlPphigsDist *d, Mat4 vp,
                        const WlPphigsHw *hw, double *us)
{
    guint n = wl_pphigs_dist_ngp(d);
    SimEngine *eng = sim_engine_new(1);
    NetTopo *t = net_ring_new(wl_pphigs_frame_stations(n,
                                                       hw->frame.renderers));
    NetNet *net = net_new(eng, t, &hw->net, hw->fidelity);
    WlPphigsFrame *f = wl_pphigs_frame_new(eng, net, n, &hw->frame);
    WlPphigsFrameStats st;
    gboolean ok = wl_pphigs_frame_run(f, d, vp, &st, NULL);
    g_assert(ok); /* no overflow possible at these sizes */
    memcpy(us, st.gp_traverse_us, n * sizeof *us);
    wl_pphigs_frame_free(f);
    net_free(net);
    net_topo_free(t);
    sim_engine_free(eng);
}

static WlPphigsDist *distribute(const ScenePphigsDb *db, guint ngp,
                                WlPphigsAlgo a, const WlPphigsCosts *c,
                                double cluster_scale)
{
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(
        c, wl_pphigs_cluster_factor(cluster_scale, ngp), &w);
    return wl_pphigs_dist_new(db->db, ngp, a, &w);
}

/* The metrics of §6 from event-driven frames: T1 is a one-GP frame. */
static void frame_metrics(const ScenePphigsDb *db, const WlPphigsDist *d,
                          const WlPphigsHw *hw, double cs,
                          WlPphigsMetrics *m)
{
    Mat4 vp = scene_camera_view_proj(&db->camera);
    guint n = wl_pphigs_dist_ngp(d);
    WlPphigsDist *one = distribute(db, 1, WL_PPHIGS_SIMPLE, &hw->costs, cs);
    frame_gp_us(one, vp, hw, &m->t1);
    wl_pphigs_dist_free(one);
    double *us = g_new(double, n);
    frame_gp_us(d, vp, hw, us);
    m->sum = m->max = 0;
    for (guint g = 0; g < n; g++) {
        m->sum += us[g];
        m->max = MAX(m->max, us[g]);
    }
    g_free(us);
    m->efficiency = m->sum > 0 ? m->t1 / m->sum : 0;
    m->utilisation = m->max > 0 ? m->sum / (n * m->max) : 0;
    m->speedup = n * m->efficiency * m->utilisation;
}

static void run_algo(const ScenePphigsDb *db, guint ngp, WlPphigsAlgo a,
                     const WlPphigsCosts *c, double cluster_scale,
                     const WlPphigsHw *hw, WlPphigsMetrics *m)
{
    WlPphigsDist *d = distribute(db, ngp, a, c, cluster_scale);
    if (hw) {
        frame_metrics(db, d, hw, cluster_scale, m);
    } else {
        double *us = g_new(double, ngp);
        wl_pphigs_metrics(d, scene_camera_view_proj(&db->camera), c, us, m);
        g_free(us);
    }
    wl_pphigs_dist_free(d);
}

void wl_pphigs_run_db(const ScenePphigsDb *db, guint ngp,
                      const WlPphigsCosts *c, double cluster_scale,
                      const WlPphigsHw *hw, WlPphigsMetrics *simple,
                      WlPphigsMetrics *complex)
{
    run_algo(db, ngp, WL_PPHIGS_SIMPLE, c, cluster_scale, hw, simple);
    run_algo(db, ngp, WL_PPHIGS_COMPLEX, c, cluster_scale, hw, complex);
}

static void add(GPtrArray *rows, const char *table, const char *row,
                const char *col, double v)
{
    g_ptr_array_add(rows, rp_row_new(table, row, col, v, NULL));
}

static void db_rows(const ScenePphigsDb *db, const char *row,
                    GPtrArray *rows)
{
    SceneDbStats st;
    scene_db_stats(db->db, &st);
    add(rows, "db", row, "depth", st.depth);
    add(rows, "db", row, "structures", st.structures);
    add(rows, "db", row, "polys_per_structure",
        (double)st.primitives / st.structures);
    add(rows, "db", row, "poly_attr_ratio",
        (double)st.primitives / (double)MAX(st.attributes, 1));
    add(rows, "db", row, "offscreen_pct",
        100 * scene_pphigs_offscreen_share(
                  db->db, scene_camera_view_proj(&db->camera)));
}

static void cell_rows(const ScenePphigsDb *db, const char *row,
                      const WlPphigsCosts *c, double cs,
                      const WlPphigsHw *hw, GPtrArray *rows)
{
    for (guint k = 0; k < G_N_ELEMENTS(gp_counts); k++) {
        WlPphigsMetrics s, x;
        guint p = gp_counts[k];
        wl_pphigs_run_db(db, p, c, cs, hw, &s, &x);
        char col[32];
        g_snprintf(col, sizeof col, "simple_eff_%u", p);
        add(rows, "1", row, col, 100 * s.efficiency);
        g_snprintf(col, sizeof col, "complex_eff_%u", p);
        add(rows, "1", row, col, 100 * x.efficiency);
        g_snprintf(col, sizeof col, "util_%u", p);
        add(rows, "1", row, col, 100 * x.utilisation);
        g_snprintf(col, sizeof col, "speedup_%u", p);
        add(rows, "1", row, col, x.speedup);
    }
}

gboolean wl_pphigs_table1(const ScenePphigsSpec *specs, guint n,
                          const WlPphigsCosts *c, double cluster_scale,
                          const WlPphigsHw *hw, GPtrArray *rows,
                          GError **err)
{
    for (guint i = 0; i < n; i++) {
        ScenePphigsDb db;
        if (!scene_pphigs_generate(&specs[i], &db, err))
            return FALSE;
        const char *row = scene_pphigs_kind_name(specs[i].kind);
        cell_rows(&db, row, c, cluster_scale, hw, rows);
        db_rows(&db, row, rows);
        scene_pphigs_db_clear(&db);
    }
    return TRUE;
}
