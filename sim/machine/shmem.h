/* shmem.h — the shared memory of a shared-memory multiprocessor, as one
 * bandwidth resource.
 *
 * Processors of a shared-memory machine (the SGI Origin 2000 of seed 002)
 * talk through memory: a command block written by one thread is read by
 * another.  MachShmem charges each such transfer to one FIFO server of
 * the machine's memory bandwidth: a transfer of b bytes requested at time
 * t starts at max(t, free_at), occupies the memory for b / bandwidth and
 * completes `latency` later.  Contention is therefore serialised, not
 * shared fairly; with the traffic of seed 002 (a few MB/s against
 * hundreds) the difference is below the model's resolution.
 *
 * Parameters come from the model's `network:` section (topology: bus):
 * `bandwidth` (the memory system's sustained bandwidth) and `startup`
 * (one memory access latency).  O(1) per transfer, no events of its own:
 * the caller schedules at the returned completion time.
 */
#ifndef PGSIM_MACHINE_SHMEM_H
#define PGSIM_MACHINE_SHMEM_H

#include "sim/machine/machine.h"

typedef struct MachShmem {
    double bandwidth; /* bytes per second */
    SimTime latency;
    SimTime free_at;
    SimTime busy;   /* total occupancy */
    uint64_t bytes; /* total bytes moved */
    uint64_t transfers;
    SimTime last_end; /* completion time of the latest transfer booked */
} MachShmem;

/* Reads bandwidth and startup from m's network section; FALSE with *err
 * (naming the machine) when the machine is not a bus or lacks them. */
gboolean mach_shmem_init(MachShmem *sh, const MachMachine *m, GError **err);
/* A memory of `bandwidth` bytes/s and `latency` (tests, uniprocessors). */
void mach_shmem_init_with(MachShmem *sh, double bandwidth, SimTime latency);
/* The time a transfer of `bytes` takes on an idle memory: its occupancy
 * (bytes / bandwidth) plus the latency, saturating. */
SimTime mach_shmem_time(const MachShmem *sh, uint64_t bytes);
/* Books a transfer of `bytes` requested at `now`; returns its completion
 * time.  bandwidth <= 0 means infinite (only the latency). */
SimTime mach_shmem_transfer(MachShmem *sh, SimTime now, uint64_t bytes);
/* mach_shmem_transfer() of `bytes` from processor src to dst (global
 * ids) requested now, then done(eng, ctx, arg) at its completion (done
 * may be NULL); a recording (`--record`) writes it as a `b` action
 * (docs/traces.md).  Its completion time is then sh->last_end.  FALSE if
 * it overflows SimTime (the engine is then stopped). */
gboolean mach_shmem_send(MachShmem *sh, SimEngine *eng, uint32_t src,
                         uint32_t dst, uint64_t bytes, SimHandler done,
                         void *ctx, void *arg);
/* Occupied fraction of [0, elapsed] (0 when elapsed is 0). */
double mach_shmem_utilisation(const MachShmem *sh, SimTime elapsed);

#endif
