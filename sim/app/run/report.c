/* report.c — text, JSON and CSV renderings of a SimResult (report.h).
 *
 * Each writer walks the result once in a fixed order (run, frames,
 * nodes, communication, metrics, simulator), so output is a pure
 * function of the result.  Simulated times are integer picoseconds
 * printed as exact decimal seconds; other numbers go through
 * js_fmt_num (shortest text that reads back exactly, locale-free).
 * The schema is docs/output.md.  Cost: O(frames + nodes * phases).
 */
#include "sim/app/run/report.h"
#include "sim/core/datapath.h"
#include "sim/output/provenance.h"
#include "sim/output/table.h"
#include <errno.h>
#include <math.h>
#include <glib/gstdio.h>
#include <string.h>
#include <unistd.h>

static const char *const format_names[] = {"text", "json", "csv", NULL};
static const char *const format_files[] = {"summary.txt", "result.json",
                                           "result.csv"};

gboolean rpt_format_parse(const char *s, RptFormat *out)
{
    for (int i = 0; format_names[i]; i++)
        if (strcmp(s, format_names[i]) == 0) {
            *out = (RptFormat)i;
            return TRUE;
        }
    return FALSE;
}

const char *rpt_format_file(RptFormat f)
{
    return format_files[f];
}

/* Exact seconds from picoseconds: "0.00035", "2", "1.000000000001". */
static void put_time(GString *s, SimTime t)
{
    uint64_t whole = t / SIM_S, frac = t % SIM_S;
    g_string_append_printf(s, "%" G_GUINT64_FORMAT, whole);
    if (!frac)
        return;
    char buf[16];
    g_snprintf(buf, sizeof buf, "%012" G_GUINT64_FORMAT, frac);
    for (int i = 11; i > 0 && buf[i] == '0'; i--)
        buf[i] = '\0';
    g_string_append_printf(s, ".%s", buf);
}

static double util(const SimResult *r, SimTime busy)
{
    return r->elapsed ? (double)busy / (double)r->elapsed : 0.0;
}

static double events_per_s(const SimResult *r)
{
    return r->wall_s > 0 ? (double)r->events / r->wall_s : 0.0;
}

static SimTime frame_at(const SimResult *r, guint i)
{
    return g_array_index(r->frame_times, SimTime, i);
}

/* ---- JSON ------------------------------------------------------------- */

/* Seconds as the double nearest the exact picosecond time (a division,
 * correctly rounded, not sim_time_to_s's multiplication). */
static double exact_s(SimTime t)
{
    return (double)t / (double)SIM_S;
}

static void set_time(JsonBuilder *b, const char *key, SimTime t)
{
    js_set_num(b, key, exact_s(t));
}

static SimProvenance provenance_of(const SimResult *r)
{
    SimProvenance p = {r->config_path, r->config_sha256, r->overrides,
                       r->seed,        r->fidelity,     r->config_effective,
                       r->inputs};
    return p;
}

static void json_run(JsonBuilder *b, const SimResult *r)
{
    js_set_str(b, "schema", "pgsim-result");
    js_set_int(b, "schema_version", 1);
    js_set_str(b, "workload", r->workload);
    js_set_str(b, "machine", r->machine);
    js_set_str(b, "fidelity", r->fidelity);
    js_set_int(b, "seed", (gint64)r->seed);
    SimProvenance p = provenance_of(r);
    prov_json(b, &p);
    set_time(b, "elapsed_s", r->elapsed);
}

static void json_frames(JsonBuilder *b, const SimResult *r)
{
    json_builder_set_member_name(b, "frames");
    json_builder_begin_object(b);
    js_set_int(b, "count", r->frame_times->len);
    js_set_num(b, "mean_s", sim_result_mean_frame_s(r));
    json_builder_set_member_name(b, "times_s");
    json_builder_begin_array(b);
    for (guint i = 0; i < r->frame_times->len; i++)
        js_add_num(b, exact_s(frame_at(r, i)));
    json_builder_end_array(b);
    json_builder_end_object(b);
}

