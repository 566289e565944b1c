/* cmd_render.c — `pgsim render SCENE -o frame.png`: a quick look.
 *
 * Renders one frame of a scene through sim/raster (transform, clip, cull,
 * scan conversion, the full or the modified scanline z-buffer) and writes
 * a PNG (or PPM when the name ends in .ppm), atomically: on any error
 * nothing is written.  Prints the operation counters (TPG, TPF ...) on
 * stdout.
 *
 * Scene sources, exactly one of:
 *   SCENE.yaml  a scene file (configs/scenes/), or a run config: its
 *               `scene:` section goes through scene_from_cfg() (generator
 *               or model file, view, camera, path, background);
 *   SCENE.obj | SCENE.ply   a user model through scene_from_file(),
 *               camera by the default view rule;
 *   --teapots N / --isosurface GRID   built-in shortcuts.
 * --frame F picks the camera of frame F of the scene's path.  Scenes
 * marked two-sided (open surfaces such as the gyroid, or `two_sided:
 * true` in YAML) are drawn without back-face culling.  Input
 * errors (bad files, bad flags) are reported as "where: found X,
 * expected Y" and exit with status 2.  Cost: O(polygons + pixels).
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"
#include "sim/scene/isosurface.h"
#include "sim/scene/scene_cfg.h"
#include "sim/scene/scene_limits.h"
#include "sim/scene/teapots.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    char *out;
    int width, height;
    char *zbuffer, *shading;
    gboolean no_cull;
    int teapots, iso_grid;
    char *layout;
    double frame;
} RenderOpts;

static gboolean has_suffix_ci(const char *s, const char *suffix)
{
    char *lower = g_ascii_strdown(s, -1);
    gboolean r = g_str_has_suffix(lower, suffix);
    g_free(lower);
    return r;
}

static Scene *scene_for_teapots(const RenderOpts *o, GError **err)
{
    SceneTeapotsParams p = scene_teapots_defaults();
    p.polygons_per_teapot = 3751;
    p.count = (guint)o->teapots;
    if (g_strcmp0(o->layout, "depth") == 0)
        p.layout = SCENE_TEAPOTS_DEPTH;
    else if (o->layout && g_strcmp0(o->layout, "spread") != 0) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "--layout: found '%s', expected spread or depth",
                    o->layout);
        return NULL;
    }
    Scene *s = scene_teapots_new(&p, "--teapots", err);
    if (s)
        s->background = scene_color(0.1f, 0.1f, 0.15f);
    return s;
}

static gboolean flag_error(GError **err, const char *flag, const char *found,
                           const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s: found %s, expected %s",
                flag, found, expected);
    return FALSE;
}

static gboolean check_side(int v, const char *flag, GError **err)
{
    char buf[32];
    if (v >= 1 && v <= RAST_MAX_SIDE)
        return TRUE;
    g_snprintf(buf, sizeof buf, "%d", v);
    return flag_error(err, flag, buf, "1 .. 16384 pixels");
}

static gboolean check_kinds(const RenderOpts *o, GError **err)
{
    char *q = NULL;
    gboolean ok = TRUE;
    if (g_strcmp0(o->zbuffer, "full") && g_strcmp0(o->zbuffer, "scanline"))
        ok = flag_error(err, "--zbuffer",
                        q = g_strdup_printf("'%s'", o->zbuffer),
                        "full or scanline");
    else if (g_strcmp0(o->shading, "flat") && g_strcmp0(o->shading, "gouraud"))
        ok = flag_error(err, "--shading",
                        q = g_strdup_printf("'%s'", o->shading),
                        "flat or gouraud");
    g_free(q);
    return ok;
}

static gboolean check_opts(const RenderOpts *o, int argc, GError **err)
{
    if (!o->out)
        return flag_error(err, "render", "no -o", "-o FILE.png or FILE.ppm");
    if (!has_suffix_ci(o->out, ".png") && !has_suffix_ci(o->out, ".ppm")) {
        char *q = g_strdup_printf("'%s'", o->out);
        flag_error(err, "-o", q, "a file name ending in .png or .ppm");
        g_free(q);
        return FALSE;
    }
    if (!check_side(o->width, "--width", err) ||
        !check_side(o->height, "--height", err) || !check_kinds(o, err))
        return FALSE;
    char *size = g_strdup_printf("%dx%d pixels", o->width, o->height);
    /* image (4 B), z-buffer and span lists: about 16 B a pixel */
    gboolean fits = sim_mem_check(16.0 * o->width * o->height,
                                  "--width x --height", size, err);
    g_free(size);
    if (!fits)
        return FALSE;
    if (argc > 2)
        return flag_error(err, "render", "more than one scene argument",
                          "one SCENE.yaml, .obj or .ply");
    if ((argc == 2) + (o->teapots > 0) + (o->iso_grid > 0) != 1)
        return flag_error(err, "render", "no scene or two",
                          "one of SCENE.yaml/.obj/.ply, --teapots N, "
                          "--isosurface GRID");
    if (o->teapots < 0 || o->teapots > SCENE_TEAPOTS_MAX)
        return flag_error(err, "--teapots", "a bad count",
                          "1 .. " G_STRINGIFY(SCENE_TEAPOTS_MAX) " teapots");
    if (o->iso_grid < 0 || o->iso_grid == 1 || o->iso_grid > SCENE_ISO_GRID_MAX)
        return flag_error(err, "--isosurface", "a bad grid",
                          "2 .. " G_STRINGIFY(SCENE_ISO_GRID_MAX) " cells");
    if (!isfinite(o->frame) || o->frame < 0)
        return flag_error(err, "--frame", "a negative or non-finite frame",
                          "a frame number >= 0");
    return TRUE;
}

