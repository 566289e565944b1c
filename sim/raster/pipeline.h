/* pipeline.h — the geometry pipeline: transform, shade, clip, cull, scan.
 *
 * One polygon at a time (polygons are independent, as in the object-space
 * parallel renderers of seeds 000–003, so any subset of a mesh can be
 * rasterised on its own):
 *
 *   1. transform each vertex by view-projection x model (counted);
 *   2. light: flat (one colour per polygon from its Newell normal) or
 *      Gouraud (one colour per vertex from the vertex normals), two-sided
 *      Lambert with an ambient term; or the raw colours, unlit;
 *   3. trivially reject polygons outside one clip plane; clip the rest
 *      homogeneously (clip.h: near, far, w > 0, guard band);
 *   4. viewport + snap to fixed point (scan.h); cull back faces and
 *      drop zero-area polygons by the exact integer signed area;
 *   5. fan-triangulate the clipped polygon and scan-convert each triangle
 *      into spans (top-left rule) sent to a sink: a span list for the
 *      modified scanline z-buffer, or a full z-buffer directly; or, with
 *      span_rule RAST_SPAN_ENDPOINTS, scan the whole polygon at once, one
 *      span per row including both end points (scan.h).
 *
 * Primitive ids are the polygon's index plus `id_base`; they decide depth
 * ties (scan.h), so give every polygon of a frame a distinct id (e.g. its
 * index in scene_flatten()'s mesh) for order-independent images.
 *
 * Front faces are counter-clockwise in normalised device coordinates
 * (OpenGL).  Polygons of more than RAST_POLY_MAX vertices are split into
 * fan triangles first; each piece is then counted as a primitive.
 * Cost: O(n) per n-gon plus O(rows) per triangle for set-up.
 */
#ifndef PGSIM_RASTER_PIPELINE_H
#define PGSIM_RASTER_PIPELINE_H

#include "sim/raster/scan.h"
#include "sim/scene/scene.h"

/* Largest polygon clipped whole (clip.h: RAST_CLIP_MAX - 7). */
#define RAST_POLY_MAX 9

typedef enum { RAST_SHADE_FLAT, RAST_SHADE_GOURAUD } RastShading;

typedef struct {
    Mat4 view_proj;         /* world -> clip */
    int width, height;      /* viewport in pixels (<= RAST_MAX_SIDE) */
    gboolean cull_back;     /* drop back-facing polygons (default TRUE) */
    RastSpanRule span_rule; /* default RAST_SPAN_EXACT (scan.h) */
    gboolean lighting;      /* FALSE: colours used as given (default TRUE) */
    RastShading shading;    /* default RAST_SHADE_GOURAUD */
    Vec3 light_dir;         /* world space, towards the light (unit) */
    float ambient, diffuse; /* default 0.25, 0.75 */
} RastView;

/* A view with the defaults above and the light along +z. */
RastView rast_view_make(Mat4 view_proj, int width, int height);
/* A view for a scene camera: its view-projection with aspect set to
 * width / height, and a light over the viewer's right shoulder. */
RastView rast_view_for_camera(const SceneCamera *cam, int width, int height);

/* Some polygons of a mesh, by index (borrowed). */
typedef struct {
    const uint32_t *ids;
    guint n;
} RastSubset;

/* Rasterises polygons of `m` placed by `model` (object -> world), colours
 * multiplied by `tint`.  `subset` lists the polygons drawn (NULL, or a
 * NULL ids: all);
 * primitive id = id_base + polygon index.  Spans go to `sink`; work is
 * added to *c. */
void rast_draw_mesh(const RastView *v, const SceneMesh *m, Mat4 model,
                    SceneColor tint, uint32_t id_base, const RastSubset *subset,
                    RastSpanSink sink, RastCounters *c);

/* Rasterises every instance of a scene; ids are consecutive over the
 * instances' polygons in instance order (the order of scene_flatten()). */
void rast_draw_scene(const RastView *v, const Scene *s, RastSpanSink sink,
                     RastCounters *c);

/* The low-level entry: one convex polygon already in clip space
 * (3 <= n <= RAST_POLY_MAX), colours final.  Counts it as one primitive. */
void rast_draw_clip_polygon(const RastView *v, const RastVert *in, int n,
                            uint32_t prim, RastSpanSink sink, RastCounters *c);

#endif
