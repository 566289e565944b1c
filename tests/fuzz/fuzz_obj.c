/* fuzz_obj.c — libFuzzer harness: Wavefront OBJ text (scene_obj_parse),
 * and for a parsed mesh its bounds and a write / re-read round trip,
 * which must parse again.  See fuzz.h. */
#include "sim/scene/obj.h"
#include "tests/fuzz/fuzz.h"
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    GError *err = NULL;
    SceneMesh *m = scene_obj_parse((const char *)data, size, "fuzz.obj", &err);
    if (m) {
        (void)scene_mesh_bbox(m);
        char *again = scene_obj_to_string(m);
        SceneMesh *m2 = scene_obj_parse(again, strlen(again), "again", NULL);
        g_assert(m2 != NULL); /* what we write we must read */
        scene_mesh_free(m2);
        g_free(again);
    }
    scene_mesh_free(m);
    g_clear_error(&err);
    return 0;
}
