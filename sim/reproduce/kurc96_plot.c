/* kurc96_plot.c — the charts of `pgsim reproduce kurc96`: Fig. 1
 * (total volume of concurrent communication) and Fig. 2 (load imbalance
 * of RS against HBP) of seed 003, from the simulated points, as gnuplot
 * PNG/SVG through plot_render() (sim/output/plot.h).  (a) charts are
 * against the processor count (2POT, N=400), (b) charts against the
 * scene and resolution (P=16, categorical x).  O(points).
 */
#include "sim/output/plot.h"
#include "sim/reproduce/kurc96.h"
#include <stdio.h>

static const char *const volume_series[4] = {"PAIR-RS", "PAIR-HBP", "AAPC-RS",
                                             "AAPC-HBP"};
static const char *const imbalance_series[2] = {"RS", "HBP"};

void rp_kurc96_figs_clear(RpKurcFigs *f)
{
    for (guint i = 0; i < f->n_a; i++)
        g_free(f->a[i].label);
    for (guint i = 0; i < f->n_b; i++)
        g_free(f->b[i].label);
    f->n_a = f->n_b = 0;
}

/* x of a point: the processor count for (a), the row key minus "b/" for
 * (b); into buf. */
static const char *x_of(const RpKurcPoint *p, gboolean by_procs, char *buf,
                        gsize len)
{
    if (by_procs)
        g_snprintf(buf, len, "%u", p->procs);
    else
        g_snprintf(buf, len, "%s", p->label + 2);
    return buf;
}

/* One table of the volumes (volume TRUE) or the imbalances of points. */
static DataTable *fig_table(const RpKurcPoint *pts, guint n, gboolean by_procs,
                            gboolean volume)
{
    DataTable *t = plot_xy_table_new();
    guint k = volume ? 4 : 2;
    for (guint s = 0; s < k; s++)
        for (guint i = 0; i < n; i++) {
            char x[64];
            x_of(&pts[i], by_procs, x, sizeof x);
            plot_xy_add_label(t, x,
                              volume ? pts[i].volume[s]
                                     : pts[i].imbalance[s],
                              volume ? volume_series[s] : imbalance_series[s]);
        }
    return t;
}

static void chart(const RpKurcPoint *pts, guint n, gboolean by_procs,
                  gboolean volume, const char *name, const char *title,
                  const char *dir)
{
    DataTable *t = fig_table(pts, n, by_procs, volume);
    PlotSpec *p = plot_spec_new(name, "x", "y");
    p->series = g_strdup("series");
    p->logx = by_procs;
    p->title = g_strdup(title);
    p->xlabel = g_strdup(by_procs ? "processors" : "scene / N");
    p->ylabel = g_strdup(volume ? "total volume of concurrent "
                                  "communication [bytes]"
                                : "load imbalance (max - min) / mean");
    GError *err = NULL;
    if (!plot_render(p, t, dir, &err)) {
        g_printerr("kurc96: chart %s not drawn: %s\n", name, err->message);
        g_clear_error(&err);
    }
    plot_spec_free(p);
    dt_free(t);
}

void rp_kurc96_charts(const RpKurcFigs *f, const char *dir,
                      const char *fidelity)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        g_printerr("kurc96: cannot create %s; no charts\n", dir);
        return;
    }
    char *t[4] = {
        g_strdup_printf("Fig. 1(a) 2POT, N=400 (simulated, %s)", fidelity),
        g_strdup_printf("Fig. 1(b) P=16 (simulated, %s)", fidelity),
        g_strdup_printf("Fig. 2(a) AAPC, 2POT, N=400 (simulated, %s)",
                        fidelity),
        g_strdup_printf("Fig. 2(b) AAPC, P=16 (simulated, %s)", fidelity)};
    chart(f->a, f->n_a, TRUE, TRUE, "kurc96-fig1a", t[0], dir);
    chart(f->b, f->n_b, FALSE, TRUE, "kurc96-fig1b", t[1], dir);
    chart(f->a, f->n_a, TRUE, FALSE, "kurc96-fig2a", t[2], dir);
    chart(f->b, f->n_b, FALSE, FALSE, "kurc96-fig2b", t[3], dir);
    for (int i = 0; i < 4; i++)
        g_free(t[i]);
}