static void json_phases(JsonBuilder *b, const SimResult *r,
                        const SimNodeResult *n)
{
    json_builder_set_member_name(b, "phases");
    json_builder_begin_object(b);
    for (guint p = 0; p < r->phases->len; p++) {
        SimTime busy = sim_busy_phase(&n->busy, p);
        json_builder_set_member_name(b, g_ptr_array_index(r->phases, p));
        json_builder_begin_object(b);
        set_time(b, "busy_s", busy);
        js_set_num(b, "utilisation", util(r, busy));
        json_builder_end_object(b);
    }
    json_builder_end_object(b);
}

static void json_nodes(JsonBuilder *b, const SimResult *r)
{
    json_builder_set_member_name(b, "phases");
    json_builder_begin_array(b);
    for (guint p = 0; p < r->phases->len; p++)
        js_add_str(b, g_ptr_array_index(r->phases, p));
    json_builder_end_array(b);
    json_builder_set_member_name(b, "nodes");
    json_builder_begin_array(b);
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        json_builder_begin_object(b);
        js_set_str(b, "name", n->name);
        js_set_str(b, "kind", n->kind);
        set_time(b, "busy_s", n->busy.total);
        js_set_num(b, "utilisation", util(r, n->busy.total));
        json_phases(b, r, n);
        json_builder_end_object(b);
    }
    json_builder_end_array(b);
    json_builder_set_member_name(b, "idle");
    json_builder_begin_array(b);
    for (guint i = 0; i < r->idle->len; i++) {
        const SimIdleResult *e = g_ptr_array_index(r->idle, i);
        json_builder_begin_object(b);
        js_set_str(b, "kind", e->kind);
        js_set_int(b, "count", (gint64)e->count);
        json_builder_end_object(b);
    }
    json_builder_end_array(b);
    SimUtilUsed u = sim_result_util_used(r);
    json_builder_set_member_name(b, "utilisation");
    json_builder_begin_object(b);
    js_set_int(b, "used", (gint64)u.used);
    js_set_int(b, "idle", (gint64)u.idle);
    js_set_num(b, "mean_used", u.mean);
    js_set_num(b, "max_used", u.max);
    json_builder_end_object(b);
}

static void json_comm(JsonBuilder *b, const SimResult *r)
{
    json_builder_set_member_name(b, "comm");
    json_builder_begin_object(b);
    js_set_int(b, "bytes", (gint64)r->comm_bytes);
    js_set_int(b, "messages", (gint64)r->comm_messages);
    js_set_str(b, "busiest_link", r->busiest_link);
    js_set_int(b, "busiest_link_bytes", (gint64)r->busiest_link_bytes);
    json_builder_end_object(b);
}

static void json_metrics(JsonBuilder *b, const SimResult *r, gboolean timing)
{
    json_builder_set_member_name(b, "metrics");
    json_builder_begin_array(b);
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m = g_ptr_array_index(r->metrics, i);
        json_builder_begin_object(b);
        js_set_str(b, "name", m->name);
        js_set_num(b, "value", m->value);
        js_set_str(b, "unit", m->unit);
        json_builder_end_object(b);
    }
    json_builder_end_array(b);
    json_builder_set_member_name(b, "sim");
    json_builder_begin_object(b);
    js_set_int(b, "events", (gint64)r->events);
    if (timing) {
        js_set_num(b, "wall_s", r->wall_s);
        js_set_num(b, "events_per_s", events_per_s(r));
    }
    json_builder_end_object(b);
}

/* "memory": only when the workload reports a per-node footprint; node_B
 * and fits are null when the model gives no node memory. */
static void json_memory(JsonBuilder *b, const SimResult *r)
{
    if (!isfinite(r->mem_peak))
        return;
    json_builder_set_member_name(b, "memory");
    json_builder_begin_object(b);
    js_set_num(b, "peak_per_node_B", r->mem_peak);
    if (r->mem_node) {
        js_set_int(b, "node_B", (gint64)r->mem_node);
        js_set_str(b, "kind", r->mem_kind);
        js_set_bool(b, "fits", !sim_result_mem_exceeds(r));
    } else {
        js_set_str(b, "node_B", NULL);
        js_set_str(b, "kind", NULL);
        js_set_str(b, "fits", NULL);
    }
    json_builder_end_object(b);
}

