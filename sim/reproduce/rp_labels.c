/* rp_labels.c — labelling a paper's cells from its labels.yaml
 * (rp_labels.h) and the headline that counts only out-of-sample cells.
 *
 * Invariants: a cell gets exactly one label; claims and leave-one-out
 * patterns take precedence over fits; a cross-validated cell's
 * leave-one-out value is a produced row, never a published one.  The
 * interval of a predicted cell is sim / (1 + e) over the range of the
 * leave-one-out errors e (the published value it admits), an honest
 * range only while the predicted cell is of the kind the fit was tested
 * on (docs/reproduction-format.md).  O(cells x (patterns + cells)).
 */
#include "sim/reproduce/rp_labels.h"
#include "sim/core/cfg.h"
#include <math.h>
#include <string.h>

typedef struct {
    char *table, *row, *column; /* globs */
} RpPattern;

typedef struct {
    char *constant;
    GPtrArray *cells; /* RpPattern * */
    RpPattern *loo;   /* templates with {table} {row} {column}; or NULL */
} RpFit;

struct RpLabels {
    GPtrArray *claims, *loo; /* RpPattern * */
    GPtrArray *fits;         /* RpFit * */
};

static void pattern_free(gpointer p)
{
    RpPattern *x = p;
    if (!x)
        return;
    g_free(x->table);
    g_free(x->row);
    g_free(x->column);
    g_free(x);
}

static void fit_free(gpointer p)
{
    RpFit *f = p;
    g_free(f->constant);
    g_ptr_array_free(f->cells, TRUE);
    pattern_free(f->loo);
    g_free(f);
}

void rp_labels_free(RpLabels *l)
{
    if (!l)
        return;
    g_ptr_array_free(l->claims, TRUE);
    g_ptr_array_free(l->loo, TRUE);
    g_ptr_array_free(l->fits, TRUE);
    g_free(l);
}

static RpPattern *pattern_read(const CfgNode *n, GError **err)
{
    const char *t = NULL, *r = "*", *c = "*";
    if (cfg_kind(n) != CFG_MAP) {
        cfg_error(err, n, "a non-map cell pattern",
                  "{table: T, row: R, column: C}");
        return NULL;
    }
    if (!cfg_get_str(n, "table", TRUE, &t, err) ||
        !cfg_get_str(n, "row", FALSE, &r, err) ||
        !cfg_get_str(n, "column", FALSE, &c, err) ||
        !cfg_check_unused(n, err))
        return NULL;
    RpPattern *p = g_new0(RpPattern, 1);
    p->table = g_strdup(t);
    p->row = g_strdup(r);
    p->column = g_strdup(c);
    return p;
}

/* A list of patterns under key (absent: empty). */
static gboolean patterns_read(const CfgNode *map, const char *key,
                              GPtrArray *out, GError **err)
{
    const CfgNode *seq = cfg_get(map, key);
    if (!seq)
        return TRUE;
    if (cfg_kind(seq) != CFG_SEQ) {
        cfg_error(err, seq, "a non-list", "a list of cell patterns");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        RpPattern *p = pattern_read(cfg_seq_at(seq, i), err);
        if (!p)
            return FALSE;
        g_ptr_array_add(out, p);
    }
    return TRUE;
}

static RpFit *fit_read(const CfgNode *n, GError **err)
{
    const char *k = NULL;
    if (cfg_kind(n) != CFG_MAP) {
        cfg_error(err, n, "a non-map fit", "{constant, cells, loo}");
        return NULL;
    }
    if (!cfg_get_str(n, "constant", TRUE, &k, err))
        return NULL;
    RpFit *f = g_new0(RpFit, 1);
    f->constant = g_strdup(k);
    f->cells = g_ptr_array_new_with_free_func(pattern_free);
    const CfgNode *loo = cfg_get(n, "loo");
    gboolean ok = patterns_read(n, "cells", f->cells, err);
    if (ok && f->cells->len == 0) {
        cfg_error(err, n, "a fit without cells", "cells: [patterns]");
        ok = FALSE;
    }
    if (ok && loo)
        ok = (f->loo = pattern_read(loo, err)) != NULL;
    if (!ok || !cfg_check_unused(n, err)) {
        fit_free(f);
        return NULL;
    }
    return f;
}

