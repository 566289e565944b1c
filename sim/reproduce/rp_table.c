/* rp_table.c — joining reproduction rows to published values; writers.
 *
 * Invariants: every row appears once, in the order produced; every
 * published cell appears once (matched, or appended as RP_MISSING).
 * rel_error is finite only for RP_COMPARED cells with published != 0.
 * Join: O(rows + cells) with the paper's hash index.
 */
#include "sim/reproduce/rp_table.h"
#include "sim/output/table.h"
#include <math.h>
#include <string.h>

static void joined_free(gpointer p)
{
    RpJoined *j = p;
    g_free(j->table);
    g_free(j->row);
    g_free(j->column);
    g_free(j->unit);
    g_free(j->note);
    g_free(j->fitted_by);
    g_free(j);
}

void rp_table_free(RpTable *t)
{
    if (!t)
        return;
    g_free(t->paper);
    g_free(t->citation);
    g_free(t->fidelity);
    g_free(t->setup);
    g_free(t->setup_sha256);
    g_free(t->setup_json);
    if (t->overrides)
        g_ptr_array_free(t->overrides, TRUE);
    sim_inputs_free(t->inputs);
    g_ptr_array_free(t->cells, TRUE);
    g_free(t);
}

const char *rp_status_name(RpStatus s)
{
    static const char *const names[] = {"compared", "withheld", "unlisted",
                                        "not simulated"};
    g_assert((unsigned)s < G_N_ELEMENTS(names));
    return names[s];
}

static RpJoined *joined_new(const char *t, const char *r, const char *c)
{
    RpJoined *j = g_new0(RpJoined, 1);
    j->table = g_strdup(t);
    j->row = g_strdup(r);
    j->column = g_strdup(c);
    j->sim = j->published = j->rel_error = NAN;
    j->loo_sim = j->loo_rel_error = j->lo = j->hi = NAN;
    j->unit = g_strdup("");
    return j;
}

static void apply_cell(RpJoined *j, const RpCell *c)
{
    g_free(j->unit);
    j->unit = g_strdup(c->unit);
    if (!j->note)
        j->note = g_strdup(c->note);
    if (c->withheld) {
        j->status = RP_WITHHELD;
        return;
    }
    j->published = c->value;
    j->status = isfinite(j->sim) ? RP_COMPARED : RP_MISSING;
    if (j->status == RP_COMPARED && c->value != 0.0)
        j->rel_error = (j->sim - c->value) / c->value;
}

static void join_rows(RpTable *t, const RpPaper *paper, const GPtrArray *rows,
                      GHashTable *seen)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        RpJoined *j = joined_new(r->table, r->row, r->column);
        j->sim = r->sim;
        j->note = g_strdup(r->note);
        j->status = RP_UNLISTED;
        const RpCell *c = rp_paper_cell(paper, r->table, r->row, r->column);
        if (c) {
            apply_cell(j, c);
            g_hash_table_add(seen, (gpointer)c);
        }
        g_ptr_array_add(t->cells, j);
    }
}

static void add_missing(RpTable *t, const RpPaper *paper, GHashTable *seen)
{
    for (guint i = 0; i < paper->cells->len; i++) {
        const RpCell *c = g_ptr_array_index(paper->cells, i);
        if (g_hash_table_contains(seen, c))
            continue;
        RpJoined *j = joined_new(c->table, c->row, c->column);
        apply_cell(j, c);
        g_ptr_array_add(t->cells, j);
    }
}

static void summarise(RpTable *t)
{
    double sum = 0.0;
    t->worst = -1;
    t->mean_abs = t->worst_abs = NAN;
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        if (!isfinite(j->rel_error))
            continue;
        double a = fabs(j->rel_error);
        sum += a;
        t->compared++;
        if (t->worst < 0 || a > t->worst_abs) {
            t->worst_abs = a;
            t->worst = (int)i;
        }
    }
    if (t->compared)
        t->mean_abs = sum / t->compared;
}

RpTable *rp_table_join(const RpPaper *paper, const GPtrArray *rows,
                       const char *fidelity, double wall_s)
{
    RpTable *t = g_new0(RpTable, 1);
    t->paper = g_strdup(paper->name);
    t->citation = g_strdup(paper->citation);
    t->fidelity = g_strdup(fidelity);
    t->wall_s = wall_s;
    t->cells = g_ptr_array_new_with_free_func(joined_free);
    GHashTable *seen = g_hash_table_new(NULL, NULL);
    join_rows(t, paper, rows, seen);
    add_missing(t, paper, seen);
    g_hash_table_destroy(seen);
    summarise(t);
    return t;
}

