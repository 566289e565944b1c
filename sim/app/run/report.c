/* report.c — text, JSON and CSV renderings of a SimResult (report.h).
 *
 * Each writer walks the result once in a fixed order (run, frames,
 * nodes, communication, metrics, simulator), so output is a pure
 * function of the result.  Simulated times are integer picoseconds
 * printed as exact decimal seconds; other numbers go through
 * json_fmt_num (shortest text that reads back exactly, locale-free).
 * The schema is docs/output.md.  Cost: O(frames + nodes * phases).
 */
#include "sim/app/run/report.h"
#include "sim/core/datapath.h"
#include "sim/output/json.h"
#include <errno.h>
#include <string.h>

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

static void put_num(GString *s, double x)
{
    char buf[32];
    const char *t = json_fmt_num(buf, x);
    g_string_append(s, *t ? t : "null");
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

/* ", "key": <value>" members of an object already opened. */
static void kv_str(GString *s, const char *key, const char *v)
{
    g_string_append_printf(s, ", \"%s\": ", key);
    json_put_str(s, v);
}

static void kv_time(GString *s, const char *key, SimTime t)
{
    g_string_append_printf(s, ", \"%s\": ", key);
    put_time(s, t);
}

static void kv_num(GString *s, const char *key, double x)
{
    g_string_append_printf(s, ", \"%s\": ", key);
    put_num(s, x);
}

static void json_key(GString *s, const char *indent, const char *key)
{
    g_string_append_printf(s, "%s\"%s\": ", indent, key);
}

#ifndef PGSIM_GIT_VERSION
#define PGSIM_GIT_VERSION "unknown"
#endif

const char *rpt_version(void)
{
    return PGSIM_GIT_VERSION;
}

/* Where the result came from: the build, the config and its overrides. */
static void json_provenance(GString *s, const SimResult *r)
{
    g_string_append(s, ",\n  \"provenance\": {\"pgsim_version\": ");
    json_put_str(s, rpt_version());
    g_string_append(s, ", \"config\": ");
    r->config_path ? json_put_str(s, r->config_path)
                   : (void)g_string_append(s, "null");
    g_string_append(s, ", \"config_sha256\": ");
    r->config_sha256 ? json_put_str(s, r->config_sha256)
                     : (void)g_string_append(s, "null");
    g_string_append(s, ", \"overrides\": [");
    for (guint i = 0; i < r->overrides->len; i++) {
        g_string_append(s, i ? ", " : "");
        json_put_str(s, r->overrides->pdata[i]);
    }
    g_string_append_printf(s, "], \"seed\": %" G_GUINT64_FORMAT
                              ", \"fidelity\": ",
                           r->seed);
    json_put_str(s, r->fidelity);
    g_string_append_printf(s, ",\n    \"effective_config\": %s}",
                           r->config_effective ? r->config_effective : "null");
}

static void json_run(GString *s, const SimResult *r)
{
    g_string_append(s, "{\n  \"schema\": \"pgsim-result\",\n"
                       "  \"schema_version\": 1,\n");
    json_key(s, "  ", "workload");
    json_put_str(s, r->workload);
    kv_str(s, "machine", r->machine);
    kv_str(s, "fidelity", r->fidelity);
    g_string_append_printf(
        s, ",\n  \"seed\": %" G_GUINT64_FORMAT, r->seed);
    json_provenance(s, r);
    g_string_append(s, ",\n  \"elapsed_s\": ");
    put_time(s, r->elapsed);
}

static void json_frames(GString *s, const SimResult *r)
{
    g_string_append_printf(s, ",\n  \"frames\": {\"count\": %u, \"mean_s\": ",
                           r->frame_times->len);
    put_num(s, sim_result_mean_frame_s(r));
    g_string_append(s, ", \"times_s\": [");
    for (guint i = 0; i < r->frame_times->len; i++) {
        g_string_append(s, i ? ", " : "");
        put_time(s, frame_at(r, i));
    }
    g_string_append(s, "]}");
}

static void json_phases(GString *s, const SimResult *r, const SimNodeResult *n)
{
    g_string_append(s, ", \"phases\": {");
    for (guint p = 0; p < r->phases->len; p++) {
        SimTime b = sim_busy_phase(&n->busy, p);
        g_string_append(s, p ? ", " : "");
        json_put_str(s, g_ptr_array_index(r->phases, p));
        g_string_append(s, ": {\"busy_s\": ");
        put_time(s, b);
        kv_num(s, "utilisation", util(r, b));
        g_string_append(s, "}");
    }
    g_string_append(s, "}}");
}

static void json_nodes(GString *s, const SimResult *r)
{
    g_string_append(s, ",\n  \"phases\": [");
    for (guint p = 0; p < r->phases->len; p++) {
        g_string_append(s, p ? ", " : "");
        json_put_str(s, g_ptr_array_index(r->phases, p));
    }
    g_string_append(s, "],\n  \"nodes\": [");
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        g_string_append(s, i ? ",\n    {\"name\": " : "\n    {\"name\": ");
        json_put_str(s, n->name);
        kv_str(s, "kind", n->kind);
        kv_time(s, "busy_s", n->busy.total);
        kv_num(s, "utilisation", util(r, n->busy.total));
        json_phases(s, r, n);
    }
    g_string_append(s, r->nodes->len ? "\n  ]" : "]");
    g_string_append(s, ",\n  \"idle\": [");
    for (guint i = 0; i < r->idle->len; i++) {
        const SimIdleResult *e = g_ptr_array_index(r->idle, i);
        g_string_append(s, i ? ", {\"kind\": " : "{\"kind\": ");
        json_put_str(s, e->kind);
        g_string_append_printf(s, ", \"count\": %" G_GUINT64_FORMAT "}",
                               e->count);
    }
    g_string_append_c(s, ']');
}

