/* pphigs_pixels.h — what a Pixel-Planes 5 renderer draws: primitives as
 * linear expressions, evaluated at every pixel of a 128x128 region.
 *
 * Fuchs et al. 1989 (Pixel-Planes 5) and seed 001 §1.1: a GP turns each
 * transformed primitive into the coefficients of linear expressions
 * A x + B y + C — one per edge, one for z, one per colour channel — and
 * sends them to the renderer that owns the region; every pixel processor
 * of the renderer's 128x128 array evaluates them at its own (x, y) at
 * once, keeps the pixel if it is inside every edge and wins the
 * visibility compare, and stores the colour.
 *
 * Pixel rule (ours, stated so that serial and distributed renders agree
 * to the pixel): expressions are evaluated at pixel centres in absolute
 * screen coordinates (x right, y down), so a pixel computes the same
 * value in any region; a pixel on an edge (E == 0) belongs to the side
 * with A > 0, or A == 0 and B > 0, so two polygons sharing an edge never
 * both draw it (the neighbour's expression is the exact negation).
 *
 * Visibility (seed 001 §4, the "priority buffer"): one 64-bit key per
 * pixel, the larger wins.  The top bit separates 3D primitives (0) from
 * order-dependent ones (1, drawn over every 3D primitive); below it a 3D
 * primitive keeps its inverted 32-bit depth and an ODP its priority; the
 * low 31 bits of a 3D key hold the primitive's tag, so equal depths are
 * decided the same way in any order.  The result is independent of the
 * order in which primitives reach a pixel: the serial render, the
 * distributed one and any renderer interleaving give the same image.
 *
 * Geometry: polygons are clipped against the near plane (w > 1e-6) in
 * homogeneous coordinates and treated as convex; a strip gives one
 * command per triangle; pixels with z outside [-1, 1] are not drawn.
 * A line is a quad one pixel wide along its projected segment (clipped
 * at the near plane), z linear along it, its colour unshaded: 4 edge, 1
 * z and 3 colour linear expressions.  A sphere is drawn with the
 * renderers' quadratic expression evaluator (fuchs89: "parallel
 * quadratic expression evaluation for every pixel"): its screen disc
 * Q = r^2 - (x - cx)^2 - (y - cy)^2 >= 0, r the largest screen distance
 * from the projected centre to the projected ends of its three axes;
 * z = z_c - dz Q / r^2 (dz the largest depth offset of those ends: the
 * front bulges toward the eye); colour times 0.3 + 0.7 Q / r^2: five
 * quadratic expressions, no linear one.  A sphere whose centre or axis
 * ends are not in front of the near plane is not drawn.
 * Colour: the inherited colour, flat, times 0.3 + 0.7 |n_z| of the
 * polygon's normal in normalised device coordinates (a GP's shading).
 *
 * Cost: building a command O(vertices); drawing O(edges) per pixel of the
 * command's box within the region.
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_PIXELS_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_PIXELS_H

#include "sim/raster/image.h"
#include "sim/scene/structdb.h"

#define WL_PPHIGS_MAX_EDGES 24

typedef struct {
    double a, b, c; /* a x + b y + c at a pixel centre */
} WlPphigsLin;

/* One renderer command: a convex polygon's expressions. */
typedef struct {
    WlPphigsLin edge[WL_PPHIGS_MAX_EDGES];
    WlPphigsLin z;       /* NDC z */
    guint nedges;
    int x0, y0, x1, y1;  /* pixel box on the screen, inclusive */
    uint32_t rgba;       /* 0xAABBGGRR */
    gboolean odp;        /* order-dependent: drawn by priority */
    int64_t priority;    /* ODP priority */
    uint32_t tag;        /* tie-break of equal depths */
    gboolean sphere;     /* a sphere: the fields below, no edges */
    double cx, cy, r2;   /* its screen disc: centre, radius^2 (pixels) */
    double zc, dz;       /* z at the rim, its rise toward the centre */
    Vec3 color;          /* its colour, shaded per pixel */
} WlPphigsCmd;

/* Appends to out (GArray of WlPphigsCmd) the commands of a primitive
 * instance seen through vp on a width x height screen: none when it is
 * degenerate or wholly behind the eye or off the screen, or when its
 * outline, clipped at the near plane, has more than
 * WL_PPHIGS_MAX_EDGES vertices.  Returns how
 * many were appended. */
guint wl_pphigs_cmds(const ScenePrimInst *pi, Mat4 vp, guint width,
                     guint height, GArray *out);

/* The linear expressions a renderer evaluates for c: its edges, z and
 * three colour channels (a sphere: none). */
guint wl_pphigs_cmd_exprs(const WlPphigsCmd *c);
/* The quadratic expressions it evaluates: a sphere's 5, else 0. */
guint wl_pphigs_cmd_quads(const WlPphigsCmd *c);

/* A region of the screen as one renderer holds it: keys and colours. */
typedef struct {
    int x0, y0, w, h;
    uint64_t *key;  /* 0: empty */
    uint32_t *rgba;
} WlPphigsRegion;

/* A cleared region (keys 0, colour bg); free with wl_pphigs_region_free().*/
WlPphigsRegion *wl_pphigs_region_new(int x0, int y0, int w, int h,
                                     uint32_t bg);
void wl_pphigs_region_free(WlPphigsRegion *r);
/* Every pixel of r evaluates c; returns the pixels c won. */
uint64_t wl_pphigs_region_draw(WlPphigsRegion *r, const WlPphigsCmd *c);
/* Copies r's colours into its place in img. */
void wl_pphigs_region_store(const WlPphigsRegion *r, RastImage *img);

/* The serial reference: every primitive of db, in traversal order,
 * drawn on one region covering the screen.  A new image (black
 * background); free with rast_image_free(). */
RastImage *wl_pphigs_render_serial(const SceneDb *db, Mat4 vp, guint width,
                                   guint height);

#endif