static void json_notes(JsonBuilder *b, const SimResult *r)
{
    if (!r->notes->len)
        return;
    json_builder_set_member_name(b, "notes");
    json_builder_begin_array(b);
    for (guint i = 0; i < r->notes->len; i++)
        js_add_str(b, g_ptr_array_index(r->notes, i));
    json_builder_end_array(b);
}

static char *render_json(const SimResult *r, gboolean timing)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    json_run(b, r);
    json_frames(b, r);
    json_nodes(b, r);
    json_comm(b, r);
    json_memory(b, r);
    json_metrics(b, r, timing);
    json_notes(b, r);
    json_builder_end_object(b);
    return js_finish(b, TRUE);
}

/* ---- CSV -------------------------------------------------------------- */

/* One row: section,name,phase,field,<value>,unit; value is preformatted. */
static void csv_row(GString *s, const char *section, const char *name,
                    const char *phase, const char *field, const char *value,
                    const char *unit)
{
    const char *f[] = {section, name, phase, field, value, unit};
    for (int i = 0; i < 6; i++) {
        if (i)
            g_string_append_c(s, ',');
        dt_csv_field(s, f[i]);
    }
    g_string_append_c(s, '\n');
}

static void csv_time(GString *s, const char *section, const char *name,
                     const char *phase, const char *field, SimTime t)
{
    GString *v = g_string_new(NULL);
    put_time(v, t);
    csv_row(s, section, name, phase, field, v->str, "s");
    g_string_free(v, TRUE);
}

static void csv_num(GString *s, const char *section, const char *name,
                    const char *phase, const char *field, double x,
                    const char *unit)
{
    char buf[32];
    csv_row(s, section, name, phase, field, js_fmt_num(buf, x), unit);
}

static void csv_u64(GString *s, const char *section, const char *field,
                    uint64_t x, const char *unit)
{
    char buf[24];
    g_snprintf(buf, sizeof buf, "%" G_GUINT64_FORMAT, x);
    csv_row(s, section, NULL, NULL, field, buf, unit);
}

static void csv_run(GString *s, const SimResult *r)
{
    g_string_append(s, "section,name,phase,field,value,unit\n");
    csv_row(s, "run", NULL, NULL, "workload", r->workload, NULL);
    csv_row(s, "run", NULL, NULL, "machine", r->machine, NULL);
    csv_row(s, "run", NULL, NULL, "fidelity", r->fidelity, NULL);
    csv_u64(s, "run", "seed", r->seed, NULL);
    SimProvenance p = provenance_of(r);
    prov_csv_rows(s, &p);
    csv_time(s, "run", NULL, NULL, "elapsed", r->elapsed);
    csv_u64(s, "frames", "count", r->frame_times->len, NULL);
    csv_num(s, "frames", NULL, NULL, "mean", sim_result_mean_frame_s(r), "s");
    for (guint i = 0; i < r->frame_times->len; i++) {
        char idx[16];
        g_snprintf(idx, sizeof idx, "%u", i);
        csv_time(s, "frame", idx, NULL, "time", frame_at(r, i));
    }
}

static void csv_nodes(GString *s, const SimResult *r)
{
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        csv_row(s, "node", n->name, NULL, "kind", n->kind, NULL);
        csv_time(s, "node", n->name, NULL, "busy", n->busy.total);
        csv_num(s, "node", n->name, NULL, "utilisation", util(r, n->busy.total),
                NULL);
        for (guint p = 0; p < r->phases->len; p++) {
            const char *ph = g_ptr_array_index(r->phases, p);
            SimTime b = sim_busy_phase(&n->busy, p);
            csv_time(s, "node", n->name, ph, "busy", b);
            csv_num(s, "node", n->name, ph, "utilisation", util(r, b), NULL);
        }
    }
    for (guint i = 0; i < r->idle->len; i++) {
        const SimIdleResult *e = g_ptr_array_index(r->idle, i);
        char buf[24];
        g_snprintf(buf, sizeof buf, "%" G_GUINT64_FORMAT, e->count);
        csv_row(s, "idle", e->kind, NULL, "count", buf, NULL);
    }
    SimUtilUsed u = sim_result_util_used(r);
    csv_u64(s, "utilisation", "used", u.used, NULL);
    csv_u64(s, "utilisation", "idle", u.idle, NULL);
    csv_num(s, "utilisation", NULL, NULL, "mean_used", u.mean, NULL);
    csv_num(s, "utilisation", NULL, NULL, "max_used", u.max, NULL);
}

