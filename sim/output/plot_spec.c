/* plot_spec.c — what a chart is: a PlotSpec's lifecycle and its reading
 * from a config's `plots:` list (sweeps, papers, `pgsim plot`), with the
 * name and `where:` checks.  Split from plot.c, which groups rows and
 * draws.  O(keys) each.
 */
#include "sim/output/plot.h"
#include <string.h>

PlotSpec *plot_spec_new(const char *name, const char *x, const char *y)
{
    PlotSpec *p = g_new0(PlotSpec, 1);
    p->name = g_strdup(name);
    p->x = g_strdup(x);
    p->y = g_strdup(y);
    p->style = g_strdup("linespoints");
    return p;
}

void plot_spec_free(gpointer spec)
{
    PlotSpec *p = spec;
    if (!p)
        return;
    g_free(p->name);
    g_free(p->x);
    g_free(p->y);
    g_free(p->series);
    g_free(p->title);
    g_free(p->xlabel);
    g_free(p->ylabel);
    g_free(p->style);
    g_free(p->where);
    g_free(p);
}

/* ---- reading specs --------------------------------------------------- */

static gboolean opt_str(const CfgNode *m, const char *key, char **out,
                        GError **err)
{
    const char *s = NULL;
    if (!cfg_get_str(m, key, FALSE, &s, err))
        return FALSE;
    if (s) {
        g_free(*out);
        *out = g_strdup(s);
    }
    return TRUE;
}

gboolean plot_cfg_name_ok(const CfgNode *at, const char *what,
                          const char *name, GError **err)
{
    if (plot_name_ok(name))
        return TRUE;
    char *shown = plot_printable(name);
    char *found = g_strdup_printf("the %s name '%s'", what, shown);
    cfg_error(err, at, found, PLOT_NAME_RULE);
    g_free(found);
    g_free(shown);
    return FALSE;
}

/* A sweep chart's optional `where: {COLUMN: VALUE, ...}`: the rows it
 * keeps, as p->where "K=V, K=V" (the sweep filters them). */
static gboolean read_where(const CfgNode *m, PlotSpec *p, GError **err)
{
    const CfgNode *w = NULL;
    if (!cfg_get_map(m, "where", FALSE, "a map {COLUMN: VALUE, ...}", &w, err))
        return FALSE;
    GString *s = g_string_new("");
    for (guint i = 0; w && i < cfg_map_len(w); i++) {
        const char *v = cfg_scalar(cfg_map_value(w, i));
        if (!v) {
            cfg_error(err, cfg_map_value(w, i), "a non-scalar 'where' value",
                      "a value of the column");
            g_string_free(s, TRUE);
            return FALSE;
        }
        g_string_append_printf(s, "%s%s=%s", i ? ", " : "",
                               cfg_map_key(w, i), v);
    }
    p->where = s->len ? g_string_free(s, FALSE) : NULL;
    if (!p->where)
        g_string_free(s, TRUE);
    return TRUE;
}

static PlotSpec *read_spec(const CfgNode *m, guint i, GError **err)
{
    static const char *const styles[] = {"linespoints", "points", "lines",
                                         NULL};
    const char *x = NULL, *y = NULL;
    int style = 0;
    if (!cfg_get_str(m, "x", TRUE, &x, err) ||
        !cfg_get_str(m, "y", TRUE, &y, err) ||
        !cfg_get_enum(m, "style", FALSE, styles, &style, err))
        return NULL;
    char *name = g_strdup_printf("plot%u", i + 1);
    PlotSpec *p = plot_spec_new(name, x, y);
    g_free(name);
    g_free(p->style);
    p->style = g_strdup(styles[style]);
    if (opt_str(m, "name", &p->name, err) &&
        plot_cfg_name_ok(cfg_get(m, "name"), "plot", p->name, err) &&
        opt_str(m, "series", &p->series, err) &&
        opt_str(m, "title", &p->title, err) &&
        opt_str(m, "xlabel", &p->xlabel, err) &&
        opt_str(m, "ylabel", &p->ylabel, err) &&
        cfg_get_bool(m, "logx", FALSE, &p->logx, err) &&
        cfg_get_bool(m, "logy", FALSE, &p->logy, err) &&
        read_where(m, p, err) && cfg_check_unused(m, err))
        return p;
    plot_spec_free(p);
    return NULL;
}

gboolean plot_specs_read(GPtrArray *specs, const CfgNode *seq, GError **err)
{
    if (cfg_kind(seq) != CFG_SEQ) {
        cfg_error(err, seq, "a non-list 'plots'", "a list of {x, y, ...}");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++) {
        const CfgNode *m = cfg_seq_at(seq, i);
        if (cfg_kind(m) != CFG_MAP) {
            cfg_error(err, m, "a plot that is not a map",
                      "{x, y, series, logx, logy, title, ...}");
            return FALSE;
        }
        PlotSpec *p = read_spec(m, i, err);
        if (!p)
            return FALSE;
        g_ptr_array_add(specs, p);
    }
    return TRUE;
}
