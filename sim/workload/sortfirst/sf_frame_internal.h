/* sf_frame_internal.h — what the files of a sort-first run share: the
 * run's struct, a processor's per-frame state and the few helpers one
 * file uses from another.  Only sf_frame.c (the frame's events and the
 * run's lifetime), sf_render.c (rendering a region) and sf_figures.c
 * (the frame's figures) include it; users include sf_frame.h.
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_FRAME_INTERNAL_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_FRAME_INTERNAL_H

#include "sim/workload/sortfirst/sf_adapt.h"
#include "sim/workload/sortfirst/sf_frame.h"

typedef struct {
    WlSfRun *run;
    guint p;
    MachProc *proc;
    WlSfBatch *out; /* P batches: what p sends each processor */
    WlSfBookWork w;
    GArray *fresh; /* chunks received this frame */
    guint received;
    guint expect; /* pull: answers awaited (masters asked) */
    WlSfBatch *reply; /* pull: P batches, its answers to each */
    gboolean sorted;
    RastCounters rc; /* raster work (vertices, primitives ...) */
    uint64_t spans, pixels, polys;
    SimTime busy0; /* busy time at the frame's start */
    SimTime region_work; /* unpack + render: the work its region sets */
    guint grids;         /* estimate: grids received (current) */
    gboolean estimated;  /* estimate: own grid done (current) */
} WlSfProc;

struct WlSfRun {
    MachMachine *m;
    NetNet *net;
    SimEngine *eng;
    const Scene *scene;
    const WlSfDb *db;
    WlSfSetup s;
    WlSfCosts c;
    WlSfRegions regions, next; /* this frame's; the next frame's */
    WlSfAdapt *adapt;          /* NULL: static regions */
    double split_imbalance;    /* of the last split, over its estimate */
    uint64_t split_cells;      /* cells the next split visits */
    WlSfBook *book;
    WlSfProc *procs;
    RastView view;
    RastZBuffer *zb, *serial;
    GArray *stats;  /* WlSfFrameStats */
    GArray *render; /* scratch: instances */
    GArray *subset; /* scratch: polygons */
    int frame, frames;
    guint done;
    WlSfTrav trav;      /* this frame's §3.5 counts (sf_trav.h) */
    const WlSfScreen *scr; /* this frame's instance screen rectangles */
    WlSfScreen *scr_own;   /* their store without setup `screens` */
    WlSfTravProc *tp;   /* per processor: its traversal work */
    WlSfEdit *edit;     /* NULL: no edits (borrowed) */
    WlSfEditFrame ef;   /* this frame's edit work */
    WlSfRemapWork *ew;  /* per processor: its pointer work */
    WlSfFrameHook hook; /* NULL: none */
    void *hook_ctx;
    SimTime start;
    unsigned ph_sort, ph_pack, ph_unpack, ph_render, ph_partition;
    unsigned ph_estimate, ph_traverse, ph_edit;
    unsigned ph_interrupt, ph_readout, ph_assemble;
    MachProc *fb;       /* the frame-buffer node (sf_fbuf.c) */
    uint64_t fb_bytes;  /* this frame's bytes to it */
    SimTime fb_busy0;   /* its busy time at the frame's start */
};

/* ---- sf_render.c: a processor's region ---------------------------------- */

/* The camera view of frame `frame` at the setup's resolution. */
RastView wl_sf_frame_view(const Scene *scene, const WlSfSetup *s, guint frame);
/* Counts come from the frame rendered once (setup `pre`): no image. */
gboolean wl_sf_prerendered(const WlSfRun *r);
/* pr's region of r->render's instances: pixels into r->zb (or counts
 * from `pre`), its raster counts, spans, pixels and polygons in pr. */
void wl_sf_render_region(WlSfRun *r, WlSfProc *pr);

/* ---- sf_frame.c: what the frame's messages and edits carry -------------- */

/* Grid cells processor p handles after the exchange (adaptive). */
uint64_t wl_sf_partition_cells(const WlSfRun *r, guint p);
/* Bytes p's grid and region work add to each message it sends. */
uint64_t wl_sf_estimate_bytes(const WlSfRun *r, guint p);
/* The bytes of the frame's edit message to one processor. */
uint64_t wl_sf_edit_message(const WlSfRun *r);
/* p's edit work as named counts of the node's costs. */
MachOps wl_sf_edit_ops(const WlSfRun *r, guint p);

/* The frame's end, when every region is done (sf_fbuf.c calls it). */
void wl_sf_frame_end(WlSfRun *r, SimEngine *eng);

/* ---- sf_fbuf.c: the frame buffer ----------------------------------------- */

/* The frame-buffer node: node P when the machine has it, else node 0. */
MachProc *wl_sf_fbuf_proc(MachMachine *m, guint procs);
/* Pixels of p's region this frame, and the bytes of its message. */
uint64_t wl_sf_fbuf_pixels(const WlSfRun *r, guint p);
uint64_t wl_sf_fbuf_bytes(const WlSfRun *r, guint p);
/* pr has rendered: its region goes to the frame buffer (or, without
 * one, counts as done at once). */
void wl_sf_fbuf_region(WlSfRun *r, WlSfProc *pr);

/* ---- sf_figures.c: the frame's figures ---------------------------------- */

/* max / mean, 0 when the mean is 0. */
double wl_sf_max_over_mean(double max, double total, guint n);
/* The frame's figures into *st (start, end and trav set by the caller). */
void wl_sf_frame_sum(const WlSfRun *r, WlSfFrameStats *st);
/* The migration invariant and, with check_image, the image against the
 * serial render; FALSE with *err (an internal error) when one fails. */
gboolean wl_sf_frame_check(WlSfRun *r, WlSfFrameStats *st, GError **err);

#endif
