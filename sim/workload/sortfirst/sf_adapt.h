/* sf_adapt.h — adaptive screen regions for sort-first (seed 000 §1.2:
 * "Adaptive screen-space partitioning is a good load-balancing solution
 * for SF, but it requires estimating the primitive work distribution
 * over the screen [12]"; [12] Mueller, "The Sort-First Architecture for
 * High-Performance Graphics", I3D 1995: the mesh-based median-cut
 * hierarchical decomposition, MAHD).
 *
 * The estimate: a G x G grid of screen cells.  During its sort each
 * master adds, for every on-screen instance of its chunks, the chunk's
 * polygon count to the cell holding the centre of the instance's screen
 * rectangle (clamped to the screen); the masters' grids are summed (the
 * sum is what every processor holds after the exchange, sf_frame.h).
 *
 * Each master's grid is sent dense (G^2 counts) or sparse (a list of
 * (cell, count) pairs for its non-zero cells), whichever is smaller:
 * `nz` holds, per processor, the distinct cells its masters added to.
 *
 * The split: a k-d tree over the grid.  A node of k processors is cut
 * into k/2 and k - k/2 processors at the cell boundary that minimises
 * the larger of the two sides' weight per processor (the weighted
 * median: left weight ~ W (k/2) / k), ties broken towards the cut
 * proportional to area; each side keeps at least enough cells for its
 * processors (enough for every level of the split below it, not only
 * one cell each).  The cut runs across the node's longer side (in cells),
 * the other side only when the longer cannot hold both halves.  Leaves are the P regions, cell
 * boundaries mapped to pixels as i W / G.  Deterministic (integer
 * weights, fixed order).  The split reads a node's line weights from a
 * summed-area table of the grid (built once, G^2 cells) in four loads a
 * line, counted as two cell visits.  Work: O(instances) to estimate,
 * O(G^2 + G P) cells visited to split.
 */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_ADAPT_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_ADAPT_H

#include "sim/workload/sortfirst/sf_db.h"
#include "sim/workload/sortfirst/sf_regions.h"

typedef struct {
    guint grid;       /* G */
    guint procs;      /* P */
    uint64_t *weight; /* G x G polygons per cell, row-major */
    uint64_t *added;  /* per processor: instances its masters added */
    uint64_t *nz;     /* per processor: distinct cells its masters added to */
    const guint *master; /* per chunk: its master now (borrowed); NULL:
                            the database's fixed masters */
    guint8 *mark;     /* P x G^2 bits: cell touched by processor p */
    double *factor;   /* G x G cost per polygon (calibrated), else 1 */
    gboolean calibrated;
    /* Motion prediction (wl_sf_adapt_predict): per chunk instance its
     * screen centre in the last estimate, pixels; NULL when off. */
    float *last_x, *last_y;
    guint8 *last_ok; /* 1: on screen in the last estimate */
    guint n_insts;
    uint64_t predicted; /* instances placed by extrapolation, last call */
} WlSfAdapt;

/* grid in 1 .. 1024 with wl_sf_adapt_fits(grid, procs). */
WlSfAdapt *wl_sf_adapt_new(guint grid, guint procs);
/* Whether the split can give each of procs processors a region of a
 * grid x grid estimate (more than grid^2 >= procs: see the split). */
gboolean wl_sf_adapt_fits(guint grid, guint procs);
void wl_sf_adapt_free(WlSfAdapt *a);
/* Clears, then adds every on-screen chunk instance under view_proj
 * (regions give the screen size). */
void wl_sf_adapt_estimate(WlSfAdapt *a, const WlSfDb *db,
                          const WlSfRegions *r, Mat4 view_proj);
/* Turns on motion prediction for a database of n_insts chunk
 * instances: from then on each estimate places an instance that was on
 * screen in the previous estimate too at its linear extrapolation one
 * frame ahead, 2 c_now - c_last (clamped to the screen), so the split
 * made from frame f's sort estimates frame f + 1, the frame it serves.
 * Exact for constant screen velocity; the camera's revolution makes
 * screen motion curve, so the error grows with its second derivative.
 * Costs each master 2 floats and a flag per instance it estimates. */
void wl_sf_adapt_predict(WlSfAdapt *a, guint n_insts);
/* With prediction on: the instances were renumbered (edits, sf_edit.h);
 * map[i] is new instance i's old number, or -1 for a new one, which has
 * no history (n new instances). */
void wl_sf_adapt_remap(WlSfAdapt *a, const gint64 *map, guint n);
/* Splits the screen into r->procs regions (r->rect) of equal estimated
 * weight; returns the cells visited. */
uint64_t wl_sf_adapt_split(const WlSfAdapt *a, WlSfRegions *r);
/* Measured correction: work[p] is processor p's region work in the
 * frame whose regions are r and whose estimate is the grid now held;
 * each cell's factor becomes its owner's work per estimated polygon
 * (the mean over processors for a region with no polygons). */
void wl_sf_adapt_calibrate(WlSfAdapt *a, const WlSfRegions *r,
                           const double *work);
/* The estimated weight inside pixel rectangle q (cells whose top-left
 * corner lies in it), for tests and reports. */
uint64_t wl_sf_adapt_weight_in(const WlSfAdapt *a, const WlSfRegions *r,
                               WlSfRect q);

#endif
