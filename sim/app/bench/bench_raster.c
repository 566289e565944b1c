/* bench_raster.c — `pgsim bench raster`: pipeline throughput.
 *
 * Times transform + clip + cull + scan conversion + z-buffering of whole
 * frames of a generated scene, repeated --frames times, with either the
 * full z-buffer (spans z-buffered as generated, cleared per frame) or
 * the modified scanline z-buffer of seed 003 (span list, sort, WPA/MSA).
 * Scenes: teapots (seed 003's N-teapot scene, 3,751 polygons each),
 * isosurface (the gyroid of sim/scene/isosurface.h, seed 004's kind of
 * data set; --grid 80 gives about 360,000 triangles, near seed 004's
 * 355,948).  Prints polygons, triangles (after fan splitting), TPG and
 * TPF per frame, then triangles/s and pixels/s (TPG per second); the
 * last line is "pixels_per_s: <number>".
 * Rates use the median frame time: wall clock, and also this thread's
 * CPU time (the "_cpu" lines), which a loaded shared machine disturbs
 * far less.  Timings are the only non-deterministic output.
 */
#include "sim/app/bench/bench.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"
#include "sim/scene/isosurface.h"
#include "sim/scene/teapots.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct {
    char *scene, *zbuffer;
    int size, frames, count, grid;
} BenchRasterOpts;

static double now_s(void)
{
    return g_get_monotonic_time() * 1e-6;
}

static double cpu_s(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0)
        return 0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of n frame times (robust to a loaded machine); sorts t. */
static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

static Scene *make_scene(const BenchRasterOpts *o, GError **err)
{
    if (g_strcmp0(o->scene, "teapots") == 0) {
        SceneTeapotsParams p = scene_teapots_defaults();
        p.polygons_per_teapot = 3751;
        p.count = (guint)o->count;
        return scene_teapots_new(&p, "--count", err);
    }
    if (g_strcmp0(o->scene, "isosurface") == 0) {
        SceneIsoParams p = scene_iso_defaults();
        p.grid = (guint)o->grid;
        return scene_iso_check(&p, "bench raster: --grid", err)
                   ? scene_iso_new(&p)
                   : NULL;
    }
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "bench raster: found --scene '%s', expected teapots or "
                "isosurface",
                o->scene);
    return NULL;
}

/* One frame; returns its counters. */
static RastCounters frame(const RastView *v, const Scene *s, gboolean full,
                          RastZBuffer *zb, RastSpanList *sl, RastActive *a)
{
    RastCounters c = {0};
    if (full) {
        rast_zbuffer_clear(zb);
        rast_draw_scene(v, s, rast_zbuffer_sink(zb), &c);
        c.winners += rast_zbuffer_covered(zb);
        return c;
    }
    rast_spanlist_clear(sl);
    rast_draw_scene(v, s, rast_spanlist_sink(sl), &c);
    rast_spanlist_sort(sl);
    rast_scanline_zbuffer(a, sl, &c);
    return c;
}