/* --frame must name a frame of the scene's camera path. */
static gboolean check_frame(const Scene *s, double frame, GError **err)
{
    guint n = s->path ? scene_path_n_frames(s->path) : 1;
    if (frame <= (double)(n - 1))
        return TRUE;
    char found[64], expected[96];
    g_snprintf(found, sizeof found, "%g", frame);
    if (s->path)
        g_snprintf(expected, sizeof expected,
                   "0 .. %u (the scene's camera path has %u frames)", n - 1, n);
    else
        g_snprintf(expected, sizeof expected,
                   "0 (the scene has no camera path)");
    return flag_error(err, "--frame", found, expected);
}

/* Renders through the chosen z-buffer into img; counts in *c. */
static void render(const RastView *v, const Scene *s, gboolean full,
                   RastImage *img, RastCounters *c)
{
    RastColor bg = {s->background.r, s->background.g, s->background.b};
    if (full) {
        RastZBuffer *zb = rast_zbuffer_new(v->width, v->height);
        rast_draw_scene(v, s, rast_zbuffer_sink(zb), c);
        c->winners += rast_zbuffer_covered(zb);
        rast_image_from_zbuffer(img, zb, bg);
        rast_zbuffer_free(zb);
        return;
    }
    RastSpanList *sl = rast_spanlist_new(v->width, v->height);
    rast_draw_scene(v, s, rast_spanlist_sink(sl), c);
    rast_spanlist_sort(sl);
    RastActive *a = rast_active_new(v->width, v->height);
    rast_scanline_zbuffer(a, sl, c);
    rast_image_from_active(img, a, bg);
    rast_active_free(a);
    rast_spanlist_free(sl);
}

static Scene *load_scene(const RenderOpts *o, const char *arg, GError **err)
{
    if (o->iso_grid > 0) {
        SceneIsoParams p = scene_iso_defaults();
        p.grid = (guint)o->iso_grid;
        return scene_iso_check(&p, "--isosurface", err) ? scene_iso_new(&p)
                                                        : NULL;
    }
    if (o->teapots > 0)
        return scene_for_teapots(o, err);
    return scene_load(arg, err);
}