static void json_comm(GString *s, const SimResult *r)
{
    g_string_append_printf(s,
                           ",\n  \"comm\": {\"bytes\": %" G_GUINT64_FORMAT
                           ", \"messages\": %" G_GUINT64_FORMAT
                           ", \"busiest_link\": ",
                           r->comm_bytes, r->comm_messages);
    json_put_str(s, r->busiest_link);
    g_string_append_printf(s,
                           ", \"busiest_link_bytes\": %" G_GUINT64_FORMAT "}",
                           r->busiest_link_bytes);
}

static void json_metrics(GString *s, const SimResult *r, gboolean timing)
{
    g_string_append(s, ",\n  \"metrics\": [");
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m = g_ptr_array_index(r->metrics, i);
        g_string_append(s, i ? ",\n    {\"name\": " : "\n    {\"name\": ");
        json_put_str(s, m->name);
        kv_num(s, "value", m->value);
        kv_str(s, "unit", m->unit);
        g_string_append(s, "}");
    }
    g_string_append(s, r->metrics->len ? "\n  ]" : "]");
    g_string_append_printf(s, ",\n  \"sim\": {\"events\": %" G_GUINT64_FORMAT,
                           r->events);
    if (timing) {
        kv_num(s, "wall_s", r->wall_s);
        kv_num(s, "events_per_s", events_per_s(r));
    }
    g_string_append(s, "}\n}\n");
}

static char *render_json(const SimResult *r, gboolean timing)
{
    GString *s = g_string_new(NULL);
    json_run(s, r);
    json_frames(s, r);
    json_nodes(s, r);
    json_comm(s, r);
    json_metrics(s, r, timing);
    return g_string_free(s, FALSE);
}

/* ---- CSV -------------------------------------------------------------- */

static void csv_field(GString *s, const char *f)
{
    if (!f)
        return;
    if (!strpbrk(f, ",\"\r\n")) {
        g_string_append(s, f);
        return;
    }
    g_string_append_c(s, '"');
    for (; *f; f++) {
        if (*f == '"')
            g_string_append_c(s, '"');
        g_string_append_c(s, *f);
    }
    g_string_append_c(s, '"');
}

