/* ag_workload.h — the `argus` workload (seed 002; Igehy, Stoll and
 * Hanrahan, "The Design of a Parallel Graphics Interface", SIGGRAPH
 * 1998): WlOps row and the pieces the tests and the reproduction use.
 * Keys and metrics: docs/workloads.md. */
#ifndef PGSIM_WORKLOAD_ARGUS_AG_WORKLOAD_H
#define PGSIM_WORKLOAD_ARGUS_AG_WORKLOAD_H

#include "sim/workload/argus/ag_pipe.h"
#include "sim/workload/workload.h"

typedef struct {
    AgSetup setup;
    AgOrder order;
    AgPrim prim;
    AgPixelMode pixels;
    AgStateMode state;
    guint block_tris, tile, cells;
    int width, height; /* 0: the scene's */
    double alpha;
    gboolean check_image;
} WlAgParams;

extern const WlOps wl_argus_ops;

#endif
