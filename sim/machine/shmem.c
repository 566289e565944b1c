/* shmem.c — shared memory as a FIFO bandwidth server (shmem.h).
 * O(1) per transfer.
 */
#include "sim/machine/shmem.h"
#include "sim/core/record.h"
#include <string.h>

void mach_shmem_init_with(MachShmem *sh, double bandwidth, SimTime latency)
{
    memset(sh, 0, sizeof *sh);
    sh->bandwidth = bandwidth;
    sh->latency = latency;
}

gboolean mach_shmem_init(MachShmem *sh, const MachMachine *m, GError **err)
{
    const char *topo = mach_net_word(m, "topology");
    double bw = 0;
    SimTime lat = 0;
    if (!topo || strcmp(topo, "bus") != 0 ||
        !mach_net_bandwidth(m, "bandwidth", &bw) ||
        !mach_net_time(m, "startup", &lat)) {
        /* located at the network's topology: a distributed-memory
         * machine cannot run a shared-memory program (docs/models.md,
         * pairings) */
        const CfgNode *net = mach_network_cfg(m);
        const CfgNode *at = net ? mach_param_node(net, "topology") : NULL;
        char *found = g_strdup_printf("machine '%s' with a %s network and "
                                      "no shared memory",
                                      mach_name(m), topo ? topo : "no");
        cfg_error(err, at ? at : mach_model_cfg(m), found,
                  "network {topology: bus, bandwidth, startup} (the "
                  "memory's bandwidth and access latency): a shared-memory "
                  "program runs on a shared-memory machine");
        g_free(found);
        return FALSE;
    }
    mach_shmem_init_with(sh, bw, lat);
    return TRUE;
}

static SimTime occupancy(const MachShmem *sh, uint64_t bytes)
{
    return sh->bandwidth > 0 ? sim_time_for_bytes((double)bytes, sh->bandwidth)
                             : 0;
}

SimTime mach_shmem_time(const MachShmem *sh, uint64_t bytes)
{
    return sim_time_add_sat(occupancy(sh, bytes), sh->latency);
}

SimTime mach_shmem_transfer(MachShmem *sh, SimTime now, uint64_t bytes)
{
    SimTime start = MAX(now, sh->free_at);
    SimTime occ = occupancy(sh, bytes);
    sh->free_at = start + occ;
    sh->busy += occ;
    sh->bytes += bytes;
    sh->transfers++;
    sh->last_end = sh->free_at + sh->latency;
    return sh->last_end;
}

gboolean mach_shmem_send(MachShmem *sh, SimEngine *eng, uint32_t src,
                         uint32_t dst, uint64_t bytes, SimHandler done,
                         void *ctx, void *arg)
{
    SimTime now = sim_now(eng), t = mach_shmem_transfer(sh, now, bytes);
    SimRecorder *rec = sim_engine_recorder(eng);
    if (rec)
        return sim_record_schedule_done(
            eng, rec, rec->ops->transfer(rec, now, src, dst, bytes, t), t, done,
            ctx, arg);
    return done ? sim_schedule_at(eng, t, done, ctx, arg) : TRUE;
}

double mach_shmem_utilisation(const MachShmem *sh, SimTime elapsed)
{
    return elapsed ? (double)sh->busy / (double)elapsed : 0;
}
