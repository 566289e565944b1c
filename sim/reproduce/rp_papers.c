/* rp_papers.c — published values of a paper, read from YAML.
 *
 * Two shapes (docs/reproduction-format.md), which may be mixed:
 *     paper: kurc96                  # or {name: kurc96, citation: "..."}
 *     citation: "..."
 *     tables:                        # compact: ~ marks a withheld cell
 *       "2":
 *         caption: "Table 2. ..."
 *         rows:
 *           P16/2POT: {merge_ms: 341, span_ms: ~,
 *                      zbuf_ms: {value: 471, unit: ms, note: "..."}}
 *     cells:                         # one cell per list item
 *       - {table: "2", row: 2POT, column: tpg_400, value: 1.25, unit: s}
 *       - {table: "2", row: BS, column: tpg_400, withheld: true, note: ...}
 * Invariants: every cell has a value xor withheld: true; (table, row,
 * column) is unique.  Unknown keys are rejected with their location.
 * Loading is O(cells).
 */
#include "sim/reproduce/rp_papers.h"
#include "sim/core/datapath.h"
#include "sim/core/cfg.h"
#include <float.h>
#include <math.h>

static char *cell_key(const char *t, const char *r, const char *c)
{
    return g_strjoin("\x1f", t, r, c, NULL);
}

static void cell_free(gpointer p)
{
    RpCell *c = p;
    g_free(c->table);
    g_free(c->row);
    g_free(c->column);
    g_free(c->unit);
    g_free(c->note);
    g_free(c);
}

void rp_paper_free(RpPaper *p)
{
    if (!p)
        return;
    g_free(p->name);
    g_free(p->citation);
    g_ptr_array_free(p->cells, TRUE);
    g_hash_table_destroy(p->index);
    g_hash_table_destroy(p->captions);
    g_free(p);
}

static gboolean read_key_fields(const CfgNode *n, RpCell *c, GError **err)
{
    const char *t = NULL, *r = NULL, *col = NULL, *unit = "", *note = NULL;
    if (!cfg_get_str(n, "table", TRUE, &t, err) ||
        !cfg_get_str(n, "row", TRUE, &r, err) ||
        !cfg_get_str(n, "column", TRUE, &col, err) ||
        !cfg_get_str(n, "unit", FALSE, &unit, err) ||
        !cfg_get_str(n, "note", FALSE, &note, err))
        return FALSE;
    c->table = g_strdup(t);
    c->row = g_strdup(r);
    c->column = g_strdup(col);
    c->unit = g_strdup(unit);
    c->note = g_strdup(note);
    return TRUE;
}

static gboolean read_value(const CfgNode *n, RpCell *c, GError **err)
{
    c->value = NAN;
    if (!cfg_get_bool(n, "withheld", FALSE, &c->withheld, err))
        return FALSE;
    const CfgNode *v = cfg_get(n, "value");
    if (c->withheld && v) {
        cfg_error(err, v, "a value in a withheld cell",
                  "either 'value' or 'withheld: true'");
        return FALSE;
    }
    if (!c->withheld && !v) {
        cfg_error(err, n, "a cell without a value",
                  "'value: <number>' or 'withheld: true'");
        return FALSE;
    }
    return c->withheld ||
           cfg_get_double(n, "value", TRUE, -DBL_MAX, DBL_MAX, &c->value, err);
}

static RpCell *read_cell(const CfgNode *n, GError **err)
{
    if (cfg_kind(n) != CFG_MAP) {
        cfg_error(err, n, "a non-map cell",
                  "a map {table, row, column, value | withheld}");
        return NULL;
    }
    RpCell *c = g_new0(RpCell, 1);
    if (!read_key_fields(n, c, err) || !read_value(n, c, err)) {
        cell_free(c);
        return NULL;
    }
    return c;
}

static gboolean add_cell(RpPaper *p, const CfgNode *n, RpCell *c, GError **err)
{
    char *key = cell_key(c->table, c->row, c->column);
    if (g_hash_table_contains(p->index, key)) {
        char *what = g_strdup_printf("a second cell (%s, %s, %s)", c->table,
                                     c->row, c->column);
        cfg_error(err, n, what, "each (table, row, column) once");
        g_free(what);
        g_free(key);
        cell_free(c);
        return FALSE;
    }
    g_hash_table_insert(p->index, key, c);
    g_ptr_array_add(p->cells, c);
    return TRUE;
}

static gboolean read_cells(RpPaper *p, const CfgNode *seq, GError **err)
{
    if (cfg_kind(seq) != CFG_SEQ) {
        cfg_error(err, seq, "a non-list 'cells'", "a list of cells");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const CfgNode *n = cfg_seq_at(seq, i);
        RpCell *c = read_cell(n, err);
        if (!c || !add_cell(p, n, c, err))
            return FALSE;
    }
    return TRUE;
}

static gboolean read_header(RpPaper *p, const CfgNode *root, GError **err)
{
    const CfgNode *hdr = cfg_get(root, "paper");
    const char *name = NULL, *cit = "";
    if (hdr && cfg_kind(hdr) == CFG_SCALAR) {
        name = cfg_scalar(hdr);
    } else if (!hdr || cfg_kind(hdr) != CFG_MAP) {
        cfg_error(err, hdr ? hdr : root,
                  hdr ? "a list 'paper'" : "no 'paper' key",
                  "paper: NAME or paper: {name, citation}");
        return FALSE;
    } else if (!cfg_get_str(hdr, "name", TRUE, &name, err) ||
               !cfg_get_str(hdr, "citation", FALSE, &cit, err)) {
        return FALSE;
    }
    if (!cfg_get_str(root, "citation", FALSE, &cit, err))
        return FALSE;
    p->name = g_strdup(name);
    p->citation = g_strdup(cit);
    return TRUE;
}