static void csv_rest(GString *s, const SimResult *r, gboolean timing)
{
    csv_u64(s, "comm", "bytes", r->comm_bytes, "B");
    csv_u64(s, "comm", "messages", r->comm_messages, NULL);
    csv_row(s, "comm", NULL, NULL, "busiest_link", r->busiest_link, NULL);
    csv_u64(s, "comm", "busiest_link_bytes", r->busiest_link_bytes, "B");
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m = g_ptr_array_index(r->metrics, i);
        csv_num(s, "metric", m->name, NULL, "value", m->value, m->unit);
    }
    csv_u64(s, "sim", "events", r->events, NULL);
    if (timing) {
        csv_num(s, "sim", NULL, NULL, "wall", r->wall_s, "s");
        csv_num(s, "sim", NULL, NULL, "events_per_s", events_per_s(r), NULL);
    }
}

static void csv_memory(GString *s, const SimResult *r)
{
    if (!isfinite(r->mem_peak))
        return;
    csv_num(s, "memory", NULL, NULL, "peak_per_node", r->mem_peak, "B");
    if (!r->mem_node)
        return;
    csv_u64(s, "memory", "node", r->mem_node, "B");
    csv_row(s, "memory", NULL, NULL, "kind", r->mem_kind, NULL);
    csv_row(s, "memory", NULL, NULL, "fits",
            sim_result_mem_exceeds(r) ? "false" : "true", NULL);
}

static char *render_csv(const SimResult *r, gboolean timing)
{
    GString *s = g_string_new(NULL);
    csv_run(s, r);
    csv_nodes(s, r);
    csv_memory(s, r);
    csv_rest(s, r, timing);
    for (guint i = 0; i < r->notes->len; i++)
        csv_row(s, "note", NULL, NULL, "text", g_ptr_array_index(r->notes, i),
                NULL);
    return g_string_free(s, FALSE);
}

/* ---- text ------------------------------------------------------------- */

/* A duration in a readable unit, fixed decimals, locale-free. */
static const char *dur(char buf[40], double s)
{
    static const char *const units[] = {"s", "ms", "us", "ns"};
    int u = 0;
    while (u < 3 && s != 0 && fabs(s) < 1.0) {
        s *= 1e3;
        u++;
    }
    char num[32];
    g_ascii_formatd(num, sizeof num, "%.3f", s);
    g_snprintf(buf, 40, "%s %s", num, units[u]);
    return buf;
}

/* Bytes with an SI prefix like the header's times ("5.4 MB"). */
static const char *bytes(char buf[48], double b)
{
    static const char *const units[] = {"B", "kB", "MB", "GB", "TB"};
    int u = 0;
    while (u < 4 && fabs(b) >= 1000.0) {
        b /= 1e3;
        u++;
    }
    char num[32];
    g_ascii_formatd(num, sizeof num, u ? "%.3g" : "%.0f", b);
    g_snprintf(buf, 48, "%s %s", num, units[u]);
    return buf;
}

/* A metric for people: times and sizes scaled to a readable unit
 * (74.8 us, not 7.47891e-05 s); other units as %.6g.  JSON and CSV keep
 * the exact value in the metric's own unit. */
static const char *human(char buf[48], const SimMetric *m)
{
    if (strcmp(m->unit, "s") == 0 || strcmp(m->unit, "ms") == 0) {
        char d[40];
        double sec = m->value * (m->unit[0] == 'm' ? 1e-3 : 1.0);
        g_strlcpy(buf, isfinite(sec) ? dur(d, sec) : "nan", 48);
        return buf;
    }
    if (strcmp(m->unit, "B") == 0 && isfinite(m->value))
        return bytes(buf, m->value);
    char num[32];
    g_ascii_formatd(num, sizeof num, "%.6g", m->value);
    g_snprintf(buf, 48, "%s%s%s", num, *m->unit ? " " : "", m->unit);
    return buf;
}