static gboolean fits_read(const CfgNode *root, RpLabels *l, GError **err)
{
    const CfgNode *seq = cfg_get(root, "fits");
    if (seq && cfg_kind(seq) != CFG_SEQ) {
        cfg_error(err, seq, "a non-list fits", "a list of fits");
        return FALSE;
    }
    for (guint i = 0; seq && i < cfg_seq_len(seq); i++) {
        RpFit *f = fit_read(cfg_seq_at(seq, i), err);
        if (!f)
            return FALSE;
        g_ptr_array_add(l->fits, f);
    }
    return TRUE;
}

RpLabels *rp_labels_load(const char *path, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return NULL;
    RpLabels *l = g_new0(RpLabels, 1);
    l->claims = g_ptr_array_new_with_free_func(pattern_free);
    l->loo = g_ptr_array_new_with_free_func(pattern_free);
    l->fits = g_ptr_array_new_with_free_func(fit_free);
    gboolean ok = cfg_kind(root) == CFG_MAP;
    if (!ok)
        cfg_error(err, root, "a non-map labels file",
                  "{claims, leave_one_out, fits}");
    ok = ok && patterns_read(root, "claims", l->claims, err) &&
         patterns_read(root, "leave_one_out", l->loo, err) &&
         fits_read(root, l, err) && cfg_check_unused(root, err);
    cfg_free(root);
    if (!ok) {
        rp_labels_free(l);
        return NULL;
    }
    return l;
}

/* ---- labelling ------------------------------------------------------- */

static gboolean matches(const RpPattern *p, const RpJoined *j)
{
    return g_pattern_match_simple(p->table, j->table) &&
           g_pattern_match_simple(p->row, j->row) &&
           g_pattern_match_simple(p->column, j->column);
}

static gboolean any_match(const GPtrArray *ps, const RpJoined *j)
{
    for (guint i = 0; i < ps->len; i++)
        if (matches(g_ptr_array_index(ps, i), j))
            return TRUE;
    return FALSE;
}

/* tmpl with {table}, {row} and {column} replaced by j's. */
static char *expand(const char *tmpl, const RpJoined *j)
{
    const char *keys[] = {"{table}", "{row}", "{column}"};
    const char *vals[] = {j->table, j->row, j->column};
    GString *s = g_string_new(tmpl);
    for (int k = 0; k < 3; k++)
        g_string_replace(s, keys[k], vals[k], 0);
    return g_string_free(s, FALSE);
}

static void find_loo(const RpFit *f, const RpTable *t, RpJoined *j)
{
    char *tb = expand(f->loo->table, j), *r = expand(f->loo->row, j);
    char *c = expand(f->loo->column, j);
    const RpJoined *x = rp_table_find(t, tb, r, c);
    if (x && isfinite(x->sim)) {
        j->loo_sim = x->sim;
        if (isfinite(j->published) && j->published != 0.0)
            j->loo_rel_error = (x->sim - j->published) / j->published;
    }
    g_free(tb);
    g_free(r);
    g_free(c);
}

static void label_fitted(const RpLabels *l, const RpTable *t, RpJoined *j)
{
    GString *by = g_string_new(NULL);
    for (guint i = 0; i < l->fits->len; i++) {
        const RpFit *f = g_ptr_array_index(l->fits, i);
        if (!any_match(f->cells, j))
            continue;
        g_string_append_printf(by, "%s%s", by->len ? "; " : "", f->constant);
        if (f->loo && !isfinite(j->loo_sim))
            find_loo(f, t, j);
    }
    if (!by->len) {
        g_string_free(by, TRUE);
        j->label = RP_LABEL_PREDICTED;
        return;
    }
    j->fitted_by = g_string_free(by, FALSE);
    j->label = isfinite(j->loo_sim) ? RP_LABEL_CV : RP_LABEL_FITTED;
}

static void label_one(const RpLabels *l, const RpTable *t, RpJoined *j)
{
    j->loo_sim = j->loo_rel_error = j->lo = j->hi = NAN;
    if (any_match(l->claims, j))
        j->label = RP_LABEL_CLAIM;
    else if (any_match(l->loo, j))
        j->label = RP_LABEL_LOO;
    else
        label_fitted(l, t, j);
}

/* ---- headline -------------------------------------------------------- */

typedef struct {
    guint n;
    double sum, worst;
    int worst_i;
} Acc;

static void acc_add(Acc *a, double e, guint i)
{
    double x = fabs(e);
    a->sum += x;
    a->n++;
    if (a->worst_i < 0 || x > a->worst) {
        a->worst = x;
        a->worst_i = (int)i;
    }
}

