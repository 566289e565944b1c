/* pf_workload.h — the `performer` workload (IRIS Performer's frame
 * pipeline on a shared-memory multiprocessor with one graphics pipe;
 * with a `pn:` section, the curved-PN-triangle geometry-compression
 * measurement instead).  docs/workloads.md, section "performer". */
#ifndef PGSIM_WORKLOAD_PERFORMER_PF_WORKLOAD_H
#define PGSIM_WORKLOAD_PERFORMER_PF_WORKLOAD_H

#include "sim/workload/workload.h"

extern const WlOps wl_pf_ops;

#endif
