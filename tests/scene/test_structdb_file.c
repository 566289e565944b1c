/* test_structdb_file.c — the structure database file format: a
 * generator's database written and read back is the same database (and
 * flattens to the same mesh); hand-written files load; bad files are
 * refused with located errors.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/structdb_file.h"
#include "sim/scene/vehicle.h"
#include "tests/support.h"

static void assert_same_elem(const SceneElem *a, const SceneElem *b)
{
    assert_int_equal(a->kind, b->kind);
    assert_true(a->tag == b->tag);
    assert_int_equal(a->nverts, b->nverts);
    if (a->nverts)
        assert_memory_equal(a->verts, b->verts, a->nverts * sizeof(Vec3));
    if (a->kind == SCENE_EL_COLOR)
        assert_memory_equal(&a->color, &b->color, sizeof(Vec3));
    if (a->kind == SCENE_EL_MATRIX) {
        assert_memory_equal(&a->matrix, &b->matrix, sizeof(Mat4));
        assert_int_equal(a->mode, b->mode);
    }
    if (a->kind == SCENE_EL_EXECUTE)
        assert_int_equal(a->child, b->child);
}

static void assert_same_db(const SceneDb *a, const SceneDb *b)
{
    assert_int_equal(scene_db_struct_count(a), scene_db_struct_count(b));
    for (guint s = 0; s < scene_db_struct_count(a); s++) {
        assert_string_equal(scene_db_struct_name(a, s),
                            scene_db_struct_name(b, s));
        assert_int_equal(scene_db_is_primitive(a, s),
                         scene_db_is_primitive(b, s));
        assert_int_equal(scene_db_len(a, s), scene_db_len(b, s));
        for (guint k = 0; k < scene_db_len(a, s); k++)
            assert_same_elem(scene_db_elem(a, s, k), scene_db_elem(b, s, k));
    }
    assert_int_equal(scene_db_posted_count(a), scene_db_posted_count(b));
    for (guint i = 0; i < scene_db_posted_count(a); i++)
        assert_int_equal(scene_db_posted_at(a, i), scene_db_posted_at(b, i));
}

/* The vehicle generator's database (structures, colours, matrices,
 * executes, three instances) round-trips exactly, and so does its text. */
static void test_roundtrip_vehicle(void **state)
{
    (void)state;
    SceneVehicleParams p = scene_vehicle_defaults();
    p.structures = 40;
    p.triangles = 3000;
    p.instances = 3;
    GError *e = NULL;
    Scene *sc = scene_vehicle_new(&p, "test", &e);
    assert_non_null(sc);
    GString *text = scene_db_to_yaml(sc->db);
    CfgNode *root = cfg_load_string(text->str, "vehicle-db.yaml", &e);
    assert_non_null(root);
    SceneDb *back = scene_db_from_cfg(root, &e);
    assert_non_null(back);
    assert_same_db(sc->db, back);
    GString *again = scene_db_to_yaml(back);
    assert_string_equal(text->str, again->str);
    SceneMesh *m1 = scene_db_flatten(sc->db), *m2 = scene_db_flatten(back);
    assert_int_equal(scene_mesh_n_polys(m1), scene_mesh_n_polys(m2));
    assert_true(scene_mesh_n_polys(m1) == 3 * 3000);
    scene_mesh_free(m1);
    scene_mesh_free(m2);
    g_string_free(again, TRUE);
    g_string_free(text, TRUE);
    scene_db_free(back);
    cfg_free(root);
    scene_free(sc);
}

static const char *good =
    "structure_database: 1\n"
    "structures:\n"
    "  - name: world\n"
    "    elements:\n"
    "      - {matrix: [1,0,0,2, 0,1,0,0, 0,0,1,0, 0,0,0,1]}\n"
    "      - execute: part\n"
    "      - {matrix: [1,0,0,-2, 0,1,0,0, 0,0,1,0, 0,0,0,1], mode: concat}\n"
    "      - execute: part\n"
    "  - name: part\n"
    "    primitive: true\n"
    "    elements:\n"
    "      - color: [1, 0, 0]\n"
    "      - triangle: [[0,0,0], [1,0,0], [0,1,0]]\n"
    "      - {tristrip: [[0,0,1], [1,0,1], [0,1,1], [1,1,1]], tag: 9}\n"
    "posted: [world]\n";

/* A hand-written file with a forward execute: two instances of a
 * triangle and a two-triangle strip. */
static void test_load_handwritten(void **state)
{
    (void)state;
    GError *e = NULL;
    CfgNode *root = cfg_load_string(good, "good.yaml", &e);
    assert_non_null(root);
    SceneDb *db = scene_db_from_cfg(root, &e);
    assert_non_null(db);
    assert_int_equal(scene_db_struct_count(db), 2);
    assert_true(scene_db_is_primitive(db, 1));
    assert_true(scene_db_elem(db, 1, 2)->tag == 9);
    assert_int_equal(scene_db_elem(db, 0, 2)->mode, SCENE_MAT_CONCAT);
    SceneMesh *m = scene_db_flatten(db);
    assert_int_equal(scene_mesh_n_polys(m), 2 * 3);
    scene_mesh_free(m);
    scene_db_free(db);
    cfg_free(root);
}

/* `good` with `from` replaced by `to` is refused at line:col with `what`. */
static void refused(const char *from, const char *to, const char *at,
                    const char *what)
{
    GError *e = NULL;
    const char *hit = strstr(good, from);
    assert_non_null(hit);
    GString *t = g_string_new_len(good, hit - good);
    g_string_append(t, to);
    g_string_append(t, hit + strlen(from));
    CfgNode *root = cfg_load_string(t->str, "bad.yaml", &e);
    SceneDb *db = root ? scene_db_from_cfg(root, &e) : NULL;
    assert_null(db);
    assert_non_null(e);
    if (!strstr(e->message, at) || !strstr(e->message, what))
        fail_msg("'%s' / '%s' not in '%s'", at, what, e->message);
    g_clear_error(&e);
    cfg_free(root);
    g_string_free(t, TRUE);
}

static void test_errors(void **state)
{
    (void)state;
    refused("execute: part\n  ", "execute: nowhere\n  ", "bad.yaml:6:18:",
            "name of a structure");
    refused("[0,1,0]]", "[0,1]]", "bad.yaml:13:38:", "3 numbers");
    refused("[[0,0,0], [1,0,0], [0,1,0]]", "[[0,0,0], [1,0,0]]",
            "bad.yaml:13:19:", "three vertices");
    refused("color: [1, 0, 0]", "colour: [1, 0, 0]", "bad.yaml:12:9:",
            "an element with a key");
    refused("color: [1, 0, 0]", "color: [1, x, 0]", "bad.yaml:12:20:",
            "finite number");
    refused("mode: concat", "mode: multiply", "bad.yaml:7", "concat");
    refused("name: part", "name: world", "bad.yaml:9:11:",
            "a name not used before");
    refused("structure_database: 1", "structure_database: 2", "bad.yaml:1:21:",
            "structure_database");
    refused("posted: [world]", "posted: [world, moon]", "bad.yaml:15:17:",
            "name of a structure");
    refused("      - color: [1, 0, 0]\n",
            "      - color: [1, 0, 0]\n      - execute: world\n",
            "bad.yaml:13:18:", "cycle");
    refused("tag: 9}", "tag: 9, size: 3}", "bad.yaml", "unknown key 'size'");
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roundtrip_vehicle),
        cmocka_unit_test(test_load_handwritten),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
