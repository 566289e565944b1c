/* pm_merge.h — the pixel merging schemes of seed 003 §3 on real pixels.
 *
 * Given each processor's local foremost pixels (WlPmWpa) and a partition
 * of the scanlines (pm_balance.h), a scheme moves the real pixels between
 * processors and z-buffers them until every processor holds the global
 * foremost pixels of the scanlines it owns.  It records, step by step,
 * the message each processor sends and the work each does, so that a
 * timing model can replay the merge without touching pixels again:
 *
 *   ZBUF-EXC  full z-buffer merging (§1): every processor holds a full
 *             N x N z-buffer; recursive halving over the d channels
 *             exchanges every location of the half being given away,
 *             active or not, and compares every received location.
 *   PAIR      pairwise exchange (§3.1): d stages; at stage i the partner
 *             over channel i receives the pixels whose owner differs from
 *             us in address bit i; retained and received pixels are merged
 *             into consecutive storage (store-compare-and-forward).
 *   AAPC      all-to-all personalized communication (§3.2): P - 1 steps,
 *             at step j processor p sends to p XOR j the pixels it owns
 *             (the contention-free schedule over e-cube routes, Abali et
 *             al. 1993); then local pixels are scattered into the owner's
 *             z-buffer without comparison and received ones compared.
 *
 * Every exchange step has exactly one message per processor (possibly
 * carrying no pixel: the header still goes).  Message bytes are
 * pixels x bytes_per_pixel + scanlines x bytes_per_scanline (the count
 * header that delimits scanlines, since pixels carry only x, §2); a
 * ZBUF-EXC message is locations x bytes_per_location.
 * Cost: O(total pixels x log P) for PAIR, O(total pixels + P^2) for AAPC,
 * O(P N^2) for ZBUF-EXC.
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_MERGE_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_MERGE_H

#include "sim/workload/pixelmerge/pm_balance.h"
#include "sim/workload/pixelmerge/pm_pixels.h"

/* Kurç's three, then the compositing schemes of pm_composite.h. */
typedef enum {
    WL_PM_ZBUF_EXC,
    WL_PM_PAIR,
    WL_PM_AAPC,
    WL_PM_BINARY_SWAP,
    WL_PM_DIRECT_SEND,
    WL_PM_RADIX_K,
    WL_PM_TWO_THREE_SWAP
} WlPmScheme;

/* TRUE for the compositing schemes (pm_composite.h). */
static inline gboolean wl_pm_scheme_composites(WlPmScheme s)
{
    return s >= WL_PM_BINARY_SWAP;
}

/* NULL-terminated names, indexed by WlPmScheme. */
extern const char *const wl_pm_scheme_names[];

typedef struct {
    guint bytes_per_pixel;    /* active pixel record (x, z, shade) */
    guint bytes_per_location; /* ZBUF-EXC record (z, shade; x implicit) */
    guint bytes_per_scanline; /* per-scanline pixel count in a message */
    guint bytes_per_run;      /* compositing: one run-length header */
    guint bytes_per_rect;     /* compositing: one bounding rectangle */
} WlPmFormat;

typedef struct {
    uint32_t src, dst;
    uint64_t pixels; /* records carried */
    uint64_t bytes;
} WlPmMsg;

/* Work of one processor in one step, in pixels. */
typedef struct {
    uint64_t pack;    /* copied into a send buffer (before sending) */
    uint64_t scatter; /* stored without a depth comparison */
    uint64_t compare; /* depth-tested against a held location */
    uint64_t gather;  /* copied back into consecutive storage */
} WlPmWork;

/* A step's messages: Kurç's schemes send exactly one per processor
 * (msg[p] is p's, n_msgs == n_procs); the compositing schemes send any
 * number, in sender order.  A processor's receives in a step are the
 * messages addressed to it. */
typedef struct {
    gboolean exchange; /* FALSE: a compute-only step (msg unused) */
    WlPmMsg *msg;      /* n_msgs, in nondecreasing src */
    guint n_msgs;
    WlPmWork *work;    /* n_procs */
} WlPmStep;

typedef struct {
    WlPmScheme scheme;
    guint n_procs;
    GPtrArray *steps;    /* WlPmStep *, in order */
    WlPmFrame *image;    /* the merged image */
    WlPmWpa **held;      /* per processor: its final pixels (owned rows) */
    uint64_t *merge_ops; /* per processor: scatter + compare, all steps */
    uint64_t total_bytes;
    uint64_t total_msgs;
    uint64_t concurrent_volume; /* sum over steps of the largest message */
} WlPmMerge;

/* Runs a scheme on local[n_procs] (borrowed, n_procs a power of two, all
 * of the partition's size).  ZBUF-EXC ignores `part` and halves into
 * equal strips.  Returns a new result; free with wl_pm_merge_free(). */
WlPmMerge *wl_pm_merge_run(WlPmScheme scheme, WlPmWpa *const *local,
                           guint n_procs, const WlPmPartition *part,
                           const WlPmFormat *fmt);
void wl_pm_merge_free(WlPmMerge *m);

/* For the compositing schemes: a new empty result for n_procs on a
 * width x height screen, a new step of n_procs with one message slot per
 * processor (src set; the caller may replace msg and n_msgs), and the
 * totals, merge_ops and image once the steps and held are filled. */
WlPmMerge *wl_pm_merge_new(WlPmScheme scheme, guint n_procs, guint width,
                           guint height);
WlPmStep *wl_pm_step_new(guint n_procs, gboolean exchange);
void wl_pm_merge_summarise(WlPmMerge *m);

/* Sum over exchange steps of the largest message in the step (bytes): the
 * "total volume of concurrent communication" of Fig. 1. */
uint64_t wl_pm_concurrent_volume(const GPtrArray *steps, guint n_procs);

#endif
