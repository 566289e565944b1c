/* fuzz_render.c — libFuzzer harness: the scene-to-image path.  The input
 * is a YAML scene file (a `scene:` section: generator or inline camera,
 * view, path, background); the scene is built (scene_from_cfg) and
 * rendered at 64 x 48 through transform, clip, scan conversion and the
 * scanline z-buffer into an image, as `pgsim render` does.  See fuzz.h. */
#include "sim/core/cfg.h"
#include "sim/raster/image.h"
#include "sim/raster/pipeline.h"
#include "sim/raster/scanzbuf.h"
#include "sim/raster/spanlist.h"
#include "sim/scene/scene_cfg.h"
#include "tests/fuzz/fuzz.h"

static void render(const Scene *s)
{
    SceneCamera cam = scene_camera_at(s, 0);
    RastView v = rast_view_for_camera(&cam, 64, 48);
    RastColor bg = {s->background.r, s->background.g, s->background.b};
    RastCounters c = {0};
    RastImage *img = rast_image_new(64, 48);
    RastSpanList *sl = rast_spanlist_new(64, 48);
    rast_draw_scene(&v, s, rast_spanlist_sink(sl), &c);
    rast_spanlist_sort(sl);
    RastActive *a = rast_active_new(64, 48);
    rast_scanline_zbuffer(a, sl, &c);
    rast_image_from_active(img, a, bg);
    rast_active_free(a);
    rast_spanlist_free(sl);
    rast_image_free(img);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    char *text = fuzz_text(data, size);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "fuzz.yaml", &err);
    const CfgNode *sec = root ? cfg_get(root, "scene") : NULL;
    Scene *s = sec ? scene_from_cfg(sec, &err) : NULL;
    if (s)
        render(s);
    scene_free(s);
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    return 0;
}
