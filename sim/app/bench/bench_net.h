/* bench_net.h — one network benchmark: a machine model, a partition size
 * and a traffic pattern, run at any fidelity (used by `pgsim bench net`
 * and by its tests).
 *
 * The machine comes from models/<name>.yaml through the machine layer:
 * a run-config tree `machine: {model: NAME}` gets the user's --set
 * overrides (machine.KEY=VALUE, as in `pgsim run`), then the partition
 * (sim/machine/partition.h) when a node count is asked for.  Every run
 * builds a fresh engine and machine from that tree, so fidelities see the
 * same network parameters and the same traffic (sim/net/traffic.h).
 */
#ifndef PGSIM_APP_BENCH_BENCH_NET_H
#define PGSIM_APP_BENCH_BENCH_NET_H

#include "sim/core/cfg.h"
#include "sim/net/net.h"
#include "sim/net/traffic.h"

typedef struct {
    const char *machine; /* model name */
    guint nodes;         /* 0: the model's own size */
    NetTraffic pattern;
    uint64_t bytes; /* per message (pairwise: see traffic.h) */
    uint64_t seed;
    const char *const *sets; /* "machine.KEY=VALUE" overrides, NULL-ended;
                                may be NULL */
} BenchNetSpec;

typedef struct {
    SimTime end;       /* simulated completion time */
    double wall;       /* seconds of wall time (traffic only) */
    uint64_t events;   /* engine events */
    uint64_t messages; /* sent */
    uint64_t delivered;
} BenchNetRun;

typedef struct BenchNet BenchNet;

/* Loads and checks the machine, its partition and the pattern's fit to
 * it.  Returns a new benchmark (bench_net_free) or NULL with *err. */
BenchNet *bench_net_new(const BenchNetSpec *spec, GError **err);
void bench_net_free(BenchNet *b);

/* Network endpoints, and a description of the machine and its network
 * for a header (borrowed). */
guint bench_net_nodes(const BenchNet *b);
const char *bench_net_describe(const BenchNet *b);

/* Runs the pattern at one fidelity; FALSE with *err if the machine cannot
 * be built or a message was never delivered. */
gboolean bench_net_run(const BenchNet *b, NetFidelity fid, BenchNetRun *out,
                       GError **err);

#endif
