/* ellsworth90_cv.c — ellsworth90's leave-one-out values as table `cv`
 * rows, read from configs/papers/ellsworth90/loo.yaml (beside the setup
 * file): the stored result of scripts/ellsworth90/fit.py --loo, which
 * refits the five fitted constants without each of the 12 fitted cells
 * (each refit is ~80 full reproductions, too slow to run here).
 *
 * Rows: cv/<db>/loo_<column> for each left-out cell (labels.yaml's
 * `loo:` template points at them), and cv/<db>/refit_min_<column> and
 * refit_max_<column> for each predicted cell over the 12 refits.  No
 * loo.yaml beside the setup (another setup): no rows.  A refit's
 * `fitted` value is the cell at the constants the refits started from;
 * when this reproduction gives another value (the constants or the model
 * changed since), the file is stale: one row cv/loo.yaml/stale and no
 * leave-one-out values, so the cells fall back to `fitted`.
 * O(refits x (rows + predicted cells)).
 */
#include "sim/reproduce/ellsworth90.h"
#include <math.h>
#include <string.h>

static void add(GPtrArray *rows, const char *row, const char *col, double v,
                const char *note)
{
    g_ptr_array_add(rows, rp_row_new("cv", row, col, v, note));
}

/* One refit's predicted cells (its `predicted` list) into the running min and
 * max (keyed by "row\tcolumn"). */
static gboolean spread_read(const CfgNode *refit, GHashTable *lo,
                            GHashTable *hi, GError **err)
{
    const CfgNode *seq = cfg_get(refit, "predicted");
    if (!seq || cfg_kind(seq) != CFG_SEQ) {
        cfg_error(err, seq ? seq : refit, "no list of predicted cells",
                  "predicted: [{row, column, value}]");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const CfgNode *n = cfg_seq_at(seq, i);
        const char *r = NULL, *c = NULL;
        double v = NAN;
        if (cfg_kind(n) != CFG_MAP) {
            cfg_error(err, n, "a non-map predicted cell",
                      "{row, column, value}");
            return FALSE;
        }
        if (!cfg_get_str(n, "row", TRUE, &r, err) ||
            !cfg_get_str(n, "column", TRUE, &c, err) ||
            !cfg_get_double(n, "value", TRUE, 0, G_MAXDOUBLE, &v, err))
            return FALSE;
        char *k = g_strdup_printf("%s\t%s", r, c);
        double *l = g_hash_table_lookup(lo, k), *h = g_hash_table_lookup(hi, k);
        if (!l) {
            l = g_new(double, 1);
            h = g_new(double, 1);
            *l = *h = v;
            g_hash_table_insert(lo, g_strdup(k), l);
            g_hash_table_insert(hi, g_strdup(k), h);
        }
        *l = MIN(*l, v);
        *h = MAX(*h, v);
        g_free(k);
    }
    return TRUE;
}

/* The sim of table 1's (row, column) among rows; NAN when absent. */
static double table1_sim(const GPtrArray *rows, const char *row,
                         const char *col)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *x = g_ptr_array_index(rows, i);
        if (strcmp(x->table, "1") == 0 && strcmp(x->row, row) == 0 &&
            strcmp(x->column, col) == 0)
            return x->sim;
    }
    return NAN;
}

/* One refit: its loo row into out, its predicted cells into lo and hi;
 * *stale set when the cell's `fitted` is not what rows give. */