/* One row: section,name,phase,field,<value>,unit; value is preformatted. */
static void csv_row(GString *s, const char *section, const char *name,
                    const char *phase, const char *field, const char *value,
                    const char *unit)
{
    const char *f[] = {section, name, phase, field, value, unit};
    for (int i = 0; i < 6; i++) {
        if (i)
            g_string_append_c(s, ',');
        csv_field(s, f[i]);
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
    csv_row(s, section, name, phase, field, json_fmt_num(buf, x), unit);
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
    csv_row(s, "provenance", NULL, NULL, "pgsim_version", rpt_version(), NULL);
    csv_row(s, "provenance", NULL, NULL, "config", r->config_path, NULL);
    csv_row(s, "provenance", NULL, NULL, "config_sha256", r->config_sha256,
            NULL);
    for (guint i = 0; i < r->overrides->len; i++) {
        char idx[16];
        g_snprintf(idx, sizeof idx, "%u", i);
        csv_row(s, "provenance", idx, NULL, "override", r->overrides->pdata[i],
                NULL);
    }
    csv_row(s, "provenance", NULL, NULL, "effective_config",
            r->config_effective, NULL);
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

static char *render_csv(const SimResult *r, gboolean timing)
{
    GString *s = g_string_new(NULL);
    csv_run(s, r);
    csv_nodes(s, r);
    csv_rest(s, r, timing);
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

static void text_nodes(GString *s, const SimResult *r)
{
    guint n = r->nodes->len, shown = n <= 32 ? n : 16;
    if (!n && !r->idle->len)
        return;
    g_string_append_printf(s,
                           "utilisation   busy / simulated time, per "
                           "phase\n  %-12s %-10s %8s",
                           "node", "kind", "busy");
    for (guint p = 0; p < r->phases->len; p++)
        g_string_append_printf(s, " %10.10s",
                               (const char *)g_ptr_array_index(r->phases, p));
    g_string_append_c(s, '\n');
    for (guint i = 0; i < shown; i++)
        text_node(s, r, g_ptr_array_index(r->nodes, i));
    if (shown < n)
        g_string_append_printf(s, "  ... %u more nodes (all in JSON/CSV)\n",
                               n - shown);
    text_idle(s, r);
}

static void text_rest(GString *s, const SimResult *r, gboolean timing)
{
    char a[32];
    g_string_append_printf(s,
                           "communication %" G_GUINT64_FORMAT " messages, "
                           "%" G_GUINT64_FORMAT " bytes",
                           r->comm_messages, r->comm_bytes);
    if (r->busiest_link)
        g_string_append_printf(
            s, "; busiest link %s (%" G_GUINT64_FORMAT " bytes)",
            r->busiest_link, r->busiest_link_bytes);
    g_string_append_c(s, '\n');
    if (r->metrics->len)
        g_string_append(s, "metrics\n");
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m = g_ptr_array_index(r->metrics, i);
        char h[48];
        g_string_append_printf(s, "  %-28s %s\n", m->name, human(h, m));
    }
    g_string_append_printf(s, "simulator     %" G_GUINT64_FORMAT " events",
                           r->events);
    if (timing)
        g_string_append_printf(
            s, " in %s s wall (%s events/s)",
            g_ascii_formatd(a, 16, "%.3g", r->wall_s),
            g_ascii_formatd(a + 16, 16, "%.3g", events_per_s(r)));
    g_string_append_c(s, '\n');
}

static char *render_text(const SimResult *r, gboolean timing)
{
    GString *s = g_string_new(NULL);
    text_frames(s, r);
    text_nodes(s, r);
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
    gboolean ok = TRUE;
    for (int f = RPT_TEXT; ok && f <= RPT_CSV; f++) {
        char *text = rpt_render(r, (RptFormat)f, timing);
        char *path = g_build_filename(dir, format_files[f], NULL);
        ok = sim_file_write(path, text, strlen(text), err);
        g_free(path);
        g_free(text);
    }
    return ok;
}
