/* dp_cost.h — cost of data-parallel steps, scans and router sends
 * (seed 004).
 *
 * A data-parallel machine is modelled as steps over arrays, never as
 * 64K entities (the design notes).  An array of n elements on p physical
 * processors runs at virtual-processor ratio v = ceil(n / p) (Hillis,
 * The Connection Machine, 1985; seed 004 §3: "each physical processor is
 * given a number of data elements ... each of these data elements is
 * considered a virtual processor"); with `vp_pow2` the ratio is rounded
 * up to a power of two, as Paris VP sets are.  Masked virtual processors
 * still take their turn, which is what makes the paper's large polygons
 * slow.  Costs:
 *
 *   step   step + v * ops * op          (op: one 32-bit operation of one
 *                                        virtual processor; on the CM-200
 *                                        32 bit-serial lanes share an FPA)
 *   scan   step + v * scan_slice        (enumerate, global max: parallel
 *                                        prefix over the array)
 *   send   words * (step + send_setup + slices * send_vp
 *                   + load * send_slice)                    SIMD router
 *          words * (step + net_latency + max(load * msg_overhead,
 *                                     fat-tree wire time of load * msg_bytes))
 *                                                          SPMD (CM-5)
 *
 * A send moves `words` arrays, one after the other (seed 004 §4: the
 * send-with-max utility "can only work with one sending array at a
 * time").  `load` is the larger of the messages one processor injects and
 * the messages one processor receives (its part of the destination
 * array): many pixels landing in one processor's part of the z-buffer
 * (collisions, dense regions) slow the router down the way a high VP
 * ratio does.  On the fat tree, bw_l is the per-node bandwidth of level l
 * and a fraction 1 - a^l / p of uniformly spread destinations leaves a
 * level-l subtree (arity a); software and wire overlap, the slower one
 * bounds the send (Leiserson et al., SPAA 1992; von Eicken et al., ISCA
 * 1992 for the per-message software cost).
 *
 * Every function is O(1) (O(levels) for the fat tree) except the load of
 * a z-buffer send, O(pixels of that send).  Costs are exact integer
 * picoseconds; overflow is asserted.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_COST_H
#define PGSIM_WORKLOAD_DPSCAN_DP_COST_H

#include "sim/core/time.h"
#include "sim/net/topology.h"
#include <glib.h>

typedef enum { WL_DP_SIMD, WL_DP_SPMD } WlDpArch;

typedef struct {
    WlDpArch arch;
    uint64_t procs;     /* physical processors (SIMD lanes or nodes) */
    gboolean vp_pow2;   /* VP ratios are powers of two */
    uint32_t router_procs; /* processors sharing one router node (0: 1) */
    SimTime op;         /* one element operation at VP ratio 1 */
    SimTime step;       /* issue overhead of one data-parallel step */
    SimTime scan_slice; /* parallel prefix, per VP slice */
    /* SIMD router */
    SimTime send_setup; /* per array sent */
    SimTime send_slice; /* per message per processor (load) */
    SimTime send_vp;    /* per VP slice of the source array */
    SimTime send_msg;   /* per message per processor on average */
    SimTime news_slice; /* NEWS grid move of one word, per VP slice */
    /* SPMD data network */
    SimTime net_latency;  /* per array sent (send phase) */
    SimTime msg_overhead; /* software cost of one message, both ends */
    uint32_t msg_bytes;   /* bytes of one message on the wire */
    unsigned arity;       /* fat-tree arity */
    unsigned levels;      /* entries of level_bw in use */
    double level_bw[NET_MAX_LEVELS]; /* B/s per node, level 0 = leaves */
} WlDpMachine;

/* Linear coefficients of a SIMD frame time:
 * time = op * op_slices + step * steps + scan_slice * scan_slices
 *      + send_setup * sends + send_slice * slices + send_vp * vp_slices
 *      + news_slice * news_slices + send_msg * msg_slices.
 * Kept so that calibration is a linear least-squares fit and tests can
 * check sums. */
typedef struct {
    double op_slices;   /* sum over steps of v * ops */
    double steps;       /* steps and scans issued */
    double scan_slices; /* sum over scans of v */
    double sends;       /* arrays sent */
    double slices;      /* sum over arrays sent of the load */
    double vp_slices;   /* sum over arrays sent of the VP slices used */
    double news_slices; /* sum over NEWS moves of v */
    double msg_slices;  /* sum over arrays sent of ceil(messages / procs) */
} WlDpCoef;

/* Where a screen pixel lives: the z-buffer (width x height) in blocks
 * over a px x py processor grid (CM Fortran's default block layout). */
typedef struct {
    uint64_t procs;
    uint32_t px, py; /* processor grid, px * py == procs */
    uint32_t bw, bh; /* block (subgrid) size */
    uint32_t width, height;
    uint32_t *col;   /* x -> x / bw, width entries */
    uint32_t *row;   /* y -> (y / bh) * px, height entries */
    uint32_t *count; /* procs counters (zero between sends) */
} WlDpLayout;

/* ceil(n / procs) (a power of two if m->vp_pow2); 0 for an empty array. */
uint64_t wl_dp_vp_ratio(const WlDpMachine *m, uint64_t n);