static const char *pct(char buf[32], double x)
{
    g_ascii_formatd(buf, 32, "%.1f", 100.0 * x);
    strcat(buf, "%");
    return buf;
}

static void text_frames(GString *s, const SimResult *r)
{
    char a[40], b[40], c[40];
    guint n = r->frame_times->len;
    SimTime lo = SIM_TIME_MAX, hi = 0;
    for (guint i = 0; i < n; i++) {
        lo = MIN(lo, frame_at(r, i));
        hi = MAX(hi, frame_at(r, i));
    }
    g_string_append_printf(
        s, "%s on %s (fidelity %s, seed %" G_GUINT64_FORMAT ")\n", r->workload,
        r->machine, r->fidelity, r->seed);
    g_string_append_printf(s, "simulated     %s\n",
                           dur(a, sim_time_to_s(r->elapsed)));
    if (n)
        g_string_append_printf(s,
                               "frames        %u, mean %s (min %s, max "
                               "%s)\n",
                               n, dur(a, sim_result_mean_frame_s(r)),
                               dur(b, sim_time_to_s(lo)),
                               dur(c, sim_time_to_s(hi)));
    for (guint i = 0; i < n && n <= 10; i++)
        g_string_append_printf(s, "  frame %-5u %s\n", i,
                               dur(a, sim_time_to_s(frame_at(r, i))));
}

static void text_node(GString *s, const SimResult *r, const SimNodeResult *n)
{
    char a[32];
    g_string_append_printf(s, "  %-12s %-10s %8s", n->name, n->kind,
                           pct(a, util(r, n->busy.total)));
    for (guint p = 0; p < r->phases->len; p++)
        g_string_append_printf(s, " %10s",
                               pct(a, util(r, sim_busy_phase(&n->busy, p))));
    g_string_append_c(s, '\n');
}

/* One line per kind of processors that did nothing. */
static void text_idle(GString *s, const SimResult *r)
{
    for (guint i = 0; i < r->idle->len; i++) {
        const SimIdleResult *e = g_ptr_array_index(r->idle, i);
        g_string_append_printf(s,
                               "  %-12s %-10s %8s  (%" G_GUINT64_FORMAT
                               " processors, all idle)\n",
                               "idle", e->kind, "0.0%", e->count);
    }
}

/* Up to this many processors the table lists each; above, one summary
 * per kind. */
#define TEXT_MAX_LISTED 32

/* One statistic ("min", "mean", "max") of busy and of each phase's
 * utilisation over the listed processors of one kind. */
static void text_kind_stat(GString *s, const SimResult *r, const char *kind,
                           guint count, int stat)
{
    static const char *const names[] = {"min", "mean", "max"};
    guint cols = r->phases->len + 1;
    double *v = g_new(double, cols);
    for (guint c = 0; c < cols; c++)
        v[c] = stat == 0 ? INFINITY : stat == 2 ? -INFINITY : 0.0;
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        if (strcmp(n->kind, kind) != 0)
            continue;
        for (guint c = 0; c < cols; c++) {
            SimTime b = c ? sim_busy_phase(&n->busy, c - 1) : n->busy.total;
            double u = util(r, b);
            v[c] = stat == 0 ? MIN(v[c], u) : stat == 2 ? MAX(v[c], u)
                                                          : v[c] + u / count;
        }
    }
    char label[32], a[32];
    g_snprintf(label, sizeof label, "%s of %u", names[stat], count);
    g_string_append_printf(s, "  %-12s %-10s %8s", label, kind, pct(a, v[0]));
    for (guint c = 1; c < cols; c++)
        g_string_append_printf(s, " %10s", pct(a, v[c]));
    g_string_append_c(s, '\n');
    g_free(v);
}

/* Above TEXT_MAX_LISTED: min, mean and max per kind, kinds in order of
 * first appearance.  O(kinds * nodes * phases). */