/* The cell's out-of-sample error: NAN when it has none. */
static double oos_error(const RpJoined *j)
{
    if (j->label == RP_LABEL_PREDICTED)
        return j->rel_error;
    return j->label == RP_LABEL_CV ? j->loo_rel_error : NAN;
}

static void headline(RpTable *t)
{
    Acc o = {0, 0, NAN, -1}, in = {0, 0, NAN, -1};
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        double e = oos_error(j);
        if (isfinite(e)) {
            acc_add(&o, e, i);
            t->oos_cv += j->label == RP_LABEL_CV;
        }
        gboolean fit = j->label == RP_LABEL_FITTED || j->label == RP_LABEL_CV;
        if (fit && isfinite(j->rel_error))
            acc_add(&in, j->rel_error, i);
    }
    t->oos_n = o.n;
    t->oos_mean = o.n ? o.sum / o.n : NAN;
    t->oos_worst = o.worst;
    t->oos_worst_i = o.worst_i;
    t->ins_n = in.n;
    t->ins_mean = in.n ? in.sum / in.n : NAN;
    t->ins_worst = in.worst;
    t->ins_worst_i = in.worst_i;
}

/* Range of the cross-validated cells' leave-one-out errors, without
 * cell `skip` (-1: none); FALSE when fewer than two remain. */
static gboolean loo_range(const RpTable *t, int skip, double *lo, double *hi)
{
    guint n = 0;
    *lo = INFINITY;
    *hi = -INFINITY;
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        if ((int)i == skip || j->label != RP_LABEL_CV ||
            !isfinite(j->loo_rel_error))
            continue;
        *lo = MIN(*lo, j->loo_rel_error);
        *hi = MAX(*hi, j->loo_rel_error);
        n++;
    }
    return n >= 2;
}

/* The published value sim / (1 + e) admits over e in [lo, hi]. */
static void interval(RpJoined *j, double centre, double lo, double hi)
{
    if (!isfinite(centre))
        return;
    double a = centre / (1.0 + hi);
    double b = 1.0 + lo > 0 ? centre / (1.0 + lo) : INFINITY * centre;
    j->lo = MIN(a, b);
    j->hi = MAX(a, b);
}

static void intervals(RpTable *t)
{
    double lo, hi;
    t->loo_min = t->loo_max = NAN;
    if (!loo_range(t, -1, &lo, &hi))
        return;
    t->loo_min = lo;
    t->loo_max = hi;
    for (guint i = 0; i < t->cells->len; i++) {
        RpJoined *j = g_ptr_array_index(t->cells, i);
        double e = oos_error(j), l = lo, h = hi;
        gboolean known = j->status == RP_COMPARED || j->status == RP_WITHHELD;
        if (j->label == RP_LABEL_CV && !loo_range(t, (int)i, &l, &h))
            continue;
        if (j->label == RP_LABEL_PREDICTED && known)
            interval(j, j->sim, l, h);
        else if (j->label == RP_LABEL_CV)
            interval(j, j->loo_sim, l, h);
        if (!isfinite(e))
            continue;
        t->inside_of++;
        t->inside += e >= l && e <= h;
    }
}

void rp_labels_apply(const RpLabels *l, RpTable *t)
{
    for (guint i = 0; i < t->cells->len; i++)
        label_one(l, t, g_ptr_array_index(t->cells, i));
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        t->loo_n += j->label == RP_LABEL_CV && isfinite(j->loo_rel_error);
    }
    t->labelled = TRUE;
    headline(t);
    intervals(t);
}

/* ---- names ----------------------------------------------------------- */

const char *rp_label_name(RpLabel l)
{
    static const char *const names[] = {"",      "fitted",
                                        "cross-validated", "predicted",
                                        "claim", "leave-one-out"};
    g_assert((unsigned)l < G_N_ELEMENTS(names));
    return names[l];
}

char *rp_label_text(const RpJoined *j)
{
    GString *s = g_string_new(rp_label_name(j->label));
    if (j->label == RP_LABEL_FITTED)
        g_string_append_printf(s, " (%s)", j->fitted_by);
    if (j->label == RP_LABEL_CV) {
        g_string_append_printf(s, ": left out %.4g", j->loo_sim);
        if (isfinite(j->loo_rel_error))
            g_string_append_printf(s, " (%+.1f%%)", 100 * j->loo_rel_error);
    }
    if (isfinite(j->lo))
        g_string_append_printf(s, ", in [%.4g, %.4g]", j->lo, j->hi);
    return g_string_free(s, FALSE);
}