static void run(const BenchRasterOpts *o, const Scene *s)
{
    gboolean full = g_strcmp0(o->zbuffer, "full") == 0;
    SceneCamera cam = scene_camera_at(s, 0);
    RastView v = rast_view_for_camera(&cam, o->size, o->size);
    RastZBuffer *zb = full ? rast_zbuffer_new(o->size, o->size) : NULL;
    RastSpanList *sl = full ? NULL : rast_spanlist_new(o->size, o->size);
    RastActive *a = full ? NULL : rast_active_new(o->size, o->size);
    RastCounters c = frame(&v, s, full, zb, sl, a); /* warm-up */
    double *t = g_new(double, o->frames), *tc = g_new(double, o->frames);
    for (int i = 0; i < o->frames; i++) {
        double t0 = now_s(), c0 = cpu_s();
        frame(&v, s, full, zb, sl, a);
        t[i] = now_s() - t0;
        tc[i] = cpu_s() - c0;
    }
    double dt = median(t, o->frames), dc = median(tc, o->frames);
    g_free(t);
    g_free(tc);
    uint64_t tris = scene_n_triangles(s);
    char *line = rast_counters_format(&c);
    printf("scene %s, %dx%d, %s z-buffer, %d frames\n", o->scene, o->size,
           o->size, o->zbuffer, o->frames);
    printf("per frame: polygons %" G_GUINT64_FORMAT
           ", triangles %" G_GUINT64_FORMAT ", %s\n",
           scene_n_polys(s), tris, line);
    printf("median cpu_frame_ms: %.3f\n", dc * 1e3);
    if (dc > 0)
        printf("triangles_per_s_cpu: %.4g\npixels_per_s_cpu: %.4g\n", tris / dc,
               c.pixels / dc);
    printf("median frame_ms: %.3f\n", dt * 1e3);
    printf("triangles_per_s: %.4g\n", tris / dt);
    printf("pixels_per_s: %.4g\n", c.pixels / dt);
    g_free(line);
    rast_zbuffer_free(zb);
    rast_spanlist_free(sl);
    rast_active_free(a);
}

/* The image buffers and timings within the memory limit before they
 * exist: a z-buffer's depth, primitive and colour (16 bytes a pixel; the
 * scanline buffer's active pixels and row offsets are estimated the
 * same) and two doubles a frame. */
static gboolean buffers_fit(const BenchRasterOpts *o, GError **err)
{
    double px = (double)o->size * o->size;
    char *what = g_strdup_printf("a %dx%d image and %d frames", o->size,
                                 o->size, o->frames);
    gboolean ok = sim_mem_check(16.0 * px + 16.0 * o->frames,
                                "bench raster: --size, --frames", what,
                                err);
    g_free(what);
    return ok;
}

int bench_raster_main(int argc, char **argv)
{
    BenchRasterOpts o = {NULL, NULL, 640, 20, 8, 80};
    GOptionEntry entries[] = {
        {"scene", 0, 0, G_OPTION_ARG_STRING, &o.scene,
         "teapots or isosurface (teapots)", "S"},
        {"count", 0, 0, G_OPTION_ARG_INT, &o.count, "teapots (8)", "N"},
        {"grid", 0, 0, G_OPTION_ARG_INT, &o.grid,
         "isosurface lattice cells per axis (80)", "G"},
        {"size", 0, 0, G_OPTION_ARG_INT, &o.size, "image side (640)", "N"},
        {"frames", 0, 0, G_OPTION_ARG_INT, &o.frames, "timed frames (20)", "K"},
        {"zbuffer", 0, 0, G_OPTION_ARG_STRING, &o.zbuffer,
         "full or scanline (scanline)", "KIND"},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    GError *err = NULL;
    if (!bench_parse_options("raster", "- rendering pipeline throughput",
                             entries, &argc, &argv, &err))
        return bench_fail(err);
    if (!o.scene)
        o.scene = g_strdup("teapots");
    if (!o.zbuffer)
        o.zbuffer = g_strdup("scanline");
    Scene *s = NULL;
    if (o.size < 1 || o.size > RAST_MAX_SIDE || o.frames < 1 || o.count < 1 ||
        o.grid < 2 ||
        (g_strcmp0(o.zbuffer, "full") && g_strcmp0(o.zbuffer, "scanline")))
        g_set_error(&err, SIM_ERROR, SIM_ERROR_INPUT,
                    "bench raster: found a bad option value, expected "
                    "--size 1..16384, --frames/--count >= 1, --grid >= 2, "
                    "--zbuffer full|scanline");
    else if (buffers_fit(&o, &err))
        s = make_scene(&o, &err);
    if (s)
        run(&o, s);
    scene_free(s);
    g_free(o.scene);
    g_free(o.zbuffer);
    return err ? bench_fail(err) : 0;
}
