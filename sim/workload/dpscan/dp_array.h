/* dp_array.h — a small data-parallel array layer over virtual processors
 * (seed 004 §3: "each physical processor is given a number of data
 * elements ... each of these data elements is considered a virtual
 * processor").
 *
 * A WlDpVm runs the operations of a CM Fortran style program: elementwise
 * statements under a context mask, scans and reductions, router sends
 * with a combiner (max, add, overwrite) and NEWS moves on the screen
 * grid.  The data movement is real (the caller's arrays are read and
 * written); the time is charged to one or more *targets* — a machine at
 * one partition size — from counted work only:
 *
 *   elementwise  step + v * ops * op               v = VP ratio of the
 *   scan/reduce  step + v * scan_slice                 array (dp_cost.h)
 *   send         per 32-bit word sent: step + send_setup + vps * send_vp
 *                + load * send_slice (SIMD router) or the SPMD formula
 *                of dp_cost.h; load = the most messages one physical
 *                processor injects or receives, counted from the real
 *                source and destination elements of this send
 *   NEWS move    step + v * news_slice
 *
 * Masked virtual processors take their turn (the SIMD array steps
 * through every VP slice), so elementwise costs depend on the array
 * length, not on how many elements are active; only the active ones are
 * computed here.  Several targets share one execution: the program's
 * data flow does not depend on the machine, so one render is costed on
 * every partition at once (ortega93).
 *
 * Layouts: a 1-D array of n elements lies in blocks of v consecutive
 * elements per processor (CM Fortran's default block layout); the screen
 * (width x height, the z-buffer) in 2-D blocks (WlDpLayout).
 *
 * Collisions: in one send, a message whose destination element already
 * received a message of that send collides and is combined; the layer
 * counts them in total and per destination (the most messages one
 * element received).
 *
 * Complexity: O(targets) per elementwise op; O(messages x targets) per
 * send; O(width x height) per NEWS move.  Memory O(procs) per target
 * plus one stamp per destination element.
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_ARRAY_H
#define PGSIM_WORKLOAD_DPSCAN_DP_ARRAY_H

#include "sim/workload/dpscan/dp_cost.h"

typedef enum {
    WL_DP_PH_TRANSFORM,
    WL_DP_PH_SCAN,
    WL_DP_PH_PIXEL,
    WL_DP_PH_ROUTER,
    WL_DP_PH_DISPLAY,
    WL_DP_N_PHASES
} WlDpPhase;

typedef enum {
    WL_DP_COMBINE_MAX,
    WL_DP_COMBINE_ADD,
    WL_DP_COMBINE_OVERWRITE /* the last message in source order wins */
} WlDpCombine;

/* Where the elements of a destination array live. */
typedef enum { WL_DP_LAYOUT_LINEAR, WL_DP_LAYOUT_SCREEN } WlDpLayoutKind;

/* The node-to-node traffic of one array sent (SPMD): pair k carries
 * msgs[k] messages from node src[k] to node dst[k]; pairs are distinct,
 * in order of their first message. */
typedef struct {
    const uint32_t *src, *dst;
    const uint64_t *msgs;
    size_t n;
} WlDpTraffic;

/* Prices a send's traffic on a network (the data network's time from the
 * first injection to the last delivery); see wl_dp_vm_set_wire(). */
typedef SimTime (*WlDpWireFn)(void *ctx, const WlDpTraffic *t);

/* One machine at one partition size, and what it was charged. */
typedef struct {
    WlDpMachine m;
    WlDpWireFn wire;    /* NULL: the analytic fat-tree formula */
    void *wire_ctx;
    WlDpLayout *screen; /* NULL until the first screen-sized operation */
    uint32_t *inj, *recv; /* per processor, zero between sends */
    SimTime phase[WL_DP_N_PHASES];
    SimTime total;
    WlDpCoef coef;
    WlDpCounts count[WL_DP_N_PHASES]; /* phase[ph] as named counts */
    uint64_t max_load; /* largest load of any send */
    /* SPMD sends: the data network's time (measured by `wire` or the
     * analytic fat tree) and the per-message software time, summed over
     * arrays sent; a send costs the larger of the two. */
    SimTime wire_total, soft_total;
} WlDpTarget;

