/* sf_frame.h — sort-first frames on a simulated machine (seed 000 §1.2,
 * §3.3.2, §3.4.3-§3.4.4, §4.1).
 *
 * A frame, on each of the P processors (machine processors of the kind
 * `node`, 0 .. P-1, which are also network endpoints):
 *
 *   sort     the bucket sort and cull tests of sf_book.h: each box is
 *            8 corner transforms (8 x transform_vertex);
 *   pack     chunk data copied into the outgoing buffers (chunk_pack per
 *            polygon); then one message to every other processor with
 *            what it needs (real sizes, sf_book.h WlSfSizes); an empty
 *            message is the end-of-sort marker, so a processor knows
 *            when all of the frame's chunks have arrived;
 *   unpack   after its sort and all P - 1 messages: received chunks
 *            stored (chunk_pack per polygon), new chunks cull-tested;
 *   render   the chunk instances overlapping its region, through
 *            sim/raster with the frame's camera, spans clipped to the
 *            region: transform_vertex per vertex, span_create per span,
 *            pixel_zbuffer per pixel inside the region.
 *
 * With adaptive regions (WlSfSetup.adaptive, sf_adapt.h) the sort also
 * adds each on-screen instance of p's master chunks to p's work grid
 * (grid_cell per instance), every message carries the sender's grid
 * (an all-gather riding on the exchange: G^2 x bytes.cell dense, or
 * 2 x bytes.cell per non-zero cell sparse, whichever is smaller), and
 * after rendering each processor adds the P - 1 received grids to its
 * own and computes the k-d split (grid_cell per cell of its own grid,
 * per entry added and per cell the split visits; phase `partition`),
 * which gives the regions of the next frame.  With `predict` the
 * previous frame's estimate places each instance at its one-frame
 * extrapolation (sf_adapt.h; one more grid_cell per instance).  Frame 0
 * uses the static grid.  With `current` (WlSfSetup.current) the
 * estimate is an extra pass before the sort instead: each processor
 * transforms its master boxes and fills its grid (phase `estimate`),
 * sends the grid to every other processor, and on holding all P sums
 * them and splits (phase `partition`), then bucket-sorts into the
 * regions just made (its master boxes are not transformed again).
 * `feedback` scales each cell by the measured region work per estimated
 * polygon of the processor that owned it (sf_adapt.h), the figures
 * riding 8 B a message.
 *
 * With pull migration (WlSfSetup.mig, sf_book.h) the sort pass is the
 * pull pass (8 x transform_vertex per box of every chunk instance, held
 * or not); then each processor sends a request only to the masters it
 * needs chunks from (bytes.request per chunk) and renders when every
 * answer is in; a master serves a request when it arrives, behind the
 * work it has already queued (FIFO), taking the request's interrupt
 * (request_interrupt, phase `interrupt`) and packing the chunks
 * (chunk_pack per polygon, phase `pack`) before the answer goes out.
 * Dynamic mastership (WlSfSetup.ms) rides on the push exchange
 * (bytes.mastership per chunk handed over); with WlSfSetup.off spread
 * the off-screen masters are made even after the sorts
 * (sf_mastership.c).
 *
 * Traversal (sf_trav.h, WlSfSetup.trav): the first pass of the frame
 * (the sort, or the estimate with `current`) starts with the
 * processor's traversal of the replicated hierarchy, phase `traverse`:
 * node_visit per structure instance scanned plus 8 x transform_vertex
 * per volume test; the chunk boxes in culled subtrees are not
 * transformed by the sort.
 *
 * Edits (WlSfSetup.edits, sf_edit.h): before frame f >= 1 the editor
 * changes the database and the book; processor 0 (the application's,
 * an assumption) sends the frame's commands to every other processor
 * (bytes.message + bytes.edit per command), and each starts its first
 * pass when they are in, after phase `edit`: node_visit per command
 * and (max-set) per max-set node created or collected, pointer_update
 * per pointer its book created or collected.
 *
 * The frame ends when every processor has rendered and, with a frame
 * buffer (WlSfSetup.fb, sf_fbuf.c), every region's pixels are read out,
 * sent and assembled at the frame-buffer node; the next frame then
 * starts.  The regions'
 * pixels land in one frame z-buffer: with `check_image` it is compared
 * with the serial render of every polygon (same primitive ids), and the
 * migration invariant (sf_book.h) is checked; a failure stops the run.
 *
 * Ownership: machine, scene and database are borrowed and must outlive
 * the run.  Cost per frame O(P x chunk instances + polygons rendered +
 * pixels), plus the serial render when checking.
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_FRAME_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_FRAME_H

#include "sim/machine/machine.h"
#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"
#include "sim/raster/prerender.h"
#include "sim/scene/scene.h"
#include "sim/workload/sortfirst/sf_book.h"
#include "sim/workload/sortfirst/sf_bv.h"
#include "sim/workload/sortfirst/sf_edit.h"
#include "sim/workload/sortfirst/sf_trav.h"

/* Cost operations of the `node` kind (NULL-terminated). */
extern const char *const wl_sf_cost_ops[];
/* The same, declared for the machine (WlOps.needs; costs.h). */
extern const MachNeed wl_sf_needs[];

