/* fuzz_structdb.c — libFuzzer harness: the structure database file
 * format (scene_db_from_cfg over cfg_load_string), and for a database
 * read, its flattening and a write / re-read round trip, which must
 * read again into the same text.  See fuzz.h. */
#include "sim/scene/structdb_file.h"
#include "tests/fuzz/fuzz.h"
#include <string.h>

static void roundtrip(const SceneDb *db)
{
    SceneMesh *m = scene_db_flatten(db);
    scene_mesh_free(m);
    GString *text = scene_db_to_yaml(db);
    CfgNode *root = cfg_load_string(text->str, "again", NULL);
    g_assert(root != NULL); /* what we write we must read */
    SceneDb *again = scene_db_from_cfg(root, NULL);
    g_assert(again != NULL);
    GString *text2 = scene_db_to_yaml(again);
    g_assert(strcmp(text->str, text2->str) == 0);
    g_string_free(text2, TRUE);
    scene_db_free(again);
    cfg_free(root);
    g_string_free(text, TRUE);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    GError *err = NULL;
    char *text = fuzz_text(data, size);
    CfgNode *root = cfg_load_string(text, "fuzz.yaml", &err);
    SceneDb *db = root ? scene_db_from_cfg(root, &err) : NULL;
    if (db)
        roundtrip(db);
    scene_db_free(db);
    cfg_free(root);
    g_clear_error(&err);
    g_free(text);
    return 0;
}