const RpJoined *rp_table_find(const RpTable *t, const char *table,
                              const char *row, const char *column)
{
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        if (!strcmp(j->table, table) && !strcmp(j->row, row) &&
            !strcmp(j->column, column))
            return j;
    }
    return NULL;
}

/* ---- text ------------------------------------------------------------ */

enum {
    COL_TABLE,
    COL_ROW,
    COL_COLUMN,
    COL_PUB,
    COL_SIM,
    COL_ERR,
    COL_LABEL,
    COL_NOTE,
    N_COLS
};

static void fmt_num(char *buf, size_t n, double x)
{
    if (isfinite(x))
        g_snprintf(buf, n, "%.4g", x);
    else
        g_strlcpy(buf, "-", n);
}

static char **text_fields(const RpJoined *j)
{
    char pub[48], sim[48], err[48];
    fmt_num(pub, sizeof pub, j->published);
    fmt_num(sim, sizeof sim, j->sim);
    if (isfinite(j->rel_error))
        g_snprintf(err, sizeof err, "%+.1f%%", 100.0 * j->rel_error);
    else
        g_strlcpy(err, "-", sizeof err);
    if (j->status == RP_WITHHELD)
        g_strlcpy(pub, "withheld", sizeof pub);
    gboolean odd = j->status == RP_UNLISTED || j->status == RP_MISSING;
    char *note =
        odd && j->note
            ? g_strdup_printf("%s; %s", rp_status_name(j->status), j->note)
            : g_strdup(odd       ? rp_status_name(j->status)
                       : j->note ? j->note
                                 : "");
    char **f = g_new0(char *, N_COLS + 1);
    f[COL_TABLE] = g_strdup(j->table);
    f[COL_ROW] = g_strdup(j->row);
    f[COL_COLUMN] = *j->unit ? g_strdup_printf("%s [%s]", j->column, j->unit)
                             : g_strdup(j->column);
    f[COL_PUB] = g_strdup(pub);
    f[COL_SIM] = g_strdup(sim);
    f[COL_ERR] = g_strdup(err);
    f[COL_LABEL] = rp_label_text(j);
    f[COL_NOTE] = note;
    return f;
}

/* One line; the label column only when `labels`. */
static void text_line(GString *out, char *const *f, const int *w,
                      gboolean labels)
{
    for (int c = 0; c < N_COLS; c++) {
        if (c == COL_LABEL && !labels)
            continue;
        gboolean right = c == COL_PUB || c == COL_SIM || c == COL_ERR;
        int pad = w[c] - (int)g_utf8_strlen(f[c], -1);
        if (c == COL_NOTE) {
            g_string_append(out, f[c]);
            break;
        }
        if (right)
            g_string_append_printf(out, "%*s%s  ", pad, "", f[c]);
        else
            g_string_append_printf(out, "%s%*s  ", f[c], pad, "");
    }
    while (out->len && out->str[out->len - 1] == ' ')
        g_string_truncate(out, out->len - 1);
    g_string_append_c(out, '\n');
}

/* " (table T, R, C)", with ", left out" when `oos` and cross-validated. */
static void where(GString *out, const RpTable *t, int i, gboolean oos)
{
    const RpJoined *w = g_ptr_array_index(t->cells, i);
    gboolean left = oos && w->label == RP_LABEL_CV;
    g_string_append_printf(out, " (table %s, %s, %s%s)", w->table, w->row,
                           w->column, left ? ", left out" : "");
}

/* The labelled headline: out of sample, in sample, intervals, joined
 * by sep. */
