/* test_structdb_file_errors.c — every error of the structure database
 * file reader (sim/scene/structdb_file.c) with its whole message and
 * line:column, and the writer's quoting of names (control bytes, quotes,
 * backslashes), tags, primitive flags, empty lists and posted lists, read
 * back equal.  Found unexecuted by make coverage (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/structdb_file.h"
#include "tests/support.h"

typedef struct {
    const char *yaml, *message;
} Case;

static const Case bad[] = {
    {"[1, 2]\n",
     "t.yaml:1:1: found a sequence, expected a map {structure_database: 1, structures, posted}"},
    {"structure_database: 2\nstructures: []\n",
     "t.yaml:1:21: found '2', expected structure_database: 1 (the format's only version)"},
    {"structure_database: 1\n",
     "t.yaml:1:1: found a map, expected a key 'structures'"},
    {"structures: []\n",
     "t.yaml:1:1: found no key 'structure_database' in this map, expected 'structure_database': an integer"},
    {"structure_database: 1\nstructures: {a: 1}\n",
     "t.yaml:2:13: found a map, expected a sequence of structures {name, elements}"},
    {"structure_database: 1\nstructures: [3]\n",
     "t.yaml:2:14: found '3', expected a structure map {name, elements}"},
    {"structure_database: 1\nstructures: [{elements: []}]\n",
     "t.yaml:2:14: found no key 'name' in this map, expected 'name': a string"},
    {"structure_database: 1\nstructures: [{name: a}, {name: a}]\n",
     "t.yaml:2:32: found 'a', expected a name not used before"},
    {"structure_database: 1\nstructures: [{name: a, primitive: maybe}]\n",
     "t.yaml:2:35: found 'maybe', expected true or false"},
    {"structure_database: 1\nstructures: [{name: a, elements: 3}]\n",
     "t.yaml:2:34: found '3', expected a sequence of elements"},
    {"structure_database: 1\nstructures: [{name: a, elements: [3]}]\n",
     "t.yaml:2:35: found '3', expected an element map {one of triangle, polygon, tristrip, polygon2d, line, sphere, color, "
     "matrix, execute, line_color, sphere_color: ...}"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{color: [1, 1, 1], execute: a}]}]\n",
     "t.yaml:2:63: found 'a', expected one element kind per list entry"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{triangle: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], color: [1, 1, 1]}]}]\n",
     "t.yaml:2:88: found a sequence, expected one element kind per list entry"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{tag: 3}]}]\n",
     "t.yaml:2:35: found a map, expected an element with a key one of triangle, polygon, tristrip, polygon2d, line, sphere, color, "
     "matrix, execute, line_color, sphere_color"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{color: [1, 1, 1], tag: -1}]}]\n",
     "t.yaml:2:59: found '-1', expected an integer >= 0"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{color: [1, 1]}]}]\n",
     "t.yaml:2:43: found a sequence, expected a sequence of 3 numbers"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{color: [1, x, 1]}]}]\n",
     "t.yaml:2:47: found 'x', expected a finite number"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{color: [1, inf, 1]}]}]\n",
     "t.yaml:2:47: found 'inf', expected a finite number"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{color: 1}]}]\n",
     "t.yaml:2:43: found '1', expected a sequence of 3 numbers"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{triangle: [[0, 0, 0], [1, 0, 0]]}]}]\n",
     "t.yaml:2:46: found a sequence, expected three vertices [[x, y, z], [x, y, z], [x, y, z]]"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{triangle: [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}]}]\n",
     "t.yaml:2:46: found a sequence, expected three vertices [[x, y, z], [x, y, z], [x, y, z]]"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{polygon: [[0, 0, 0], [1, 0, 0]]}]}]\n",
     "t.yaml:2:45: found a sequence, expected a sequence of at least three [x, y, z] vertices"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{polygon: [[0, 0, 0], [1, 0], [0, 1, 0]]}]}]\n",
     "t.yaml:2:57: found a sequence, expected a sequence of 3 numbers"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{polygon: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], extra: 1}]}]\n",
     "t.yaml:2:80: found unknown key 'extra', expected one of: polygon, tag"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{matrix: [1, 0, 0, 0]}]}]\n",
     "t.yaml:2:44: found a sequence, expected a sequence of 16 numbers"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], mode: add}]}]\n",
     "t.yaml:2:100: found 'add', expected one of: replace, concat"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{execute: b}]}]\n",
     "t.yaml:2:45: found 'b', expected the name of a structure in this file"},
    {"structure_database: 1\nstructures: [{name: a, elements: [{execute: [b]}]}]\n",
     "t.yaml:2:45: found a sequence, expected the name of a structure in this file"},
    {"structure_database: 1\nstructures: [{name: a}]\nposted: a\n",
     "t.yaml:3:9: found 'a', expected a sequence of structure names"},
    {"structure_database: 1\nstructures: [{name: a}]\nposted: [b]\n",
     "t.yaml:3:10: found 'b', expected the name of a structure in this file"},
    {"structure_database: 1\nstructures: [{name: a}]\nposted: [[a]]\n",
     "t.yaml:3:10: found a sequence, expected the name of a structure in this file"},
    {"structure_database: 1\nstructures: [{name: a}]\nextra: 1\n",
     "t.yaml:3:1: found unknown key 'extra', expected one of: structure_database, structures, posted"},
};

static SceneDb *from_text(const char *yaml, GError **err)
{
    CfgNode *root = cfg_load_string(yaml, "t.yaml", err);
    assert_non_null(root);
    SceneDb *db = scene_db_from_cfg(root, err);
    cfg_free(root);
    return db;
}

static void test_errors(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        GError *err = NULL;
        SceneDb *db = from_text(bad[i].yaml, &err);
        if (db)
            print_error("accepted: %s", bad[i].yaml);
        assert_null(db);
        if (strcmp(err->message, bad[i].message))
            print_error("got  %s\nwant %s\n", err->message, bad[i].message);
        assert_string_equal(err->message, bad[i].message);
        assert_int_equal(err->code, SIM_ERROR_INPUT);
        g_error_free(err);
    }
    /* a cycle: located at the execute (the wording is structdb.c's) */
    GError *err = NULL;
    assert_null(from_text("structure_database: 1\nstructures: [{name: a, "
                          "elements: [{execute: a}]}]\n",
                          &err));
    assert_true(g_str_has_prefix(err->message, "t.yaml:2:45: "));
    assert_non_null(strstr(err->message, "cycle"));
    g_error_free(err);
}