static void text_kinds(GString *s, const SimResult *r)
{
    GPtrArray *kinds = g_ptr_array_new();
    GArray *counts = g_array_new(FALSE, TRUE, sizeof(guint));
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        guint k = 0;
        while (k < kinds->len && strcmp(kinds->pdata[k], n->kind) != 0)
            k++;
        if (k == kinds->len) {
            g_ptr_array_add(kinds, n->kind);
            guint zero = 0;
            g_array_append_val(counts, zero);
        }
        g_array_index(counts, guint, k)++;
    }
    for (guint k = 0; k < kinds->len; k++) {
        guint count = g_array_index(counts, guint, k);
        for (guint i = 0; count == 1 && i < r->nodes->len; i++) {
            const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
            if (strcmp(n->kind, kinds->pdata[k]) == 0)
                text_node(s, r, n); /* a kind of one: the processor */
        }
        for (int stat = 0; count > 1 && stat < 3; stat++)
            text_kind_stat(s, r, kinds->pdata[k], count, stat);
    }
    g_string_append_printf(s, "  (%u busy processors summarised per kind; "
                              "each one in JSON/CSV)\n",
                           r->nodes->len);
    g_array_free(counts, TRUE);
    g_ptr_array_free(kinds, TRUE);
}

static void text_nodes(GString *s, const SimResult *r)
{
    guint n = r->nodes->len;
    if (!n && !r->idle->len)
        return;
    g_string_append_printf(s,
                           "utilisation   busy / simulated time, per "
                           "phase\n  %-12s %-10s %8s",
                           n <= TEXT_MAX_LISTED ? "node" : "node / stat",
                           "kind", "busy");
    for (guint p = 0; p < r->phases->len; p++)
        g_string_append_printf(s, " %10.10s",
                               (const char *)g_ptr_array_index(r->phases, p));
    g_string_append_c(s, '\n');
    if (n <= TEXT_MAX_LISTED)
        for (guint i = 0; i < n; i++)
            text_node(s, r, g_ptr_array_index(r->nodes, i));
    else
        text_kinds(s, r);
    text_idle(s, r);
    SimUtilUsed u = sim_result_util_used(r);
    char a[32];
    g_string_append_printf(s,
                           "  mean busy over the %" G_GUINT64_FORMAT
                           " processors used: %s (%" G_GUINT64_FORMAT
                           " idle, not in it)\n",
                           u.used, pct(a, u.mean), u.idle);
}

/* "note          " then the text in lines of at most 78 columns, each
 * indented like the first (a word longer than a line stays whole). */
static void text_note(GString *s, const char *text)
{
    enum { INDENT = 14, WIDTH = 78 };
    g_string_append_printf(s, "%-*s", INDENT, "note");
    guint col = INDENT;
    char **words = g_strsplit(text, " ", -1);
    for (guint w = 0; words[w]; w++) {
        guint len = (guint)strlen(words[w]);
        if (!len)
            continue;
        if (col > INDENT && col + 1 + len > WIDTH) {
            g_string_append_printf(s, "\n%*s", INDENT, "");
            col = INDENT;
        } else if (col > INDENT) {
            g_string_append_c(s, ' ');
            col++;
        }
        g_string_append(s, words[w]);
        col += len;
    }
    g_strfreev(words);
    g_string_append_c(s, '\n');
}

static void text_rest(GString *s, const SimResult *r, gboolean timing)
{
    char a[32], b[48];
    g_string_append_printf(s,
                           "communication %" G_GUINT64_FORMAT " messages, %s",
                           r->comm_messages, bytes(b, (double)r->comm_bytes));
    if (r->busiest_link)
        g_string_append_printf(s, "; busiest link %s (%s)", r->busiest_link,
                               bytes(b, (double)r->busiest_link_bytes));
    g_string_append_c(s, '\n');
    if (r->metrics->len)
        g_string_append(s, "metrics\n");
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m = g_ptr_array_index(r->metrics, i);
        char h[48];
        g_string_append_printf(s, "  %-28s %s\n", m->name, human(h, m));
    }
    for (guint i = 0; i < r->notes->len; i++)
        text_note(s, g_ptr_array_index(r->notes, i));
    g_string_append_printf(s, "simulator     %" G_GUINT64_FORMAT " events",
                           r->events);
    if (timing)
        g_string_append_printf(
            s, " in %s s wall (%s events/s)",
            g_ascii_formatd(a, 16, "%.3g", r->wall_s),
            g_ascii_formatd(a + 16, 16, "%.3g", events_per_s(r)));
    g_string_append_c(s, '\n');
}