static void headline(const RpTable *t, const char *sep, GString *out)
{
    if (t->oos_n) {
        g_string_append_printf(out,
                               "out-of-sample mean |rel_error| %.1f%% over %u "
                               "cells (%u cross-validated, %u predicted), "
                               "worst %.1f%%",
                               100.0 * t->oos_mean, t->oos_n, t->oos_cv,
                               t->oos_n - t->oos_cv, 100.0 * t->oos_worst);
        where(out, t, t->oos_worst_i, TRUE);
    } else {
        g_string_append(out, "out-of-sample: no visible cell is predicted or "
                             "cross-validated");
    }
    g_string_append(out, sep);
    if (t->ins_n) {
        g_string_append_printf(out,
                               "in-sample (fitted cells) mean |rel_error| "
                               "%.1f%% over %u cells, worst %.1f%%",
                               100.0 * t->ins_mean, t->ins_n,
                               100.0 * t->ins_worst);
        where(out, t, t->ins_worst_i, FALSE);
    } else {
        g_string_append(out, "in-sample: no visible cell was fitted");
    }
    g_string_append(out, sep);
    if (isfinite(t->loo_min))
        g_string_append_printf(out,
                               "%u of %u visible cells inside their own "
                               "leave-one-out interval (leave-one-out errors "
                               "%+.1f%% to %+.1f%% over %u cells)",
                               t->inside, t->inside_of, 100.0 * t->loo_min,
                               100.0 * t->loo_max, t->loo_n);
    else
        g_string_append(out, "no leave-one-out values: no intervals");
}

void rp_table_summary(const RpTable *t, GString *out)
{
    if (t->labelled) {
        headline(t, "; ", out);
        return;
    }
    if (!t->compared) {
        g_string_append(out, "no cell compared with a published value");
        return;
    }
    const RpJoined *w = g_ptr_array_index(t->cells, t->worst);
    g_string_append_printf(out,
                           "mean |rel_error| %.1f%% over %u cells, worst "
                           "%.1f%% (table %s, %s, %s)",
                           100.0 * t->mean_abs, t->compared,
                           100.0 * t->worst_abs, w->table, w->row, w->column);
}

SimProvenance rp_table_provenance(const RpTable *t)
{
    return (SimProvenance){t->setup,     t->setup_sha256, t->overrides,
                           RP_SEED,      t->fidelity,     t->setup_json,
                           t->inputs};
}

void rp_table_text(const RpTable *t, GString *out)
{
    static char *const head[] = {"table", "row",   "column", "published",
                                 "sim",   "error", "label",  "note", NULL};
    GPtrArray *lines =
        g_ptr_array_new_with_free_func((GDestroyNotify)g_strfreev);
    int w[N_COLS];
    for (int c = 0; c < N_COLS; c++)
        w[c] = (int)strlen(head[c]);
    for (guint i = 0; i < t->cells->len; i++) {
        char **f = text_fields(g_ptr_array_index(t->cells, i));
        for (int c = 0; c < N_COLS; c++)
            w[c] = MAX(w[c], (int)g_utf8_strlen(f[c], -1));
        g_ptr_array_add(lines, f);
    }
    SimProvenance p = rp_table_provenance(t);
    prov_text_notes(out, &p);
    g_string_append_printf(out, "%s (fidelity %s)%s%s\n", t->paper, t->fidelity,
                           *t->citation ? ": " : "", t->citation);
    prov_text_line(out, &p);
    g_string_append_c(out, '\n');
    text_line(out, head, w, t->labelled);
    for (guint i = 0; i < lines->len; i++)
        text_line(out, g_ptr_array_index(lines, i), w, t->labelled);
    if (t->labelled)
        headline(t, "\n", out);
    else
        rp_table_summary(t, out);
    g_string_append_c(out, '\n');
    g_ptr_array_free(lines, TRUE);
}

/* ---- CSV and JSON ---------------------------------------------------- */

void rp_table_csv_head(const RpTable *t, GString *out)
{
    g_string_append(out, "paper,table,row,column,sim,published,rel_error");
    if (t->labelled)
        g_string_append(out, ",label,fitted_by,loo_sim,loo_rel_error,"
                             "interval_lo,interval_hi");
}

void rp_table_csv(const RpTable *t, gboolean header, GString *out)
{
    SimProvenance p = rp_table_provenance(t);
    prov_comment_lines(out, &p);
    if (header) {
        rp_table_csv_head(t, out);
        g_string_append_c(out, '\n');
    }
    rp_table_csv_rows(t, out);
}

static void csv_labels(const RpJoined *j, GString *out)
{
    char buf[32];
    g_string_append_printf(out, ",%s,", rp_label_name(j->label));
    dt_csv_field(out, j->fitted_by ? j->fitted_by : "");
    const double v[] = {j->loo_sim, j->loo_rel_error, j->lo, j->hi};
    for (int k = 0; k < 4; k++)
        g_string_append_printf(out, ",%s", js_fmt_num(buf, v[k]));
}