static void test_write_read(void **st)
{
    (void)st;
    SceneDb *db = scene_db_new();
    const char *names[] = {"plain", "tab\there \"q\" back\\slash",
                           "line\nbreak \x7f del", "empty"};
    for (guint i = 0; i < 4; i++)
        scene_db_add_struct(db, names[i]);
    Vec3 v[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.1, 0.2, 1e-17}};
    SceneElem e = scene_elem_prim(SCENE_EL_POLYGON, v, 4);
    e.tag = 42;
    assert_true(scene_db_append(db, 0, &e, NULL));
    e = scene_elem_prim(SCENE_EL_TRIANGLE, v, 3);
    assert_true(scene_db_append(db, 1, &e, NULL));
    Mat4 m = mat4_translate(1, 2, 3);
    m.m[3][0] = 0.5;
    e = scene_elem_matrix(m, SCENE_MAT_CONCAT);
    e.tag = 7;
    assert_true(scene_db_append(db, 1, &e, NULL));
    e = scene_elem_color(vec3(0.25, 0.5, 1));
    assert_true(scene_db_append(db, 2, &e, NULL));
    e = scene_elem_execute(1);
    assert_true(scene_db_append(db, 2, &e, NULL));
    e = scene_elem_execute(0);
    assert_true(scene_db_append(db, 2, &e, NULL));
    scene_db_set_primitive(db, 1, TRUE);
    scene_db_post(db, 2);
    scene_db_post(db, 3);
    GString *y = scene_db_to_yaml(db);
    assert_non_null(strstr(y->str, "name: \"tab\\x09here \\\"q\\\" "
                                    "back\\\\slash\"\n    primitive: true\n"));
    assert_non_null(strstr(y->str, "name: \"line\\x0abreak \\x7f del\""));
    assert_non_null(strstr(y->str, "tag: 42}"));
    assert_non_null(strstr(y->str, "mode: concat, tag: 7}"));
    assert_non_null(strstr(y->str, "name: \"empty\"\n    elements: []\n"));
    assert_null(strstr(y->str, "tag: 0"));
    assert_non_null(strstr(y->str, "posted: [\"line\\x0abreak \\x7f "
                                   "del\", \"empty\"]\n"));
    GError *err = NULL;
    SceneDb *r = from_text(y->str, &err);
    if (!r)
        print_error("%s\n%s\n", err->message, y->str);
    assert_non_null(r);
    assert_int_equal(scene_db_struct_count(r), 4);
    for (guint i = 0; i < 4; i++)
        assert_string_equal(scene_db_struct_name(r, i), names[i]);
    assert_true(scene_db_is_primitive(r, 1) && !scene_db_is_primitive(r, 0));
    const SceneElem *p = scene_db_elem(r, 0, 0);
    assert_int_equal(p->kind, SCENE_EL_POLYGON);
    assert_true(p->tag == 42 && p->nverts == 4 && p->verts[3].z == 1e-17);
    const SceneElem *mx = scene_db_elem(r, 1, 1);
    assert_int_equal(mx->mode, SCENE_MAT_CONCAT);
    assert_true(mx->tag == 7 && mx->matrix.m[3][0] == 0.5 &&
                mx->matrix.m[1][3] == 2);
    assert_int_equal(scene_db_elem(r, 2, 1)->child, 1);
    assert_int_equal(scene_db_elem(r, 2, 2)->child, 0);
    assert_true(scene_db_elem(r, 2, 0)->color.x == 0.25);
    assert_int_equal(scene_db_len(r, 3), 0);
    assert_int_equal(scene_db_posted_count(r), 2);
    assert_int_equal(scene_db_posted_at(r, 0), 2);
    assert_int_equal(scene_db_posted_at(r, 1), 3);
    g_string_free(y, TRUE);
    /* an empty database: empty lists */
    SceneDb *none = scene_db_new();
    y = scene_db_to_yaml(none);
    assert_string_equal(y->str, "structure_database: 1\nstructures: []\n"
                                "posted: []\n");
    SceneDb *r2 = from_text(y->str, &err);
    assert_int_equal(scene_db_struct_count(r2), 0);
    g_string_free(y, TRUE);
    /* a file that is not there, or does not parse: no database */
    assert_null(scene_db_load("/nonexistent-pgsim-dir/db.yaml", &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    g_clear_error(&err);
    /* an unwritable path: an I/O error naming it */
    assert_false(scene_db_save(db, "/nonexistent-pgsim-dir/db.yaml", &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    assert_true(g_str_has_prefix(err->message, "/nonexistent-pgsim-dir/db.yaml: "
                                               "found an unwritable path ("));
    g_clear_error(&err);
    scene_db_free(r2);
    scene_db_free(none);
    scene_db_free(r);
    scene_db_free(db);
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_write_read),
    };
    return cmocka_run_group_tests_name("structdb_file_errors", tests, NULL,
                                       NULL);
}
