/* pf_arena.c — stages' shared-arena traffic on the memory bus (see
 * pf_arena.h).  A job per stage run walks its pieces: transfer, then
 * compute.  Deterministic; O(pieces) per stage.
 */
#include "sim/workload/performer/pf_arena.h"

#include "sim/core/error.h"

uint64_t wl_pf_share(uint64_t total, guint i, guint n)
{
    return (uint64_t)((unsigned __int128)total * (i + 1) / n -
                      (unsigned __int128)total * i / n);
}

void wl_pf_share_ops(MachOps *out, const MachOps *o, guint i, guint n)
{
    *out = *o;
    for (guint k = 0; k < o->n; k++)
        out->op[k].count = wl_pf_share(o->op[k].count, i, n);
}

gboolean wl_pf_arena_init(WlPfArena *a, SimEngine *eng, MachMachine *m,
                          const WlPfArenaParams *p, GError **err)
{
    double bw = 0;
    SimTime lat = 0;
    *a = (WlPfArena){.p = *p, .eng = eng};
    if (!mach_net_bandwidth(m, "aggregate_bandwidth", &bw) ||
        !mach_net_time(m, "startup", &lat)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "machine '%s': found a network without a memory bus, "
                    "expected network {aggregate_bandwidth, startup} (the "
                    "bandwidth every processor shares, for workload.arena)",
                    mach_name(m));
        return FALSE;
    }
    mach_shmem_init_with(&a->bus, bw, lat);
    a->phase = sim_engine_phase(eng, "arena");
    a->jobs = g_ptr_array_new_with_free_func(g_free);
    return TRUE;
}

void wl_pf_arena_clear(WlPfArena *a)
{
    if (a->jobs)
        g_ptr_array_free(a->jobs, TRUE);
    a->jobs = NULL;
}

void wl_pf_arena_move(WlPfArena *a, MachProc *p, uint64_t bytes,
                      SimHandler done, void *ctx, void *arg)
{
    SimTime now = sim_now(a->eng);
    if (a->bus.free_at > now)
        a->queued += a->bus.free_at - now;
    SimTime end = mach_shmem_transfer(&a->bus, now, bytes);
    /* the processor stalls until its bytes are through: a recording
     * writes the stall as that time (the contention is in it) */
    mach_proc_compute(p, end - now, a->phase, done, ctx, arg);
}

typedef struct {
    WlPfArena *a;
    MachProc *p;
    unsigned phase;
    SimTime c;
    MachOps ops;
    uint64_t bytes;
    guint k;
    SimHandler done;
    void *ctx, *arg;
} Job;

static void piece(Job *j);

static void computed(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    Job *j = ctx;
    j->k++;
    piece(j);
}

static void moved(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)arg;
    Job *j = ctx;
    guint n = j->a->p.pieces;
    if (j->ops.n) {
        MachOps o;
        wl_pf_share_ops(&o, &j->ops, j->k, n);
        mach_proc_compute_list(j->p, &o, j->phase, computed, j, NULL);
        return;
    }
    mach_proc_compute(j->p, wl_pf_share(j->c, j->k, n), j->phase, computed,
                      j, NULL);
}

static void piece(Job *j)
{
    if (j->k == j->a->p.pieces) {
        SimHandler done = j->done;
        void *ctx = j->ctx, *arg = j->arg;
        SimEngine *eng = j->a->eng;
        g_ptr_array_remove_fast(j->a->jobs, j);
        done(eng, ctx, arg);
        return;
    }
    uint64_t b = wl_pf_share(j->bytes, j->k, j->a->p.pieces);
    if (b)
        wl_pf_arena_move(j->a, j->p, b, moved, j, NULL);
    else
        moved(j->a->eng, j, NULL);
}

void wl_pf_arena_run(WlPfArena *a, MachProc *p, unsigned phase, SimTime c,
                     const MachOps *ops, uint64_t bytes, SimHandler done,
                     void *ctx, void *arg)
{
    g_assert(a->p.pieces >= 1);
    Job *j = g_new0(Job, 1);
    *j = (Job){.a = a, .p = p, .phase = phase, .c = c, .bytes = bytes,
               .done = done, .ctx = ctx, .arg = arg};
    if (ops)
        j->ops = *ops;
    g_ptr_array_add(a->jobs, j);
    piece(j);
}