void rp_table_csv_rows(const RpTable *t, GString *out)
{
    char buf[32];
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        const char *f[] = {t->paper, j->table, j->row, j->column};
        for (int k = 0; k < 4; k++) {
            dt_csv_field(out, f[k]);
            g_string_append_c(out, ',');
        }
        g_string_append_printf(out, "%s,", js_fmt_num(buf, j->sim));
        g_string_append_printf(out, "%s,", js_fmt_num(buf, j->published));
        g_string_append(out, js_fmt_num(buf, j->rel_error));
        if (t->labelled)
            csv_labels(j, out);
        g_string_append_c(out, '\n');
    }
}

static void json_cell(JsonBuilder *b, const RpJoined *j)
{
    json_builder_begin_object(b);
    js_set_str(b, "table", j->table);
    js_set_str(b, "row", j->row);
    js_set_str(b, "column", j->column);
    js_set_str(b, "unit", j->unit);
    js_set_num(b, "sim", j->sim);
    js_set_num(b, "published", j->published);
    js_set_num(b, "rel_error", j->rel_error);
    js_set_str(b, "status", rp_status_name(j->status));
    js_set_str(b, "note", j->note);
    if (j->label != RP_LABEL_NONE) {
        js_set_str(b, "label", rp_label_name(j->label));
        js_set_str(b, "fitted_by", j->fitted_by);
        js_set_num(b, "loo_sim", j->loo_sim);
        js_set_num(b, "loo_rel_error", j->loo_rel_error);
        js_set_num(b, "interval_lo", j->lo);
        js_set_num(b, "interval_hi", j->hi);
    }
    json_builder_end_object(b);
}

/* The labelled headline's members (rp_table.h). */
static void json_headline(JsonBuilder *b, const RpTable *t)
{
    js_set_int(b, "out_of_sample_cells", t->oos_n);
    js_set_int(b, "out_of_sample_cross_validated", t->oos_cv);
    js_set_num(b, "out_of_sample_mean_abs_rel_error", t->oos_mean);
    js_set_num(b, "out_of_sample_worst_abs_rel_error", t->oos_worst);
    js_set_int(b, "in_sample_cells", t->ins_n);
    js_set_num(b, "in_sample_mean_abs_rel_error", t->ins_mean);
    js_set_num(b, "in_sample_worst_abs_rel_error", t->ins_worst);
    js_set_int(b, "leave_one_out_cells", t->loo_n);
    js_set_num(b, "leave_one_out_min_rel_error", t->loo_min);
    js_set_num(b, "leave_one_out_max_rel_error", t->loo_max);
    js_set_int(b, "inside_own_interval", t->inside);
    js_set_int(b, "inside_own_interval_of", t->inside_of);
}

static void json_summary(JsonBuilder *b, const RpTable *t)
{
    json_builder_set_member_name(b, "summary");
    json_builder_begin_object(b);
    js_set_int(b, "compared", t->compared);
    js_set_num(b, "mean_abs_rel_error", t->mean_abs);
    js_set_num(b, "worst_abs_rel_error", t->worst_abs);
    if (t->labelled)
        json_headline(b, t);
    json_builder_end_object(b);
}

JsonNode *rp_table_node(const RpTable *t)
{
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_str(b, "paper", t->paper);
    js_set_str(b, "citation", t->citation);
    js_set_str(b, "fidelity", t->fidelity);
    js_set_num(b, "wall_s", t->wall_s);
    SimProvenance p = rp_table_provenance(t);
    prov_json(b, &p);
    json_builder_set_member_name(b, "cells");
    json_builder_begin_array(b);
    for (guint i = 0; i < t->cells->len; i++)
        json_cell(b, g_ptr_array_index(t->cells, i));
    json_builder_end_array(b);
    json_summary(b, t);
    json_builder_end_object(b);
    JsonNode *root = json_builder_get_root(b);
    g_object_unref(b);
    return root;
}

void rp_table_json(const RpTable *t, GString *out)
{
    JsonNode *root = rp_table_node(t);
    char *text = js_text(root, FALSE);
    g_string_append(out, text);
    g_free(text);
    json_node_unref(root);
}
