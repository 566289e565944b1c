/* papers.c — published values of a paper, read from YAML.
 *
 * Shape (docs/reproduction-format.md):
 *     paper: {name: kurc96, citation: "..."}
 *     cells:
 *       - {table: "2", row: 2POT, column: tpg_400, value: 1.25, unit: s}
 *       - {table: "2", row: BS, column: tpg_400, withheld: true, note: ...}
 * Invariants: every cell has a value xor withheld: true; (table, row,
 * column) is unique.  Unknown keys are rejected with their location.
 * Loading is O(cells).
 */
#include "sim/app/papers.h"
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
           cfg_get_double(n, "value", TRUE, -DBL_MAX, DBL_MAX, &c->value,
                          err);
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

static gboolean add_cell(RpPaper *p, const CfgNode *n, RpCell *c,
                         GError **err)
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
    if (!hdr || cfg_kind(hdr) != CFG_MAP) {
        cfg_error(err, hdr ? hdr : root, hdr ? "a non-map 'paper'"
                                             : "no 'paper' section",
                  "paper: {name, citation}");
        return FALSE;
    }
    if (!cfg_get_str(hdr, "name", TRUE, &name, err) ||
        !cfg_get_str(hdr, "citation", FALSE, &cit, err))
        return FALSE;
    p->name = g_strdup(name);
    p->citation = g_strdup(cit);
    return TRUE;
}

static gboolean read_paper(RpPaper *p, const CfgNode *root, GError **err)
{
    if (cfg_kind(root) != CFG_MAP) {
        cfg_error(err, root, "a document that is not a map",
                  "a map with 'paper' and 'cells'");
        return FALSE;
    }
    if (!read_header(p, root, err))
        return FALSE;
    const CfgNode *cells = cfg_get(root, "cells");
    if (!cells) {
        cfg_error(err, root, "no 'cells' list", "cells: [...]");
        return FALSE;
    }
    return read_cells(p, cells, err) && cfg_check_unused(root, err);
}

RpPaper *rp_paper_load(const char *path, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return NULL;
    RpPaper *p = g_new0(RpPaper, 1);
    p->cells = g_ptr_array_new_with_free_func(cell_free);
    p->index = g_hash_table_new_full(g_str_hash, g_str_equal, g_free, NULL);
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

char *rp_paper_path(const char *dir, const char *name)
{
    char *file = g_strconcat(name, ".yaml", NULL);
    char *path = g_build_filename(dir, file, NULL);
    g_free(file);
    return path;
}
