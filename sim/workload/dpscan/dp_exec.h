/* dp_exec.h — one frame of data-parallel rendering as engine events on
 * a machine (sim/machine), its messages through sim/net.
 *
 * The steps of dp_sched.h run one after the other, each as work on the
 * machine's processors (mach_proc_compute, busy time per phase):
 *
 *   SIMD (CM-200)  the array is one lock-step processor (`array`, design:
 *                  steps over arrays, not 64K entities); every step,
 *                  scan and router send is one piece of work whose cost
 *                  is dp_cost.h's; the completion of one issues the next.
 *                  The router is part of the step cost (send-with-max is
 *                  a machine instruction of the array).
 *   SPMD (CM-5)    every node (`node` 0 .. p-1) runs each compute step
 *                  (one completion event per step, busy time on every
 *                  node); a send becomes, per source node, one message
 *                  per destination node carrying all its words for that
 *                  step (real destinations: segment slots and z-buffer
 *                  blocks), sent with net_send() after the sender's
 *                  software cost and handled at arrival by the receiver
 *                  (half of msg_overhead each side, von Eicken et al.
 *                  1992).  The step ends when every message has been
 *                  handled, plus net_latency (the control-network
 *                  barrier).  So run.fidelity (analytic | flow | packet)
 *                  chooses how the fat tree carries the traffic.  When a
 *                  step would make more than 2p messages, destinations
 *                  are merged into two halves of the machine (one message
 *                  per source and half, to the node opposite the source
 *                  in that half), which keeps the bytes and the top-level
 *                  crossings and bounds events by the scene's steps.
 *
 * Memory O(p) per step besides the schedule; events O(steps) (SIMD) and
 * O(steps * min(pairs, 2p)) (SPMD).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_EXEC_H
#define PGSIM_WORKLOAD_DPSCAN_DP_EXEC_H

#include "sim/machine/machine.h"
#include "sim/workload/dpscan/dp_frame.h"

/* Runs one frame of g on `mach` (its engine must be idle; SIMD: a kind
 * `array`, SPMD: a kind `node` with m->procs processors and a network)
 * and runs the engine until the frame is done.  Fills *out (phases: busy
 * time of the array / of node 0; total: the frame's elapsed simulated
 * time).  FALSE with *err if the machine does not fit or the engine
 * failed. */
gboolean wl_dp_exec_frame(MachMachine *mach, const WlDpMachine *m,
                          const WlDpGeom *g, const WlDpAlgo *a, WlDpFrame *out,
                          GError **err);

/* A new machine for the dpscan model `model` (cm200, cm5 ...) with
 * `procs` lanes (SIMD) or nodes (SPMD) at `fidelity`; free with
 * mach_free(). */
MachMachine *wl_dp_exec_machine(SimEngine *eng, const char *model,
                                const WlDpMachine *m, const char *fidelity,
                                GError **err);

#endif
