/* cmd_render.c — `pgsim render SCENE -o frame.png`: a quick look.
 *
 * Renders one frame of a scene through sim/raster (transform, clip, cull,
 * scan conversion, the full or the modified scanline z-buffer) and writes
 * a PNG (or PPM when the name ends in .ppm), atomically.  Prints the
 * operation counters (TPG, TPF ...) on stdout.
 *
 * Scene sources: a Wavefront OBJ or PLY file (the scene library's
 * loaders, sim/scene/obj.h and ply.h), or a built-in teapot
 * scene of seed 003 (--teapots N, 3,751 polygons per teapot), or the
 * gyroid isosurface of sim/scene/isosurface.h (--isosurface GRID).  The
 * camera of a model file is fitted to its bounding box.  YAML scene files
 * need the scene library's scene_from_cfg(), not yet on main.
 * Cost: O(polygons + pixels).
 */
#include "sim/app/commands.h"
#include "sim/core/error.h"
#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"
#include "sim/scene/isosurface.h"
#include "sim/scene/obj.h"
#include "sim/scene/ply.h"
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

/* A model file: PLY when the name ends in .ply, OBJ otherwise. */
static SceneMesh *load_model(const char *path, GError **err)
{
    if (g_str_has_suffix(path, ".ply"))
        return scene_ply_load(path, err);
    return scene_obj_load(path, err);
}

static Scene *scene_for_obj(const char *path, GError **err)
{
    SceneMesh *m = load_model(path, err);
    if (!m)
        return NULL;
    if (m->normals->len != m->pos->len)
        scene_mesh_compute_normals(m);
    Scene *s = scene_new(path);
    SceneBox box = scene_mesh_bbox(m);
    scene_add_instance(s, scene_add_mesh(s, m), mat4_identity(),
                       scene_color(1, 1, 1), 0);
    s->camera.eye = vec3(0.6, 0.5, 1.0);
    s->camera.target = vec3(0, 0, 0);
    scene_camera_fit(&s->camera, box, 0.9);
    s->background = scene_color(0.1f, 0.1f, 0.15f);
    return s;
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

static gboolean check_opts(const RenderOpts *o, int argc, GError **err)
{
    const char *bad = NULL, *exp = NULL;
    if (!o->out)
        bad = "no -o", exp = "-o FILE.png";
    else if (o->width < 1 || o->width > RAST_MAX_SIDE || o->height < 1 ||
             o->height > RAST_MAX_SIDE)
        bad = "a bad --width/--height", exp = "1 .. 16384 pixels";
    else if (g_strcmp0(o->zbuffer, "full") && g_strcmp0(o->zbuffer, "scanline"))
        bad = "a bad --zbuffer", exp = "full or scanline";
    else if (g_strcmp0(o->shading, "flat") && g_strcmp0(o->shading, "gouraud"))
        bad = "a bad --shading", exp = "flat or gouraud";
    else if ((argc == 2) + (o->teapots > 0) + (o->iso_grid > 0) != 1)
        bad = "no scene or two",
        exp = "one of SCENE.obj/.ply, --teapots N, --isosurface GRID";
    else if (o->iso_grid == 1 || o->iso_grid > 400)
        bad = "a bad --isosurface grid", exp = "2 .. 400 cells";
    if (bad)
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "render: found %s, expected %s", bad, exp);
    return bad == NULL;
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

static gboolean run(RenderOpts *o, int argc, char **argv, GError **err)
{
    if (!check_opts(o, argc, err))
        return FALSE;
    Scene *s;
    if (o->iso_grid > 0) {
        SceneIsoParams p = scene_iso_defaults();
        p.grid = (guint)o->iso_grid;
        s = scene_iso_new(&p);
    } else {
        s = o->teapots > 0 ? scene_for_teapots(o, err)
                           : scene_for_obj(argv[1], err);
    }
    if (!s)
        return FALSE;
    SceneCamera cam = scene_camera_at(s, o->frame);
    RastView v = rast_view_for_camera(&cam, o->width, o->height);
    v.cull_back = !o->no_cull;
    v.shading = g_strcmp0(o->shading, "flat") == 0 ? RAST_SHADE_FLAT
                                                   : RAST_SHADE_GOURAUD;
    RastImage *img = rast_image_new(o->width, o->height);
    RastCounters c = {0};
    render(&v, s, g_strcmp0(o->zbuffer, "full") == 0, img, &c);
    gboolean ok = rast_image_write(img, o->out, err);
    if (ok) {
        char *line = rast_counters_format(&c);
        printf("%s: %dx%d %s z-buffer: %s\n", o->out, o->width, o->height,
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
        {"no-cull", 0, 0, G_OPTION_ARG_NONE, &o.no_cull,
         "draw back faces too", NULL},
        {"teapots", 0, 0, G_OPTION_ARG_INT, &o.teapots,
         "built-in scene of N teapots (seed 003)", "N"},
        {"isosurface", 0, 0, G_OPTION_ARG_INT, &o.iso_grid,
         "built-in gyroid isosurface on a GRID^3 lattice", "GRID"},
        {"layout", 0, 0, G_OPTION_ARG_STRING, &o.layout,
         "teapot layout: spread or depth", "L"},
        {"frame", 0, 0, G_OPTION_ARG_DOUBLE, &o.frame,
         "frame of the camera path (0)", "F"},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    GOptionContext *ctx = g_option_context_new("SCENE.obj|SCENE.ply -o FRAME.png");
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
