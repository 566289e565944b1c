/* support.c — set-up steps many test binaries share (support.h). */
#include "tests/support.h"

#include <glib.h>
#include <glib/gstdio.h>

void support_warnings_fatal(void)
{
    g_log_set_always_fatal(G_LOG_FATAL_MASK | G_LOG_LEVEL_WARNING |
                           G_LOG_LEVEL_CRITICAL);
}

int support_test_models(void **state)
{
    (void)state;
    g_setenv("PGSIM_MODELS", "tests/data/models", TRUE);
    return 0;
}

static int vec3_same(Vec3 a, Vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

int support_camera_equal(const SceneCamera *a, const SceneCamera *b)
{
    return a->proj == b->proj && vec3_same(a->eye, b->eye) &&
           vec3_same(a->target, b->target) && vec3_same(a->up, b->up) &&
           a->fov_deg == b->fov_deg && a->height == b->height &&
           a->near == b->near && a->far == b->far && a->aspect == b->aspect;
}

void support_rm_tree(const char *path)
{
    GDir *d = g_dir_open(path, 0, NULL);
    if (d) {
        const char *e;
        while ((e = g_dir_read_name(d))) {
            char *p = g_build_filename(path, e, NULL);
            support_rm_tree(p);
            g_free(p);
        }
        g_dir_close(d);
    }
    g_remove(path);
}
