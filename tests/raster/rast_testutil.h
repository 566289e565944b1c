/* rast_testutil.h — shared helpers for the raster test suites.
 *
 * A coverage sink counting how many spans touch each pixel (to prove
 * watertightness: every pixel exactly once), screen-space vertex
 * constructors, and a renderer of a mesh through both z-buffers.
 */
#ifndef PGSIM_TESTS_RASTER_TESTUTIL_H
#define PGSIM_TESTS_RASTER_TESTUTIL_H

#include "sim/core/rng.h"
#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"

typedef struct {
    int width, height;
    uint16_t *count; /* spans covering each pixel */
    uint64_t spans;
} TuCoverage;

TuCoverage *tu_coverage_new(int width, int height);
void tu_coverage_free(TuCoverage *cv);
RastSpanSink tu_coverage_sink(TuCoverage *cv);
/* Pixels covered exactly k times. */
uint64_t tu_coverage_count(const TuCoverage *cv, unsigned k);
/* Largest coverage of any pixel. */
unsigned tu_coverage_max(const TuCoverage *cv);

/* A screen vertex at pixel coordinates (x, y), snapped. */
RastScreenVert tu_sv(double x, double y, double z);

/* Scan converts the triangle with vertices in pixel coordinates if its
 * snapped area is not zero; returns FALSE if it is degenerate. */
gboolean tu_scan(double ax, double ay, double bx, double by, double cx,
                 double cy, uint32_t prim, int w, int h, RastSpanSink sink,
                 RastCounters *c);

/* A clip-space vertex (w = 1 unless given) with a colour. */
RastVert tu_cv(double x, double y, double z, double w);

/* Renders polygons of mesh (identity model, white tint) with `view`
 * through the full z-buffer and through the modified scanline z-buffer;
 * returns both images (new) and adds the work to the counters. */
void tu_render_both(const RastView *view, const SceneMesh *m,
                    const uint32_t *subset, guint n_subset, RastImage **full,
                    RastImage **scan, RastCounters *cf, RastCounters *cs);

/* A UV sphere of radius r about the origin with inward (invert = TRUE)
 * or outward facing polygons (quads, triangles at the poles). */
SceneMesh *tu_sphere(double r, int slices, int stacks, gboolean invert);
/* Random coloured triangles in [-1,1]^3 (object = clip space when the
 * view is the identity). */
SceneMesh *tu_random_tris(uint64_t seed, int n, double size);

#endif
