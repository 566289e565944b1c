/* metrics.c — declared metrics: the runner's check of a result and reads
 * by a declared name (see metrics.h). */
#include "sim/workload/metrics.h"
#include "sim/core/error.h"
#include <string.h>

/* Does `name` match the declaration `decl`: the same name, or for a
 * family "NAME@P" any "NAME@<digits>"? */
static gboolean matches(const char *decl, const char *name)
{
    if (strcmp(decl, name) == 0)
        return TRUE;
    size_t n = strlen(decl);
    if (n < 2 || strcmp(decl + n - 2, "@P") != 0 ||
        strncmp(decl, name, n - 1) != 0 || !name[n - 1])
        return FALSE;
    for (const char *c = name + n - 1; *c; c++)
        if (!g_ascii_isdigit(*c))
            return FALSE;
    return TRUE;
}

const WlMetric *wl_metric_decl(const WlOps *ops, const char *name)
{
    for (const WlMetric *m = ops->metrics; m && m->name; m++)
        if (matches(m->name, name))
            return m;
    return NULL;
}

gboolean wl_check_metrics(const WlOps *ops, const SimResult *r,
                          GError **err)
{
    for (guint i = 0; i < r->metrics->len; i++) {
        const SimMetric *m = g_ptr_array_index(r->metrics, i);
        const WlMetric *d = wl_metric_decl(ops, m->name);
        if (d && strcmp(d->unit, m->unit) == 0)
            continue;
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "workload '%s': found metric '%s' (unit '%s'), expected "
                    "%s%s%s (a bug: each metric a workload sets is declared "
                    "in its WlOps.metrics)",
                    ops->name, m->name, m->unit,
                    d ? "its declared unit '" : "one it declares",
                    d ? d->unit : "", d ? "'" : "");
        return FALSE;
    }
    return TRUE;
}

/* r's workload's declaration of name; aborts when there is none. */
static void need_declared(const SimResult *r, const char *name)
{
    const WlOps *ops = r->workload ? wl_find(r->workload) : NULL;
    if (!ops || !wl_metric_decl(ops, name))
        g_error("metric '%s' read from a result of workload '%s', which "
                "does not declare it (WlOps.metrics; pgsim help run)",
                name, r->workload ? r->workload : "(none)");
}

double wl_metric(const SimResult *r, const char *name)
{
    need_declared(r, name);
    return sim_result_metric(r, name);
}

gboolean wl_get_metric(const SimResult *r, const char *name, double *value)
{
    need_declared(r, name);
    return sim_result_get_metric(r, name, value);
}
