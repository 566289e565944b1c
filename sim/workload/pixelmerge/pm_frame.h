/* pm_frame.h — one frame of object-space parallel rendering with active
 * pixel merging (seed 003): local span lists and modified scanline
 * z-buffer on every processor (pm_render.h), the merge with a scheme and
 * a load balancing (pm_merge.h, pm_balance.h), timed on a hypercube
 * (pm_replay.h).  The engine-free parts are real: pixels, counts, the
 * merged image; time comes from counts x costs and from the network.
 *
 * The compositing schemes (pm_composite.h) take the place of the merge:
 * no scanline partition and no global sum; P need not be a power of
 * two; with the over operator the image is checked against the serial
 * front-to-back blend of the processors' local images.  With block
 * images (pm_images.h) the local images are the blocks', composited in
 * their visibility order from the view, and checked against the serial
 * render too.
 *
 * Phases are separated by a barrier, as the per-phase times of Table 2
 * imply: span_ms and zbuf_ms are the largest processor's busy time in the
 * phase, merge_ms runs from the end of the slowest local z-buffer to the
 * end of the last merge.  ZBUF-EXC builds unsorted span lists (no
 * insertion steps) and z-buffers into a full N x N buffer (initialised:
 * N^2 x zbuf_init, every pixel compared); active-pixel schemes use sorted
 * span lists and the modified scanline z-buffer (comparisons only where
 * spans of the row overlap, no initialisation) (§2, §5).
 * Cost: O(polygons + pixels x log P + N P) plus O(P N^2) for ZBUF-EXC.
 */
#ifndef PGSIM_WORKLOAD_PIXELMERGE_PM_FRAME_H
#define PGSIM_WORKLOAD_PIXELMERGE_PM_FRAME_H

#include "sim/raster/image.h"

#include "sim/scene/scene.h"
#include "sim/workload/pixelmerge/pm_composite.h"
#include "sim/workload/pixelmerge/pm_images.h"
#include "sim/workload/pixelmerge/pm_render.h"
#include "sim/workload/pixelmerge/pm_replay.h"
#include "sim/workload/pixelmerge/pm_rung.h"

typedef struct {
    WlPmScheme scheme;
    WlPmBalance balance;
    guint procs;      /* P, a power of two for Kurç's schemes */
    guint resolution; /* N: the screen is N x N */
    WlPmSplit split;
    WlPmFormat fmt;
    gboolean check_image; /* compare with the serial render */
    gboolean cull_back;   /* drop back-facing polygons before scanning */
    RastSpanRule span_rule; /* exact coverage or both end points (scan.h) */
    gboolean keep_image;  /* return the merged image (WlPmFrameOut.image) */
    WlPmCompose comp;     /* the compositing schemes' options */
    WlPmImages images;    /* the local images: the scene's or blocks' */
    WlPmRung rung;        /* image fidelity (pm_rung_frame.h); pixels */
} WlPmSetup;

/* Node costs of the local phases, per counted operation. */
typedef struct {
    SimTime polygon;     /* transform, light, clip, set up one polygon */
    SimTime span;        /* generate one span */
    SimTime insert_step; /* one step of sorted insertion into a list */
    SimTime pixel;       /* interpolate and shade one generated pixel */
    SimTime zcompare;    /* one depth comparison */
    SimTime scanline;    /* per-scanline loop of the z-buffer */
    SimTime zbuf_init;   /* clear one entry of a full z-buffer */
    WlPmMergeCosts merge;
} WlPmCosts;

typedef struct {
    double span_ms, zbuf_ms, merge_ms, frame_ms;
    uint64_t polygons, tpg, tpf; /* Table 1 counts of the whole scene */
    uint64_t concurrent_volume;  /* bytes, Fig. 1 */
    uint64_t merge_bytes;        /* pixel bytes sent in the merge */
    uint64_t merge_msgs;         /* messages sent in the merge */
    uint64_t merge_records;      /* pixel records (or locations) sent */
    guint stages;                /* compositing stages (0: Kurç's) */
    double load_imbalance;       /* merge operations, Fig. 2 */
    double partition_imbalance;  /* pixels z-buffered per owner (AAPC) */
    gboolean image_checked, image_ok;
    SimBusy *busy;      /* per processor: phases "span", "zbuf", "merge" */
    WlPmCounts *counts; /* per processor: its local rendering counts */
    uint64_t *active;   /* per processor: its local foremost pixels */
    RastImage *image;   /* the merged frame when keep_image, else NULL */
} WlPmFrameOut;

/* Renders and merges one frame of `scene` (its frame-0 camera) on `net`
 * (P <= its nodes; the engine is net's) without machine processors:
 * every compute is priced at c and is an engine event; starts at the
 * engine's current time, which it advances to the frame's end; fills
 * *out (free its busy with wl_pm_frame_out_clear()).  FALSE with *err on
 * engine failure. */
gboolean wl_pm_frame_run(NetNet *net, const Scene *scene, const WlPmSetup *s,
                         const WlPmCosts *c, WlPmFrameOut *out, GError **err);
/* The same for the scene's camera of frame `frame`, computing on machine
 * processors procs[0 .. P-1] (borrowed; NULL: as wl_pm_frame_run): each
 * is charged its span, zbuf and merge work once, as named counts priced
 * by its kind (mach_proc_compute_ops), in the engine's phases "span",
 * "zbuf" and "merge"; the frame's times and out->busy are read from
 * them, and c supplies only the merge's count_bytes. */
gboolean wl_pm_frame_run_procs(NetNet *net, MachProc *const *procs, guint frame,
                               const Scene *scene, const WlPmSetup *s,
                               const WlPmCosts *c, WlPmFrameOut *out,
                               GError **err);
void wl_pm_frame_out_clear(WlPmFrameOut *out, guint procs);

/* Time of the local phases of the whole scene on one processor (the
 * sequential renderer of the speed-up), in ms.  *insert_ms (may be NULL)
 * gets the part of it spent inserting spans into the sorted row lists:
 * s (s - 1) / 4 steps for s spans on a row, the one cost that falls
 * faster than 1/P when P nodes share the polygons, and so the modelled
 * cause of a speed-up above P. */
double wl_pm_serial_ms(const Scene *scene, const WlPmSetup *s,
                       const WlPmCosts *c, double *insert_ms);

#endif