/* The footprint against the node memory, when the workload reports one. */
static void text_memory(GString *s, const SimResult *r)
{
    if (!isfinite(r->mem_peak))
        return;
    const double mib = 1048576.0;
    g_string_append_printf(s, "memory        %.2f MiB per node (largest)",
                           r->mem_peak / mib);
    if (r->mem_node)
        g_string_append_printf(
            s, " of %.2f MiB (kind %s): %s", (double)r->mem_node / mib,
            r->mem_kind,
            sim_result_mem_exceeds(r) ? "DOES NOT FIT, infeasible on "
                                        "this machine"
                                      : "fits");
    else
        g_string_append(s, "; the model gives no node memory");
    g_string_append_c(s, '\n');
}

static char *render_text(const SimResult *r, gboolean timing)
{
    GString *s = g_string_new(NULL);
    SimProvenance p = provenance_of(r);
    prov_text_notes(s, &p);
    text_frames(s, r);
    text_nodes(s, r);
    text_memory(s, r);
    text_rest(s, r, timing);
    return g_string_free(s, FALSE);
}

char *rpt_render(const SimResult *r, RptFormat f, gboolean timing)
{
    switch (f) {
    case RPT_JSON:
        return render_json(r, timing);
    case RPT_CSV:
        return render_csv(r, timing);
    default:
        return render_text(r, timing);
    }
}

/* A format's file: summary.txt ends with the provenance line the
 * reproductions' text tables carry (result.json and result.csv hold the
 * provenance in their own shapes); no time of day, so the file is a
 * function of the result. */
static char *render_file(const SimResult *r, RptFormat f, gboolean timing)
{
    char *text = rpt_render(r, f, timing);
    if (f != RPT_TEXT)
        return text;
    GString *s = g_string_new(text);
    g_free(text);
    SimProvenance p = provenance_of(r);
    prov_text_line(s, &p);
    g_string_append_c(s, '\n');
    return g_string_free(s, FALSE);
}

/* Renames or removes the staged files (NULL entries skipped). */
static gboolean unstage(char **staged, const char *dir, gboolean keep,
                        GError **err)
{
    gboolean ok = TRUE;
    for (int f = RPT_TEXT; f <= RPT_CSV; f++) {
        if (!staged[f])
            continue;
        char *path = g_build_filename(dir, format_files[f], NULL);
        if (keep && ok && g_rename(staged[f], path) != 0) {
            int e = errno;
            g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                        "%s: found %s, expected a writable file", path,
                        g_strerror(e));
            ok = FALSE;
        }
        if (!keep || !ok)
            g_remove(staged[f]);
        g_free(path);
        g_free(staged[f]);
    }
    return ok;
}

/* The three files are written beside their places first (".NAME.PID"
 * hidden files, each whole and synced) and renamed into place only when
 * all three are written: a full disk or any other failure leaves the
 * earlier run's files as they were, never a mix of old and new. */
gboolean rpt_write_dir(const SimResult *r, const char *dir, gboolean timing,
                       GError **err)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found %s, expected a "
                    "directory that can be created",
                    dir, g_strerror(errno));
        return FALSE;
    }
    char *staged[RPT_CSV + 1] = {NULL};
    gboolean ok = TRUE;
    for (int f = RPT_TEXT; ok && f <= RPT_CSV; f++) {
        char *text = render_file(r, (RptFormat)f, timing);
        char *name = g_strdup_printf(".%s.%d", format_files[f], (int)getpid());
        staged[f] = g_build_filename(dir, name, NULL);
        ok = sim_file_write(staged[f], text, strlen(text), err);
        g_free(name);
        g_free(text);
    }
    return unstage(staged, dir, ok, err) && ok;
}