static gboolean refit_read(const CfgNode *n, const GPtrArray *rows,
                           GPtrArray *out_rows, GHashTable *lo, GHashTable *hi,
                           gboolean *stale, GError **err)
{
    const CfgNode *out = NULL;
    const char *t = NULL, *r = NULL, *c = NULL;
    double loo = NAN, fitted = NAN;
    if (cfg_kind(n) != CFG_MAP) {
        cfg_error(err, n, "a non-map refit",
                  "{left_out, published, loo, constants, predicted}");
        return FALSE;
    }
    if (!cfg_get_map(n, "left_out", TRUE, "a cell {table, row, column}", &out,
                     err) ||
        !cfg_get_str(out, "table", TRUE, &t, err) ||
        !cfg_get_str(out, "row", TRUE, &r, err) ||
        !cfg_get_str(out, "column", TRUE, &c, err) ||
        !cfg_get_double(n, "loo", TRUE, 0, G_MAXDOUBLE, &loo, err) ||
        !cfg_get_double(n, "fitted", TRUE, 0, G_MAXDOUBLE, &fitted, err))
        return FALSE;
    double now = table1_sim(rows, r, c);
    if (!(fabs(now - fitted) <= 1e-5 * fabs(fitted)))
        *stale = TRUE;
    cfg_mark_read(cfg_get(n, "published")); /* for the reader */
    cfg_mark_read(cfg_get(n, "constants"));
    if (!spread_read(n, lo, hi, err))
        return FALSE;
    char *col = g_strdup_printf("loo_%s", c);
    add(out_rows, r, col, loo, "refit without this cell (loo.yaml)");
    g_free(col);
    return TRUE;
}

/* The spread rows, in a deterministic order. */
static void spread_rows(GHashTable *lo, GHashTable *hi, GPtrArray *rows)
{
    GList *keys =
        g_list_sort(g_hash_table_get_keys(lo), (GCompareFunc)g_strcmp0);
    for (GList *k = keys; k; k = k->next) {
        char **rc = g_strsplit(k->data, "\t", 2);
        char *mn = g_strdup_printf("refit_min_%s", rc[1]);
        char *mx = g_strdup_printf("refit_max_%s", rc[1]);
        const char *note = "over the 12 leave-one-out refits (loo.yaml)";
        add(rows, rc[0], mn, *(double *)g_hash_table_lookup(lo, k->data), note);
        add(rows, rc[0], mx, *(double *)g_hash_table_lookup(hi, k->data), note);
        g_free(mn);
        g_free(mx);
        g_strfreev(rc);
    }
    g_list_free(keys);
}

gboolean rp_ellsworth90_loo(const char *setup, GPtrArray *rows, GError **err)
{
    char *dir = g_path_get_dirname(setup);
    char *path = g_build_filename(dir, "loo.yaml", NULL);
    g_free(dir);
    if (!g_file_test(path, G_FILE_TEST_EXISTS)) {
        g_free(path);
        return TRUE;
    }
    CfgNode *root = cfg_load_file(path, err);
    g_free(path);
    if (!root)
        return FALSE;
    GHashTable *lo =
        g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    GHashTable *hi =
        g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    const CfgNode *seq =
        cfg_kind(root) == CFG_MAP ? cfg_get(root, "refits") : NULL;
    GPtrArray *loo = g_ptr_array_new_with_free_func(rp_row_free);
    gboolean ok = seq && cfg_kind(seq) == CFG_SEQ, stale = FALSE;
    if (!ok)
        cfg_error(err, seq ? seq : root, "no list of refits",
                  "refits: [{left_out, loo, predicted}]");
    for (guint i = 0; ok && i < cfg_seq_len(seq); i++)
        ok = refit_read(cfg_seq_at(seq, i), rows, loo, lo, hi, &stale, err);
    ok = ok && cfg_check_unused(root, err);
    if (ok && stale)
        add(rows, "loo.yaml", "stale", 1,
            "the fitted cells moved since loo.yaml was made: regenerate "
            "it with python3 scripts/ellsworth90/fit.py --loo");
    if (ok && !stale) {
        g_ptr_array_extend_and_steal(rows, loo);
        loo = NULL;
        spread_rows(lo, hi, rows);
    }
    if (loo)
        g_ptr_array_free(loo, TRUE);
    g_hash_table_destroy(lo);
    g_hash_table_destroy(hi);
    cfg_free(root);
    return ok;
}
