/* fuzz_ply.c — libFuzzer harness: PLY files, ASCII and binary
 * (scene_ply_parse), and for a parsed mesh its bounds.  See fuzz.h. */
#include "sim/scene/ply.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    GError *err = NULL;
    SceneMesh *m = scene_ply_parse(data, size, "fuzz.ply", &err);
    if (m)
        (void)scene_mesh_bbox(m);
    scene_mesh_free(m);
    g_clear_error(&err);
    return 0;
}