static gboolean run(RenderOpts *o, int argc, char **argv, GError **err)
{
    if (!check_opts(o, argc, err))
        return FALSE;
    Scene *s = load_scene(o, argc == 2 ? argv[1] : NULL, err);
    if (!s)
        return FALSE;
    if (!check_frame(s, o->frame, err)) {
        scene_free(s);
        return FALSE;
    }
    SceneCamera cam = scene_camera_at(s, o->frame);
    RastView v = rast_view_for_camera(&cam, o->width, o->height);
    v.cull_back = !o->no_cull && !s->two_sided;
    v.shading = g_strcmp0(o->shading, "flat") == 0 ? RAST_SHADE_FLAT
                                                   : RAST_SHADE_GOURAUD;
    RastImage *img = rast_image_new(o->width, o->height);
    RastCounters c = {0};
    render(&v, s, g_strcmp0(o->zbuffer, "full") == 0, img, &c);
    gboolean ok = rast_image_write(img, o->out, err);
    if (ok) {
        char *line = rast_counters_format(&c);
        printf("%s: %s, %" G_GUINT64_FORMAT " polygons, frame %g, %dx%d %s "
               "z-buffer: %s\n",
               o->out, s->name, scene_n_polys(s), o->frame, o->width, o->height,
               o->zbuffer, line);
        g_free(line);
    }
    rast_image_free(img);
    scene_free(s);
    return ok;
}

int cmd_render(int argc, char **argv)
{
    RenderOpts o = {NULL, 640, 640, NULL, NULL, FALSE, 0, 0, NULL, 0};
    GOptionEntry entries[] = {
        {"output", 'o', 0, G_OPTION_ARG_FILENAME, &o.out,
         "image to write (.png, or .ppm)", "FILE"},
        {"width", 0, 0, G_OPTION_ARG_INT, &o.width, "pixels (640)", "W"},
        {"height", 0, 0, G_OPTION_ARG_INT, &o.height, "pixels (640)", "H"},
        {"zbuffer", 0, 0, G_OPTION_ARG_STRING, &o.zbuffer,
         "full or scanline (scanline)", "KIND"},
        {"shading", 0, 0, G_OPTION_ARG_STRING, &o.shading,
         "flat or gouraud (gouraud)", "KIND"},
        {"no-cull", 0, 0, G_OPTION_ARG_NONE, &o.no_cull, "draw back faces too",
         NULL},
        {"frame", 0, 0, G_OPTION_ARG_DOUBLE, &o.frame,
         "frame of the scene's camera path (0)", "N"},
        {"teapots", 0, 0, G_OPTION_ARG_INT, &o.teapots,
         "built-in scene of N teapots (kurc96)", "N"},
        {"isosurface", 0, 0, G_OPTION_ARG_INT, &o.iso_grid,
         "built-in gyroid isosurface on a GRID^3 lattice", "GRID"},
        {"layout", 0, 0, G_OPTION_ARG_STRING, &o.layout,
         "teapot layout: spread or depth", "L"},
        CLI_MEM_LIMIT_ENTRY,
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    GOptionContext *ctx =
        g_option_context_new("SCENE.yaml|SCENE.obj|SCENE.ply -o FRAME.png");
    g_option_context_set_summary(
        ctx, "Renders one frame of a scene (configs/scenes/*.yaml, a run "
             "config's scene: section, or an OBJ/PLY model).");
    g_option_context_add_main_entries(ctx, entries, NULL);
    GError *err = NULL;
    gboolean ok = g_option_context_parse(ctx, &argc, &argv, &err);
    if (!ok) {
        err->domain = SIM_ERROR;
        err->code = SIM_ERROR_INPUT;
    }
    g_option_context_free(ctx);
    if (!o.zbuffer)
        o.zbuffer = g_strdup("scanline");
    if (!o.shading)
        o.shading = g_strdup("gouraud");
    if (ok)
        ok = run(&o, argc, argv, &err);
    int status = 0;
    if (!ok) {
        fprintf(stderr, "pgsim: %s\n", err->message);
        status = sim_error_exit_status(err);
        g_error_free(err);
    }
    g_free(o.out);
    g_free(o.zbuffer);
    g_free(o.shading);
    g_free(o.layout);
    return status;
}