typedef struct {
    SimTime transform_vertex, span_create, pixel_zbuffer, chunk_pack;
    SimTime grid_cell, node_visit, pointer_update;
    SimTime sphere_bound; /* a sphere's screen bounds (sf_bv.h) */
    SimTime request_interrupt, pixel_readout, pixel_assemble;
} WlSfCosts;

/* The frame buffer (sf_fbuf.c): none (a frame ends when every region is
 * rendered) | node (the regions' pixels read out, sent to the frame-
 * buffer node and assembled there). */
typedef enum { WL_SF_FB_NONE, WL_SF_FB_NODE } WlSfFrameBuffer;
extern const char *const wl_sf_framebuffer_names[]; /* none, node */

typedef struct {
    guint procs;
    int resolution; /* N x N screen */
    WlSfBookkeeping bk;
    WlSfMigration mig;  /* push | pull (pull: min-set, fixed, static) */
    WlSfMastership ms;  /* fixed | dynamic (push only) */
    WlSfSizes sizes;
    gboolean cull_back, check_image;
    gboolean adaptive; /* regions re-split each frame (sf_adapt.h) */
    guint grid;        /* G of the adaptive work grid, <= resolution */
    gboolean current;  /* estimate from this frame (an extra pass and
                          exchange before the sort), else the previous */
    gboolean predict;  /* previous-frame estimate, each instance moved
                          to its extrapolation one frame ahead */
    gboolean feedback; /* weight cells by measured work per polygon */
    WlSfTravMode trav; /* §3.5 traversal (sf_trav.h); plain for pull */
    RastPrerenderSet *pre; /* NULL: each region rasterised; else, with no
                              image wanted (check_image, a hook), counts
                              from each frame rasterised once and kept
                              here by frame number, for runs of one scene
                              at one resolution (prerender.h); not with
                              edits */
    WlSfScreenSet *screens; /* NULL: the instances' screen rectangles
                               computed each frame; else kept here by
                               frame number, for runs of one database's
                               boxes, scene and resolution (sf_regions.h);
                               not with edits */
    gboolean edits;    /* an editor will be set (phase `edit`) */
    WlSfFrameBuffer fb; /* frame buffer: none (0) | node (sf_fbuf.c) */
    uint64_t pixel_bytes; /* per pixel sent to it (workload bytes.pixel) */
    WlSfOffscreen off;  /* dynamic: keep (0) | spread (sf_mastership.c) */
} WlSfSetup;

