/* dp_cost.h — cost of data-parallel steps and router sends (seed 004).
 *
 * A data-parallel machine is modelled as steps over arrays, never as
 * 64K entities (design.md).  A step over an array of n elements on p
 * physical processors runs at virtual-processor ratio v = ceil(n / p)
 * (Hillis, The Connection Machine, 1985, §virtual processors; seed 004
 * §3) and costs
 *
 *     step + v * ops * op
 *
 * where `ops` is the step's operation count per element, `op` one
 * element operation on one processor (a CM-200 lane, a CM-5 node with its
 * vector units) and `step` the front end's / node's issue overhead.  On
 * the SIMD machine every virtual processor of the array takes its turn
 * whether it is active or not (context masking); this is what makes the
 * paper's large polygons slow.
 *
 * A send of `active` messages (send-with-max into the z-buffer, seed 004
 * §4) costs, on a SIMD router machine (CM-200),
 *
 *     send_setup + ceil(active / p) * send_slice
 *
 * (one router delivery cycle per virtual-processor slice that holds a
 * message).  On an SPMD fat-tree machine (CM-5, Leiserson et al., SPAA
 * 1992) each node sends k = ceil(active / p) messages of msg_bytes to
 * uniformly spread owners, and the send costs
 *
 *     net_latency + max(k * msg_overhead, max_l f_l * k * msg_bytes / bw_l)
 *
 * where bw_l is the per-node bandwidth of fat-tree level l and f_l the
 * fraction of destinations outside the node's level-l subtree (1 - a^l /
 * p for arity a): software overhead and wire time overlap, the slower
 * one bounds the send.
 *
 * Every function is O(1) (O(levels) for the fat tree).  Costs are exact
 * integer picoseconds; overflow is asserted (a frame is far below the
 * 213 days SimTime holds).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_COST_H
#define PGSIM_WORKLOAD_DPSCAN_DP_COST_H

#include "sim/core/time.h"
#include "sim/net/topology.h"

typedef enum { WL_DP_SIMD, WL_DP_SPMD } WlDpArch;

typedef struct {
    WlDpArch arch;
    uint64_t procs;      /* physical processors (SIMD lanes or nodes) */
    SimTime op;          /* one element operation on one processor */
    SimTime step;        /* issue overhead of one data-parallel step */
    /* SIMD router */
    SimTime send_setup;  /* per send */
    SimTime send_slice;  /* per virtual-processor slice with a message */
    /* SPMD data network */
    SimTime net_latency; /* per send phase */
    SimTime msg_overhead;/* software cost of one message, both ends */
    uint32_t msg_bytes;  /* bytes of one pixel message on the wire */
    unsigned arity;      /* fat-tree arity */
    unsigned levels;     /* entries of level_bw in use */
    double level_bw[NET_MAX_LEVELS]; /* B/s per node, level 0 = leaves */
} WlDpMachine;

/* Linear coefficients of a SIMD frame time: time = op * op_slices +
 * step * steps + send_setup * sends + send_slice * slices.  Kept so that
 * calibration is a linear least-squares fit and tests can check sums. */
typedef struct {
    double op_slices;  /* sum over steps of v * ops */
    double steps;
    double sends;
    double slices;     /* sum over sends of ceil(active / p) */
} WlDpCoef;

/* ceil(n / procs); 0 for an empty array. */
uint64_t wl_dp_vp_ratio(uint64_t n, uint64_t procs);

/* Cost of one step over n elements with `ops` operations each; adds its
 * coefficients to *k (may be NULL). */
SimTime wl_dp_step_cost(const WlDpMachine *m, uint64_t n, uint32_t ops,
                        WlDpCoef *k);

/* Cost of one send of `active` messages; 0 when active is 0. */
SimTime wl_dp_send_cost(const WlDpMachine *m, uint64_t active,
                        WlDpCoef *k);

/* The fraction of uniformly spread destinations that leave a level-l
 * subtree of an arity-ary fat tree over p nodes (0 when the subtree
 * holds them all). */
double wl_dp_fattree_escape(unsigned arity, uint64_t p, unsigned level);

#endif
