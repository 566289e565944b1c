/* rp_speed.c — speed against error across network fidelities.
 *
 * The reference is the last pass (packet level).  Cells are matched by
 * (table, row, column) with rp_table_find, O(cells) each, so a pass costs
 * O(cells^2): a paper has at most a few hundred cells.
 */
#include "sim/reproduce/rp_speed.h"
#include "sim/output/json.h"
#include "sim/output/plot.h"
#include <math.h>

static const RpTable *ref_of(const GPtrArray *passes)
{
    g_assert(passes->len > 0);
    return g_ptr_array_index(passes, passes->len - 1);
}

double rp_speed_vs_ref(const RpJoined *j, const RpTable *ref)
{
    const RpJoined *r = rp_table_find(ref, j->table, j->row, j->column);
    if (!r || !isfinite(r->sim) || !isfinite(j->sim) || r->sim == 0.0)
        return NAN;
    return (j->sim - r->sim) / r->sim;
}

double rp_speed_mean_vs_ref(const RpTable *t, const RpTable *ref)
{
    double sum = 0.0;
    guint n = 0;
    for (guint i = 0; i < t->cells->len; i++) {
        double e = rp_speed_vs_ref(g_ptr_array_index(t->cells, i), ref);
        if (isfinite(e)) {
            sum += fabs(e);
            n++;
        }
    }
    return n ? sum / n : NAN;
}

static void pct(GString *o, double x)
{
    if (isfinite(x))
        g_string_append_printf(o, "%9.1f%%", 100.0 * x);
    else
        g_string_append_printf(o, "%10s", "-");
}

void rp_speed_summary(const GPtrArray *passes, GString *out)
{
    const RpTable *ref = ref_of(passes);
    g_string_append_printf(out,
                           "%s: speed against error (reference: %s)\n"
                           "fidelity      wall_s  compared  "
                           "vs paper     worst  vs %s\n",
                           ref->paper, ref->fidelity, ref->fidelity);
    for (guint p = 0; p < passes->len; p++) {
        const RpTable *t = g_ptr_array_index(passes, p);
        g_string_append_printf(out, "%-10s %9.3f  %8u ", t->fidelity, t->wall_s,
                               t->compared);
        pct(out, t->mean_abs);
        pct(out, t->worst_abs);
        pct(out, rp_speed_mean_vs_ref(t, ref));
        g_string_append_c(out, '\n');
    }
}

void rp_speed_text(const GPtrArray *passes, GString *out)
{
    for (guint p = 0; p < passes->len; p++) {
        rp_table_text(g_ptr_array_index(passes, p), out);
        g_string_append_c(out, '\n');
    }
    rp_speed_summary(passes, out);
}

void rp_speed_csv(const GPtrArray *passes, gboolean header, GString *out)
{
    const RpTable *ref = ref_of(passes);
    char buf[32];
    for (guint p = 0; p < passes->len; p++) {
        const RpTable *t = g_ptr_array_index(passes, p);
        SimProvenance pv = rp_table_provenance(t);
        prov_comment_lines(out, &pv);
        if (header && p == 0) {
            rp_table_csv_head(t, out);
            g_string_append(out, ",fidelity,wall_s,rel_error_vs_packet\n");
        }
        GString *one = g_string_new(NULL);
        rp_table_csv_rows(t, one);
        char **lines = g_strsplit(one->str, "\n", -1);
        for (guint i = 0; i < t->cells->len; i++) {
            double e = rp_speed_vs_ref(g_ptr_array_index(t->cells, i), ref);
            g_string_append_printf(out, "%s,%s,", lines[i], t->fidelity);
            g_string_append_printf(out, "%s,", js_fmt_num(buf, t->wall_s));
            g_string_append_printf(out, "%s\n", js_fmt_num(buf, e));
        }
        g_strfreev(lines);
        g_string_free(one, TRUE);
    }
}

void rp_speed_json(const GPtrArray *passes, GString *out)
{
    const RpTable *ref = ref_of(passes);
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "paper", ref->paper);
    js_set_str(b, "reference", ref->fidelity);
    json_builder_set_member_name(b, "passes");
    json_builder_begin_array(b);
    for (guint p = 0; p < passes->len; p++) {
        const RpTable *t = g_ptr_array_index(passes, p);
        json_builder_begin_object(b);
        js_set_num(b, "mean_abs_vs_reference", rp_speed_mean_vs_ref(t, ref));
        json_builder_set_member_name(b, "table");
        json_builder_add_value(b, rp_table_node(t));
        json_builder_end_object(b);
    }
    json_builder_end_array(b);
    json_builder_end_object(b);
    char *text = js_finish(b, FALSE);
    g_string_append(out, text);
    g_free(text);
}

static DataTable *speed_table(const GPtrArray *passes)
{
    static const char *const cols[] = {"fidelity", "wall_s", "mean_abs_error",
                                       "against", "point", NULL};
    DataTable *d = dt_new_named(cols);
    const RpTable *ref = ref_of(passes);
    for (guint p = 0; p < passes->len; p++) {
        const RpTable *t = g_ptr_array_index(passes, p);
        char w[32], e1[32], e2[32];
        /* the clock ticks in microseconds: keep x > 0 on the log axis */
        js_fmt_num(w, MAX(t->wall_s, 1e-6));
        /* each point its own series, so the legend names it */
        char *p1 = g_strdup_printf("%s against the paper", t->fidelity);
        char *p2 = g_strdup_printf("%s against %s", t->fidelity,
                                   ref->fidelity);
        char *r1[] = {t->fidelity, w, (char *)js_fmt_num(e1, t->mean_abs),
                      "paper", p1};
        char *r2[] = {t->fidelity, w,
                      (char *)js_fmt_num(e2, rp_speed_mean_vs_ref(t, ref)),
                      ref->fidelity, p2};
        dt_add_row(d, r1);
        dt_add_row(d, r2);
        g_free(p1);
        g_free(p2);
    }
    return d;
}

gboolean rp_speed_chart(const GPtrArray *passes, const char *dir, GError **err)
{
    const RpTable *ref = ref_of(passes);
    char *name = g_strdup_printf("%s-speed", ref->paper);
    PlotSpec *p = plot_spec_new(name, "wall_s", "mean_abs_error");
    p->series = g_strdup("point");
    p->logx = TRUE;
    p->title = g_strdup_printf("%s: mean |relative error| against wall "
                               "time (analytic, flow, packet)",
                               ref->paper);
    p->xlabel = g_strdup("wall time of the reproduction [s]");
    p->ylabel = g_strdup("mean |relative error|");
    DataTable *d = speed_table(passes);
    gboolean ok = plot_render(p, d, dir, err);
    dt_free(d);
    plot_spec_free(p);
    g_free(name);
    return ok;
}
