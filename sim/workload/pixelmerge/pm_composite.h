/* pm_composite.h — sort-last compositing on real pixels: binary swap,
 * direct send, radix-k and 2-3 swap (plans in pm_stages.h), with the
 * depth (z) or the over operator, optional bounding rectangles and
 * run-length encoding of active pixels.  Like pm_merge.h it records,
 * stage by stage, every message and every processor's work, so that
 * pm_replay.h times it on the machine's network and processors.
 *
 * Images.  Processor p's local image is its active (local foremost)
 * pixels, local[p].  The image is a linear array of width x height
 * pixels in row-major order; a stage splits it into pieces of
 * consecutive pixels (as IceT does).  Rank r of the visibility order
 * (nearest first) is processor order[r] (processor r without an order);
 * the schemes group ranks, so the processes that combine first are the
 * ones adjacent in visibility.
 *
 * Operators.  z: the nearer pixel (pm_pixels.h order, ties by polygon
 * id) wins, so the result equals the serial z-buffer exactly.  over:
 * every active pixel is its colour at opacity `opacity`, premultiplied
 * (r a, g a, b a, a), or its own premultiplied colour when its image
 * carries one (WlPmWpa.rgba: block and volume images); a block nearer in visibility order is composited
 * over a farther one, front over back, c = f + (1 - f.a) b.  The serial
 * reference blends the processors front to back one after the other; a
 * scheme groups the same blends differently, so its result agrees with
 * the reference to rounding (wl_pm_over_diff's tolerance), not bit for
 * bit.
 *
 * A stage (pm_stages.h): in each group of blocks, the group's active
 * processes, sorted by where their pieces start (then by block), take
 * equal consecutive shares of the image (a fold group: its first process
 * takes it all); each process sends to each other one the part of its
 * piece inside the other's new share (a message per non-empty overlap,
 * even one holding no active pixel: the receiver waits for it), and the
 * receiver composites what it kept and received, block by block, front
 * to back.  With equal blocks this is radix-k's exchange exactly (a new
 * share lies inside the old piece); with unequal ones (2-3 swap, the
 * fold) a process may send to several.
 *
 * A message carries a fragment (an overlap of o locations holding a
 * active pixels in `runs` maximal runs, and, with a bounding rectangle,
 * the b locations of the overlap inside the box of its active pixels):
 *   plain            o x bytes_per_location
 *   bounding_rect    b x bytes_per_location + bytes_per_rect
 *   rle              a x bytes_per_location + (runs + 1) x bytes_per_run
 *   both             a x bytes_per_location + (runs + 1) x bytes_per_run
 *                    + bytes_per_rect (runs counted row by row in the box)
 * and the sender packs, the receiver composites ("compare"), the records
 * carried: o, b, a, a.  Cost: O(active pixels x stages + P x stages).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_COMPOSITE_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_COMPOSITE_H

#include "sim/workload/pixelmerge/pm_stages.h"

typedef enum { WL_PM_OP_Z, WL_PM_OP_OVER } WlPmOperator;

/* NULL-terminated names, indexed by WlPmOperator: "z", "over". */
extern const char *const wl_pm_operator_names[];

typedef struct {
    guint radices[WL_PM_MAX_RADICES]; /* radix-k; n_radices 0: default */
    guint n_radices;
    gboolean bounding_rect, rle;
    WlPmOperator op;
    double opacity; /* over: alpha of every active pixel, (0, 1] */
    const guint *order; /* rank -> processor, a permutation of n_procs
                         * (borrowed); NULL: processor order */
} WlPmCompose;

/* Runs a compositing scheme on local[n_procs] (borrowed, all one size).
 * The result's held[p] is p's final piece (for over, colours are the
 * premultiplied blend over black, rounded to 8 bits); image the whole;
 * rgba (over only) the blended image as width x height x 4 doubles.
 * Free with wl_pm_composite_free(). */
typedef struct {
    WlPmMerge *merge;
    double *rgba;
    guint stages;
} WlPmComposite;

WlPmComposite *wl_pm_composite_run(WlPmScheme scheme, const WlPmCompose *c,
                                   WlPmWpa *const *local, guint n_procs,
                                   const WlPmFormat *fmt);
void wl_pm_composite_free(WlPmComposite *c);

/* The serial front-to-back blend of local[order[0]], local[order[1]]
 * ... (order NULL: local[0], local[1] ...) at opacity: width x height x 4
 * premultiplied doubles (free with g_free). */
double *wl_pm_over_serial(WlPmWpa *const *local, guint n_procs,
                          const guint *order, double opacity);

/* TRUE when order[n] is a permutation of 0 .. n - 1. */
gboolean wl_pm_order_ok(const guint *order, guint n);

/* The first component where a and b (n doubles each) differ by more
 * than 1e-9 (the blends' rounding is ~1e-15 per stage), or -1. */
int64_t wl_pm_over_diff(const double *a, const double *b, gsize n);

#endif