SimTime wl_dp_step_cost(const WlDpMachine *m, uint64_t n, uint32_t ops,
                        WlDpCoef *k);
SimTime wl_dp_scan_cost(const WlDpMachine *m, uint64_t n, WlDpCoef *k);
/* `words` arrays of `active` messages from an array of n elements, with
 * `load` messages on the busiest processor; 0 when nothing is sent. */
SimTime wl_dp_send_cost(const WlDpMachine *m, uint32_t words, uint64_t n,
                        uint64_t active, uint64_t load, WlDpCoef *k);

/* The same send with the data network's time `wire` measured elsewhere
 * (the machine's network at the run's fidelity, dp_array.h) in place of
 * the analytic fat-tree formula; SPMD only. */
SimTime wl_dp_send_cost_wired(const WlDpMachine *m, uint32_t words,
                              uint64_t n, uint64_t active, uint64_t load,
                              SimTime wire, WlDpCoef *k);

/* The analytic fat-tree wire time of one node's `load` messages (the
 * busiest level's share of them over its per-node bandwidth). */
SimTime wl_dp_fattree_wire(const WlDpMachine *m, uint64_t load);

/* The fraction of uniformly spread destinations that leave a level-l
 * subtree of an arity-ary fat tree over p nodes (0 when the subtree
 * holds them all). */
double wl_dp_fattree_escape(unsigned arity, uint64_t p, unsigned level);

/* Block layout of a width x height array over procs processors (the
 * grid as square as the power-of-two factors allow, wider than tall).
 * Returns a new layout; free with wl_dp_layout_free(). */
WlDpLayout *wl_dp_layout_new(uint64_t procs, uint32_t width, uint32_t height);
void wl_dp_layout_free(WlDpLayout *l);
static inline uint64_t wl_dp_layout_owner(const WlDpLayout *l, uint32_t x,
                                          uint32_t y)
{
    g_assert(x < l->width && y < l->height);
    return (uint64_t)l->row[y] + l->col[x];
}

/* A NEWS move of one word over an array of n elements: step + v *
 * news_slice (SIMD); on the SPMD machine a grid shift is boundary
 * messages, charged the same way with news_slice per VP slice. */
SimTime wl_dp_news_cost(const WlDpMachine *m, uint64_t n, WlDpCoef *k);

/* The named counts a target was charged (per phase: dp_array.h): the
 * time is exactly the sum of count[c] x wl_dp_cost_value(m, c), plus
 * `wire`, the data network's time of the SPMD sends it bounded (a time,
 * measured on the network or by the fat-tree formula, not a count).
 * Each count is of one model constant of the `dpscan:` section, and is
 * named after its key (wl_dp_cost_name): a replay prices the counts from
 * another model's section (docs/traces.md).  Counts are at the
 * partition charged: VP slices depend on the processor count. */
typedef enum {
    WL_DP_C_STEP,         /* steps issued (elementwise, scan, NEWS, per
                             array sent) */
    WL_DP_C_OP,           /* sum over steps of v * ops */
    WL_DP_C_SCAN_SLICE,   /* sum over scans of v */
    WL_DP_C_NEWS_SLICE,   /* sum over NEWS moves of v */
    WL_DP_C_SEND_SETUP,   /* SIMD: arrays sent */
    WL_DP_C_SEND_VP,      /* SIMD: sum over arrays sent of the VP slices */
    WL_DP_C_SEND_MSG,     /* SIMD: sum over arrays sent of the mean load */
    WL_DP_C_SEND_SLICE,   /* SIMD: sum over arrays sent of the load */
    WL_DP_C_NET_LATENCY,  /* SPMD: arrays sent */
    WL_DP_C_MSG_OVERHEAD, /* SPMD: the load of arrays the software bounds */
    WL_DP_N_COSTS
} WlDpCost;

typedef struct {
    uint64_t n[WL_DP_N_COSTS];
    SimTime wire; /* SPMD: wire time of the sends the wire bounds */
} WlDpCounts;

/* The model key of cost c ("send_slice"), its path in a model
 * ("dpscan.send_slice": a static string, the name a recording gives the
 * count) and its value on m. */
const char *wl_dp_cost_name(WlDpCost c);
const char *wl_dp_cost_path(WlDpCost c);
SimTime wl_dp_cost_value(const WlDpMachine *m, WlDpCost c);
/* sum of k->n[c] x wl_dp_cost_value(m, c) + k->wire (asserted no overflow). */
SimTime wl_dp_counts_price(const WlDpMachine *m, const WlDpCounts *k);

/* Adds to k what each cost function above charges for the same
 * arguments (k may be NULL).  A send: `wire` is its wire time (SPMD). */
void wl_dp_count_step(const WlDpMachine *m, uint64_t n, uint32_t ops,
                      WlDpCounts *k);
void wl_dp_count_slices(const WlDpMachine *m, uint64_t n, WlDpCost c,
                        WlDpCounts *k);
void wl_dp_count_send(const WlDpMachine *m, uint32_t words, uint64_t n,
                      uint64_t active, uint64_t load, SimTime wire,
                      WlDpCounts *k);

#endif