static gboolean scalar_number(const CfgNode *v, double *out, GError **err)
{
    const char *text = cfg_scalar(v);
    char *end = NULL;
    *out = g_ascii_strtod(text, &end);
    if (end == text || *end || !isfinite(*out)) {
        char *found = g_strdup_printf("'%s'", text);
        cfg_error(err, v, found, "a number or ~ (withheld)");
        g_free(found);
        return FALSE;
    }
    return TRUE;
}

/* A compact cell: a number, ~ (withheld) or {value|withheld, unit, note}. */
static RpCell *compact_cell(const char *t, const char *r, const char *c,
                            const CfgNode *v, GError **err)
{
    RpCell *cell = g_new0(RpCell, 1);
    cell->table = g_strdup(t);
    cell->row = g_strdup(r);
    cell->column = g_strdup(c);
    cell->value = NAN;
    const char *unit = "", *note = NULL;
    gboolean ok = TRUE;
    if (cfg_kind(v) == CFG_NULL)
        cell->withheld = TRUE;
    else if (cfg_kind(v) == CFG_MAP)
        ok = cfg_get_str(v, "unit", FALSE, &unit, err) &&
             cfg_get_str(v, "note", FALSE, &note, err) &&
             read_value(v, cell, err);
    else if (cfg_kind(v) == CFG_SCALAR)
        ok = scalar_number(v, &cell->value, err);
    else {
        cfg_error(err, v, "a list", "a number, ~ or {value, unit, note}");
        ok = FALSE;
    }
    cell->unit = g_strdup(unit);
    cell->note = g_strdup(note);
    if (!ok) {
        cell_free(cell);
        return NULL;
    }
    return cell;
}

static gboolean need_map(const CfgNode *n, const char *what, GError **err)
{
    if (n && cfg_kind(n) == CFG_MAP)
        return TRUE;
    char *exp = g_strdup_printf("a map (%s)", what);
    cfg_error(err, n, n ? "something else" : "nothing", exp);
    g_free(exp);
    return FALSE;
}

static gboolean read_row(RpPaper *p, const char *t, const char *r,
                         const CfgNode *cols, GError **err)
{
    if (!need_map(cols, "column: value", err))
        return FALSE;
    for (guint i = 0; i < cfg_map_len(cols); i++) {
        const CfgNode *v = cfg_map_value(cols, i);
        RpCell *c = compact_cell(t, r, cfg_map_key(cols, i), v, err);
        if (!c || !add_cell(p, v, c, err))
            return FALSE;
    }
    return TRUE;
}

static gboolean read_table(RpPaper *p, const char *t, const CfgNode *tab,
                           GError **err)
{
    const char *caption = NULL;
    if (!need_map(tab, "caption, rows", err) ||
        !cfg_get_str(tab, "caption", FALSE, &caption, err))
        return FALSE;
    const CfgNode *rows = cfg_get(tab, "rows");
    if (rows && !need_map(rows, "rows: {ROW: {COLUMN: value}}", err))
        return FALSE;
    if (caption)
        g_hash_table_insert(p->captions, g_strdup(t), g_strdup(caption));
    for (guint i = 0; rows && i < cfg_map_len(rows); i++)
        if (!read_row(p, t, cfg_map_key(rows, i), cfg_map_value(rows, i), err))
            return FALSE;
    return TRUE;
}

static gboolean read_tables(RpPaper *p, const CfgNode *tabs, GError **err)
{
    if (!need_map(tabs, "TABLE: {caption, rows}", err))
        return FALSE;
    for (guint i = 0; i < cfg_map_len(tabs); i++)
        if (!read_table(p, cfg_map_key(tabs, i), cfg_map_value(tabs, i), err))
            return FALSE;
    return TRUE;
}

static gboolean read_paper(RpPaper *p, const CfgNode *root, GError **err)
{
    if (cfg_kind(root) != CFG_MAP) {
        cfg_error(err, root, "a document that is not a map",
                  "a map with 'paper' and 'tables' or 'cells'");
        return FALSE;
    }
    if (!read_header(p, root, err))
        return FALSE;
    const CfgNode *tabs = cfg_get(root, "tables");
    const CfgNode *cells = cfg_get(root, "cells");
    if (!tabs && !cells) {
        cfg_error(err, root, "neither 'tables' nor 'cells'",
                  "the published values");
        return FALSE;
    }
    return (!tabs || read_tables(p, tabs, err)) &&
           (!cells || read_cells(p, cells, err)) && cfg_check_unused(root, err);
}

RpPaper *rp_paper_load(const char *path, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return NULL;
    RpPaper *p = g_new0(RpPaper, 1);
    p->cells = g_ptr_array_new_with_free_func(cell_free);
    p->index = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, NULL);
    p->captions =
        g_hash_table_new_full(g_str_hash, g_str_equal, g_free, g_free);
    gboolean ok = read_paper(p, root, err);
    cfg_free(root);
    if (!ok) {
        rp_paper_free(p);
        return NULL;
    }
    return p;
}

const RpCell *rp_paper_cell(const RpPaper *p, const char *table,
                            const char *row, const char *column)
{
    char *key = cell_key(table, row, column);
    const RpCell *c = g_hash_table_lookup(p->index, key);
    g_free(key);
    return c;
}

char *rp_paper_file(const char *dir, const char *name, const char *file)
{
    char *rel = g_build_filename(dir, name, file, NULL);
    char *path = sim_data_path(rel);
    g_free(rel);
    return path;
}

char *rp_paper_path(const char *dir, const char *name)
{
    return rp_paper_file(dir, name, RP_PUBLISHED_FILE);
}
