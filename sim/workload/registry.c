/* registry.c — the table of workloads (one row per workload). */
#include "sim/workload/workload.h"
#include "sim/workload/dpscan/dp_wl.h"
#include <string.h>

extern const WlOps wl_pphigs_ops;

const WlOps *const wl_all[] = {
    &wl_pphigs_ops,
    &wl_dpscan_ops,
    NULL,
};

const WlOps *wl_find(const char *name)
{
    for (int i = 0; wl_all[i]; i++)
        if (strcmp(wl_all[i]->name, name) == 0)
            return wl_all[i];
    return NULL;
}