typedef struct {
    uint64_t steps;      /* data-parallel operations issued */
    uint64_t ew_elems;   /* element slots of elementwise ops (n * ops) */
    uint64_t ew_active;  /* active element ops (mask set) */
    uint64_t sends, messages, words;
    uint64_t collisions; /* messages combined with an earlier one */
    uint64_t max_depth;  /* most messages one element got in one send */
    uint64_t news_moves;
} WlDpVmCounts;

typedef struct WlDpVm WlDpVm;

/* A new layer for a width x height screen (NEWS grid and z-buffer
 * layout) charging every target in ms (copied; n_targets >= 1).  Free
 * with wl_dp_vm_free(). */
WlDpVm *wl_dp_vm_new(const WlDpMachine *ms, guint n_targets, uint32_t width,
                     uint32_t height);
void wl_dp_vm_free(WlDpVm *vm);
guint wl_dp_vm_n_targets(const WlDpVm *vm);
const WlDpTarget *wl_dp_vm_target(const WlDpVm *vm, guint i);
const WlDpVmCounts *wl_dp_vm_counts(const WlDpVm *vm);
uint64_t wl_dp_vm_screen_elems(const WlDpVm *vm);
const char *wl_dp_phase_name(WlDpPhase ph);

/* Target i (SPMD) prices the wire time of its sends with fn(ctx, traffic)
 * instead of dp_cost.h's analytic fat tree: the workload hands them to
 * the machine's network at the run's fidelity.  O(messages) per send
 * plus what fn costs. */
void wl_dp_vm_set_wire(WlDpVm *vm, guint i, WlDpWireFn fn, void *ctx);

/* An elementwise statement of `ops` operations per element over an
 * array of n elements of which `active` are selected by the context
 * mask (the caller computed them). */
void wl_dp_ew(WlDpVm *vm, WlDpPhase ph, uint64_t n, uint64_t active,
              uint32_t ops);

/* Exclusive add-scan (enumerate) of in[0..m) into out[0..m), on an
 * array of n >= m elements (the others masked off); returns the sum. */
uint64_t wl_dp_scan_add(WlDpVm *vm, WlDpPhase ph, uint64_t n,
                        const uint32_t *in, uint32_t *out, uint64_t m);
/* Global maximum of v[0..m) on an array of n >= m elements (0 if m = 0). */
uint32_t wl_dp_reduce_max(WlDpVm *vm, WlDpPhase ph, uint64_t n,
                          const uint32_t *v, uint64_t m);

/* A router send of `count` messages, each `words` 32-bit words (the
 * arrays go one after the other), from elements src[k] of an n_src
 * array to elements dst[k] of `dest` (n_dst elements in layout `lay`;
 * for WL_DP_LAYOUT_SCREEN, dst = y * width + x), values val[k] combined
 * with `comb`.  src may be NULL (message k comes from element k); dest
 * and val may be NULL to route without moving data (records the caller
 * moves itself).  Returns the collisions of this send. */
typedef struct {
    WlDpPhase phase;
    uint64_t n_src, n_dst;
    WlDpLayoutKind lay;
    const uint64_t *src, *dst, *val;
    uint64_t count;
    uint64_t *dest;
    uint32_t words;
    WlDpCombine comb;
} WlDpSend;
uint64_t wl_dp_send(WlDpVm *vm, const WlDpSend *s);

/* NEWS move of a screen array: out[x, y] = in[x - dx, y - dy], `fill`
 * where that is off the grid (|dx| + |dy| == 1). */
void wl_dp_news(WlDpVm *vm, WlDpPhase ph, const uint64_t *in, uint64_t *out,
                int dx, int dy, uint64_t fill);

#endif
