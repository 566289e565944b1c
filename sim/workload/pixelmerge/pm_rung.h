/* pm_rung.h — the image fidelity ladder of sort-last compositing: the
 * schemes of pm_composite.h run on images held at three rungs, so that
 * compositing scales with the active pixels, not with processes x image
 * size (issue 35, point 2):
 *
 *   pixels  real pixels (pm_composite.h: depth, colour, the operator);
 *   runs    active spans without values: each process holds the sorted
 *           maximal runs [s, e) of linear indices it covers; a composite
 *           is their union.  The messages, their bytes and the work are
 *           those of the pixel rung exactly (an active set, its runs and
 *           its bounding box are all a message's size depends on);
 *   counts  rectangles and coverage only: each process holds a few
 *           screen rectangles, each with how many active pixels it holds
 *           (spread evenly over it); a piece of a rectangle keeps its
 *           share; a composite merges rectangles that intersect into
 *           their bounding box, the overlap counted once at the product of
 *           the two coverages (independent placement).  Runs are
 *           estimated as one per rectangle row.  Its error against the
 *           pixel rung is measured (pgsim bench composite).
 *
 * The plan, the groups, the shares and who sends what to whom are those
 * of pm_composite.h (a message per non-empty overlap of a piece and a
 * share); only what a message holds is measured on the rung's image.
 * The result is a WlPmMerge without image or held pixels (steps and
 * totals only), for pm_replay.h.
 * Cost: O(runs x stages + P x stages) for runs, O(rectangles x stages +
 * P x stages) for counts, plus, for direct send, O(P^2).
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_RUNG_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_RUNG_H

#include "sim/workload/pixelmerge/pm_composite.h"

typedef enum { WL_PM_RUNG_PIXELS, WL_PM_RUNG_RUNS, WL_PM_RUNG_COUNTS } WlPmRung;

/* NULL-terminated names, indexed by WlPmRung: "pixels", "runs",
 * "counts". */
extern const char *const wl_pm_rung_names[];

/* One run of active pixels: linear indices [s, e). */
typedef struct {
    uint64_t s, e;
} WlPmRun;

/* One rectangle x0..x1, y0..y1 (inclusive) holding `active` pixels. */
typedef struct {
    guint x0, y0, x1, y1;
    double active;
} WlPmCover;

/* A process's image at the runs or counts rung: WlPmRun (sorted,
 * disjoint, not adjacent) or WlPmCover elements. */
typedef struct {
    WlPmRung rung;
    guint width, height;
    GArray *el;
} WlPmRungImage;

/* A new empty image (rung runs or counts); free with
 * wl_pm_rung_image_free(). */
WlPmRungImage *wl_pm_rung_image_new(WlPmRung rung, guint width, guint height);
void wl_pm_rung_image_free(WlPmRungImage *im);
/* Appends a span of row y, x0..x1 inclusive, rows in nondecreasing order
 * (runs: coalesced with the previous run when adjacent). */
void wl_pm_rung_add_span(WlPmRungImage *im, guint y, guint x0, guint x1);
/* Appends a rectangle holding `active` pixels (counts). */
void wl_pm_rung_add_rect(WlPmRungImage *im, const WlPmCover *r);
/* The image of an active pixel array at a rung (runs or counts: one
 * rectangle, its bounding box, holding its pixels). */
WlPmRungImage *wl_pm_rung_from_wpa(WlPmRung rung, const WlPmWpa *w);
/* Active pixels held (counts: rounded). */
uint64_t wl_pm_rung_image_active(const WlPmRungImage *im);

/* Runs `scheme` on images[n_procs] (borrowed, one rung, one size) as
 * pm_composite.h does (c's radices, bounding_rect, rle, order; the
 * operator does not matter).  Returns a new merge holding steps and
 * totals (image and held NULL); free with wl_pm_rung_merge_free().
 * *stages (may be NULL) gets the plan's stage count. */
WlPmMerge *wl_pm_rung_run(WlPmScheme scheme, const WlPmCompose *c,
                          WlPmRungImage *const *images, guint n_procs,
                          const WlPmFormat *fmt, guint *stages);
void wl_pm_rung_merge_free(WlPmMerge *m);

/* What a fragment holds: active pixels, runs (linear order, or the
 * box's rows when box_mode), and the bounding box of its active pixels
 * x0, x1, y0, y1 (inclusive; any FALSE when it holds none). */
typedef struct {
    uint64_t active, runs;
    gboolean any;
    guint box[4];
} WlPmMeasure;

/* An image representation a plan runs on (every rung: pixels in
 * pm_composite.c, runs and counts in pm_runs.c): a process holds an
 * array of elements sorted by linear index; slice copies those of el
 * (NULL: none) inside [a, b) into a new array, over composites front
 * over back (both consumed) into a new one, measure says what a
 * fragment holds.  ctx is theirs. */
typedef struct {
    GArray *(*slice)(const void *ctx, const GArray *el, uint64_t a,
                     uint64_t b);
    GArray *(*over)(const void *ctx, GArray *front, GArray *back);
    void (*measure)(const void *ctx, const GArray *el, gboolean box_mode,
                    WlPmMeasure *m);
    const void *ctx;
} WlPmRep;

/* Runs scheme's plan (pm_stages.h) for n_procs processes on an image of
 * npix locations `width` wide, as pm_composite.h describes (c's radices,
 * bounding_rect, rle, order): el[p] is processor p's image (consumed),
 * replaced by its final piece (empty when it ends inactive); the steps
 * are appended to steps.  Returns the plan's stage count. */
guint wl_pm_plan_run(const WlPmRep *rep, WlPmScheme scheme,
                     const WlPmCompose *c, GArray **el, guint n_procs,
                     guint width, uint64_t npix, const WlPmFormat *fmt,
                     GPtrArray *steps);

/* The messages msgs (WlPmMsg, freed) of n processes in sender order,
 * stably (the replay's order): a new array of at least one slot. */
WlPmMsg *wl_pm_msgs_by_sender(GArray *msgs, guint n);

/* Locations of the linear range [a, b) inside box x0..x1, y0..y1
 * (inclusive) of a screen `width` wide: O(1). */
uint64_t wl_pm_box_locations(guint width, uint64_t a, uint64_t b,
                             const guint *box);

#endif