/* One frame's figures (sums over processors unless said). */
typedef struct {
    SimTime start, end;
    uint64_t migrated_chunks, migrated_polys, migrated_insts;
    uint64_t migrated_bytes, messages;
    uint64_t master_boxes, slave_boxes, new_boxes, deleted_chunks;
    uint64_t probe_boxes; /* pull: boxes of chunks not held */
    uint64_t polys_rendered;     /* polygons transformed for rendering */
    uint64_t load_max, load_min; /* polygons rendered per processor */
    double poly_imbalance;       /* max / mean polygons rendered */
    double imbalance;            /* max / mean busy time (work) */
    uint64_t estimate_bytes;     /* grid bytes sent (adaptive) */
    uint64_t estimate_cells;     /* grid cells added, summed, visited */
    double split_imbalance;      /* max / mean estimated weight over the
                                    regions the split made (adaptive) */
    uint64_t onscreen_insts;     /* chunk instances in some region */
    uint64_t region_insts;       /* Σ regions over them */
    double box_side;             /* Σ over them: √ screen box area, px */
    uint64_t pixels;             /* pixels z-buffered in the regions */
    uint64_t peak_memory;        /* largest processor's store, bytes */
    uint64_t requests;           /* pull: chunks requested */
    uint64_t handovers;          /* dynamic: masterships passed on */
    uint64_t held_polys;         /* Σ over processors of polygons held */
    double master_imbalance;     /* max / mean master polygons */
    uint64_t offscreen_max;      /* most off-screen master polygons on
                                    one processor (no instance in any
                                    region) */
    uint64_t offscreen_total;    /* off-screen master polygons, all */
    WlSfTrav trav;               /* §3.5 counts, all processors */
    SimTime traverse_busy;       /* Σ over processors: traversal time
                                    charged (nodes, volume tests) */
    uint64_t edits;              /* edit commands applied (sf_edit.h) */
    uint64_t edit_bytes;         /* command messages + the pointers
                                    masters sent for instances the edits
                                    created (max-set) */
    uint64_t nodes_created, nodes_collected; /* max-set nodes */
    uint64_t pointers_collected; /* max-set pointers garbage-collected */
    uint64_t chunks_collected;   /* slave copies deleted, no instance */
    SimTime edit_busy;           /* Σ over processors: edit time */
    uint64_t spread;             /* dynamic: off-screen chunks moved */
    uint64_t interrupts;         /* pull: requests served (interrupts) */
    SimTime interrupt_busy;      /* pull: their time, all masters */
    uint64_t fb_bytes;           /* bytes sent to the frame buffer */
    SimTime fb_busy;             /* the frame buffer's assembly time */
    double utilisation;          /* busy / (P x frame time) */
    gboolean image_checked, image_ok;
} WlSfFrameStats;

typedef struct WlSfRun WlSfRun;

/* workload.framebuffer, workload.offscreen and bytes.pixel into *s
 * (sf_fbuf.c; defaults node, spread, 4 B). */
gboolean wl_sf_parse_costed(const CfgNode *sec, WlSfSetup *s, GError **err);
/* The metrics of the frame buffer, the pull interrupt and the
 * off-screen spread, means over frames from `from` (sf_fbuf.c). */
void wl_sf_fill_costed_metrics(SimResult *out, const GArray *stats, guint from,
                               const WlSfSetup *s);

/* Checks the `node` kind has the cost operations and fills *c. */
gboolean wl_sf_costs_from_machine(const MachMachine *m, WlSfCosts *c,
                                  GError **err);
/* A new run (wl_sf_run_free) over processors node0 .. node<P-1>. */
WlSfRun *wl_sf_run_new(MachMachine *m, const Scene *scene, const WlSfDb *db,
                       const WlSfSetup *s, const WlSfCosts *c);
void wl_sf_run_free(WlSfRun *r);
/* Runs `frames` frames from the engine's present time (the engine stops
 * at `until`); FALSE with *err on an engine error, an image differing
 * from the serial render or a broken migration invariant. */
gboolean wl_sf_run_frames(WlSfRun *r, int frames, SimTime until, GError **err);
/* Per-frame figures (borrowed GArray of WlSfFrameStats). */
const GArray *wl_sf_run_stats(const WlSfRun *r);
/* The bookkeeping state (borrowed), for tests. */
const WlSfBook *wl_sf_run_book(const WlSfRun *r);
/* The regions the next frame will use (borrowed). */
const WlSfRegions *wl_sf_run_regions(const WlSfRun *r);
/* The last frame's image (borrowed; NULL before a frame, and when the
 * frames were counted from setup `pre`). */
const RastZBuffer *wl_sf_run_zbuffer(const WlSfRun *r);

/* Called after each frame's checks with the frame's assembled image
 * (the regions' pixels, borrowed); FALSE with *err stops the run. */
typedef gboolean (*WlSfFrameHook)(void *ctx, int frame,
                                  const RastZBuffer *zb, GError **err);
void wl_sf_run_set_hook(WlSfRun *r, WlSfFrameHook hook, void *ctx);
/* Edits between frames (sf_edit.h; borrowed, must edit the run's
 * database); needs WlSfSetup.edits; before the first frame. */
void wl_sf_run_set_edit(WlSfRun *r, WlSfEdit *e);

/* Renders the whole network serially for frame f into zb (cleared). */
void wl_sf_render_serial(const Scene *scene, const WlSfDb *db,
                         const WlSfSetup *s, guint frame, RastZBuffer *zb);

#endif
