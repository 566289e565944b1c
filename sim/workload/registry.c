/* registry.c — the table of workloads (one row per workload). */
#include "sim/workload/workload.h"
#include "sim/workload/argus/ag_workload.h"
#include "sim/workload/dpscan/dp_workload.h"
#include "sim/workload/pixelmerge/pm_workload.h"
#include "sim/workload/sortfirst/sf_workload.h"
#include "sim/workload/tokenring/tokenring_workload.h"
#include <string.h>

extern const WlOps wl_pphigs_ops;

const WlOps *const wl_all[] = {
    &wl_pphigs_ops,    &wl_dpscan_ops,    &wl_pixelmerge_ops,
    &wl_sortfirst_ops, &wl_tokenring_ops, &wl_argus_ops, NULL,
};

const WlOps *wl_find(const char *name)
{
    for (int i = 0; wl_all[i]; i++)
        if (strcmp(wl_all[i]->name, name) == 0)
            return wl_all[i];
    return NULL;
}

SimTime wl_until(const WlContext *ctx)
{
    SimTime t = SIM_TIME_MAX;
    const CfgNode *run = cfg_get(ctx->root, "run");
    if (!cfg_get_time(run, "until", FALSE, &t, NULL))
        t = SIM_TIME_MAX; /* cannot happen on a loaded config */
    return t;
}
