/* test_loaders.c — OBJ and PLY: good files, round-trips, malformed files
 * under tests/data/bad/scene/ with located errors, and truncation /
 * corruption sweeps that must never crash (run under ASan by make check).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/core/rng.h"
#include "sim/scene/obj.h"
#include "sim/scene/ply.h"
#include "sim/scene/teapot.h"
#include "tests/support.h"

static SceneMesh *obj(const char *text)
{
    GError *err = NULL;
    SceneMesh *m = scene_obj_parse(text, strlen(text), "t.obj", &err);
    if (!m)
        print_error("%s\n", err->message);
    assert_non_null(m);
    return m;
}

static void test_obj_forms(void **st)
{
    (void)st;
    SceneMesh *m = obj("# comment\n"
                       "o first\n"
                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1\n"
                       "vt 0 0\nvt 1 0\nvt 1 1\n"
                       "vn 0 0 2\n"
                       "f 1 2 3 4\n"
                       "s off\nusemtl x\n"
                       "f 1/1 2/2 3/3\n"
                       "g second\n"
                       "f 1//1 3//1 4//1\r\n"
                       "f -4/-3/-1 -3/-2/-1 -2/-1/-1   # trailing\n"
                       "v 2 4 6 2\n"
                       "l 1 2\n");
    assert_int_equal(scene_mesh_n_vertices(m), 5);
    assert_int_equal(scene_mesh_n_polys(m), 4);
    assert_int_equal(scene_mesh_poly_len(m, 0), 4);
    assert_int_equal(scene_mesh_poly(m, 3)[0], 0); /* -4 of 4 */
    assert_int_equal(scene_mesh_poly(m, 3)[2], 2);
    assert_int_equal(g_array_index(m->poly_tag, uint32_t, 1), 0);
    assert_int_equal(g_array_index(m->poly_tag, uint32_t, 2), 1);
    Vec3 w = scene_mesh_vertex(m, 4);
    assert_true(w.x == 1 && w.y == 2 && w.z == 3); /* divided by w */
    assert_int_equal(m->normals->len, 0); /* not every corner had one */
    scene_mesh_free(m);
    m = obj("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0\nvn 0 0 1\n"
            "f 1//1 2//1 3//1\n");
    assert_int_equal(m->normals->len, 3);
    assert_true(g_array_index(m->normals, Vec3, 2).z == 1);
    assert_int_equal(m->colors->len, 3);
    assert_true(g_array_index(m->colors, SceneColor, 1).g == 1);
    assert_true(g_array_index(m->colors, SceneColor, 2).b == 1); /* white */
    scene_mesh_free(m);
}

static const char ply_ascii[] =
    "ply\nformat ascii 1.0\ncomment hi\n"
    "element vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nproperty uchar red\nproperty uchar green\n"
    "property uchar blue\nproperty list uchar int extra\n"
    "element face 2\nproperty list uchar int vertex_indices\n"
    "property float red\nproperty float green\nproperty float blue\n"
    "element edge 1\nproperty int a\nproperty int b\n"
    "end_header\n"
    "0 0 0 255 0 0 0\n1 0 0 0 255 0 2 7 7\n1 1 0 0 0 255 0\n"
    "0 1 0 255 255 255 1 1\n"
    "3 0 1 2 0.5 0.25 1\n4 0 1 2 3 1 1 1\n"
    "0 1\n";

static void test_ply_ascii(void **st)
{
    (void)st;
    GError *err = NULL;
    SceneMesh *m = scene_ply_parse((const guchar *)ply_ascii, strlen(ply_ascii),
                                   "a.ply", &err);
    assert_non_null(m);
    assert_int_equal(scene_mesh_n_vertices(m), 4);
    assert_int_equal(scene_mesh_n_polys(m), 2);
    assert_int_equal(scene_mesh_poly_len(m, 1), 4);
    assert_true(g_array_index(m->colors, SceneColor, 1).g == 1.0f);
    assert_true(g_array_index(m->poly_color, SceneColor, 0).g == 0.25f);
    assert_true(scene_mesh_vertex(m, 2).y == 1);
    scene_mesh_free(m);
}

/* A binary file built by hand: shorts, a double, big-endian counts. */
static void test_ply_binary_types(void **st)
{
    (void)st;
    const char hdr[] = "ply\nformat binary_big_endian 1.0\n"
                       "element vertex 3\nproperty short x\n"
                       "property double y\nproperty int8 z\n"
                       "element face 1\n"
                       "property list ushort uint32 vertex_index\n"
                       "end_header\n";
    guchar body[] = {0,    1, 0x40, 0, 0, 0, 0, 0, 0, 0, 0xff, /* 1, 2, -1 */
                     0,    2, 0,    0, 0, 0, 0, 0, 0, 0, 0,    0xff,
                     0xfe, 0, 0,    0, 0, 0, 0, 0, 0, 3, 0,    3,
                     0,    0, 0,    2, 0, 0, 0, 1, 0, 0, 0,    0};
    GByteArray *b = g_byte_array_new();
    g_byte_array_append(b, (const guchar *)hdr, strlen(hdr));
    g_byte_array_append(b, body, sizeof body);
    SceneMesh *m = scene_ply_parse(b->data, b->len, "b.ply", NULL);
    assert_non_null(m);
    Vec3 v0 = scene_mesh_vertex(m, 0), v2 = scene_mesh_vertex(m, 2);
    assert_true(v0.x == 1 && v0.y == 2 && v0.z == -1);
    assert_true(v2.x == -2 && v2.z == 3);
    assert_int_equal(scene_mesh_poly(m, 0)[0], 2);
    scene_mesh_free(m);
    g_byte_array_free(b, TRUE);
}

static SceneMesh *sample_mesh(void)
{
    SceneTeapotTess t = {4, 20};
    SceneMesh *m = scene_teapot_mesh(t, scene_color(0.2f, 0.4f, 0.6f));
    g_array_index(m->poly_color, SceneColor, 3) = scene_color(1, 0, 0);
    return m;
}

static void assert_same_mesh(const SceneMesh *a, const SceneMesh *b,
                             gboolean colours)
{
    assert_int_equal(scene_mesh_n_vertices(a), scene_mesh_n_vertices(b));
    assert_int_equal(scene_mesh_n_polys(a), scene_mesh_n_polys(b));
    assert_memory_equal(a->pos->data, b->pos->data, a->pos->len * sizeof(Vec3));
    assert_memory_equal(a->start->data, b->start->data,
                        a->start->len * sizeof(uint32_t));
    assert_memory_equal(a->idx->data, b->idx->data,
                        a->idx->len * sizeof(uint32_t));
    assert_int_equal(a->normals->len, b->normals->len);
    for (guint i = 0; i < a->normals->len; i++) {
        Vec3 d = vec3_sub(g_array_index(a->normals, Vec3, i),
                          g_array_index(b->normals, Vec3, i));
        assert_true(vec3_len(d) < 1e-12);
    }
    for (guint i = 0; colours && i < scene_mesh_n_polys(a); i++) {
        SceneColor x = g_array_index(a->poly_color, SceneColor, i);
        SceneColor y = g_array_index(b->poly_color, SceneColor, i);
        assert_true(fabsf(x.r - y.r) <= 0.5f / 255 + 1e-6f);
        assert_true(fabsf(x.b - y.b) <= 0.5f / 255 + 1e-6f);
    }
}

/* A vertex and a face of 66 properties each: values past the 64th are
 * read and dropped.  Then x as property 64 (the 65th): rejected, since
 * roles must sit among the first 64. */
static void test_ply_wide_elements(void **st)
{
    (void)st;
    GString *h = g_string_new("ply\nformat ascii 1.0\nelement vertex 3\n");
    for (int pass = 0; pass < 2; pass++) {
        g_string_truncate(h, strlen("ply\nformat ascii 1.0\nelement vertex 3\n"));
        if (!pass)
            g_string_append(h, "property float x\nproperty float y\n"
                               "property float z\n");
        for (int i = 0; i < (pass ? 62 : 63); i++)
            g_string_append_printf(h, "property float pad%d\n", i);
        if (pass)
            g_string_append(h, "property float y\nproperty float z\n"
                               "property float x\n");
        g_string_append(h, "element face 1\n"
                           "property list uchar int vertex_indices\n");
        for (int i = 0; i < 65; i++)
            g_string_append_printf(h, "property float q%d\n", i);
        g_string_append(h, "end_header\n");
        for (int v = 0; v < 3; v++) {
            g_string_append_printf(h, "%d %d %d", v, 2 * v, 3 * v);
            for (int i = 0; i < 63; i++)
                g_string_append(h, " 7");
            g_string_append(h, "\n");
        }
        g_string_append(h, "3 0 1 2");
        for (int i = 0; i < 65; i++)
            g_string_append(h, " 5");
        g_string_append(h, "\n");
        GError *err = NULL;
        SceneMesh *m =
            scene_ply_parse((const guchar *)h->str, h->len, "w.ply", &err);
        if (pass) {
            assert_null(m);
            assert_non_null(strstr(err->message, "among the first 64"));
            g_error_free(err);
            continue;
        }
        assert_non_null(m);
        Vec3 v2 = scene_mesh_vertex(m, 2);
        assert_true(v2.x == 2 && v2.y == 4 && v2.z == 6);
        assert_int_equal(scene_mesh_n_polys(m), 1);
        scene_mesh_free(m);
    }
    g_string_free(h, TRUE);
}

static void test_obj_roundtrip(void **st)
{
    (void)st;
    SceneMesh *m = sample_mesh();
    char *text = scene_obj_to_string(m);
    SceneMesh *r = obj(text);
    assert_same_mesh(m, r, FALSE);
    /* without normals the faces are written as plain 1-based indices */
    SceneMesh *bare = scene_mesh_new();
    for (int i = 0; i < 4; i++)
        scene_mesh_add_vertex(bare, vec3(i & 1, i >> 1, 0));
    scene_mesh_add_quad(bare, 0, 1, 3, 2, scene_color(1, 1, 1), 0);
    char *bt = scene_obj_to_string(bare);
    assert_non_null(strstr(bt, "f 1 2 4 3\n"));
    SceneMesh *br = obj(bt);
    assert_int_equal(scene_mesh_poly(br, 0)[2], 3);
    g_free(bt);
    scene_mesh_free(br);
    scene_mesh_free(bare);
    char *path = g_build_filename(g_get_tmp_dir(), "pgsim-rt.obj", NULL);
    assert_true(scene_obj_save(r, path, NULL));
    SceneMesh *r2 = scene_obj_load(path, NULL);
    assert_non_null(r2);
    assert_same_mesh(m, r2, FALSE);
    g_unlink(path);
    g_free(path);
    g_free(text);
    scene_mesh_free(r2);
    scene_mesh_free(r);
    scene_mesh_free(m);
}

static void test_ply_roundtrip(void **st)
{
    (void)st;
    SceneMesh *m = sample_mesh();
    for (int f = SCENE_PLY_ASCII; f <= SCENE_PLY_BINARY_BE; f++) {
        gsize len;
        guchar *data = scene_ply_encode(m, f, &len);
        GError *err = NULL;
        SceneMesh *r = scene_ply_parse(data, len, "rt.ply", &err);
        assert_non_null(r);
        assert_same_mesh(m, r, TRUE);
        scene_mesh_free(r);
        g_free(data);
    }
    char *path = g_build_filename(g_get_tmp_dir(), "pgsim-rt.ply", NULL);
    assert_true(scene_ply_save(m, path, SCENE_PLY_BINARY_LE, NULL));
    SceneMesh *r = scene_ply_load(path, NULL);
    assert_same_mesh(m, r, TRUE);
    g_unlink(path);
    g_free(path);
    scene_mesh_free(r);
    scene_mesh_free(m);
}

typedef struct {
    const char *file, *message;
} BadCase;

static const BadCase bad[] = {
    {"obj_bad_corner.obj", ":4:5: found '2x', expected a corner"},
    {"obj_bad_number.obj", ":3:5: found 'x', expected a finite number"},
    {"obj_index_range.obj", ":4:7: found '9', expected a vertex index in 1..3"},
    {"obj_index_zero.obj", ":4:3: found '0', expected a non-zero"},
    {"obj_negative_range.obj", ":4:9: found '-4', expected a vertex index"},
    {"obj_no_texcoords.obj", ":4:5: found '1', expected no texture index"},
    {"obj_normal_range.obj", ":5:11: found '2', expected a normal index"},
    {"obj_short_face.obj", ":5:1: found a face of fewer than 3 corners"},
    {"obj_short_vertex.obj", ":1:6: found end of line, expected a vertex"},
    {"ply_ascii_bad_number.ply", ":11:3: found 'zero', expected a finite"},
    {"ply_ascii_index_range.ply", ":13:1: found a vertex index out of range"},
    {"ply_ascii_short_face.ply", ":13:1: found a face of fewer than 3"},
    {"ply_ascii_truncated.ply", ":12:1: found end of file, expected a number"},
    {"ply_bad_magic.ply", ":1:1: found 'plx', expected 'ply'"},
    {"ply_bad_type.ply", ":4:10: found 'flaot', expected a type"},
    {"ply_bad_version.ply", ":2:14: found '2.0', expected version 1.0"},
    {"ply_be_index_range.ply",
     ": byte offset 202: found a vertex index out of range"},
    {"ply_face_first.ply", ":3:1: found element 'face'"},
    {"ply_huge_count.ply", ":3:16: found '99999999999', expected a count"},
    {"ply_le_nan.ply", ": byte offset 185: found a non-finite number"},
    {"ply_le_truncated.ply",
     ": byte offset 201: found end of file, expected 4 more bytes"},
    {"ply_missing_z.ply", ":3:1: found element 'vertex' without them, "
                          "expected vertex properties x, y and z"},
    {"ply_no_end_header.ply", ":5:1: found end of file, expected "
                              "'end_header'"},
};

static void test_bad_files(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *path =
            g_build_filename("tests/data/bad/scene", bad[i].file, NULL);
        GError *err = NULL;
        SceneMesh *m = g_str_has_suffix(path, ".obj")
                           ? scene_obj_load(path, &err)
                           : scene_ply_load(path, &err);
        assert_null(m);
        assert_non_null(err);
        char *want = g_strconcat(path, bad[i].message, NULL);
        if (!g_str_has_prefix(err->message, want))
            print_error("got  %s\nwant %s\n", err->message, want);
        assert_true(g_str_has_prefix(err->message, want));
        assert_int_equal(sim_error_exit_status(err), 2);
        g_free(want);
        g_error_free(err);
        g_free(path);
    }
    GError *err = NULL;
    assert_null(scene_ply_load("tests/data/bad/scene/none.ply", &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    g_error_free(err);
}

/* Every prefix of a valid file parses or fails cleanly (never crashes). */
static void test_truncations(void **st)
{
    (void)st;
    SceneTeapotTess t = {3, 0};
    SceneMesh *m = scene_teapot_mesh(t, scene_color(1, 1, 1));
    for (int f = SCENE_PLY_ASCII; f <= SCENE_PLY_BINARY_BE; f++) {
        gsize len;
        guchar *data = scene_ply_encode(m, f, &len);
        guint ok = 0;
        for (gsize n = 0; n < len; n += 1 + n / 64) {
            guchar *cut = g_memdup2(data, n);
            GError *err = NULL;
            SceneMesh *r = scene_ply_parse(cut, n, "cut.ply", &err);
            assert_true((r == NULL) == (err != NULL));
            ok += r != NULL;
            scene_mesh_free(r);
            if (err)
                g_error_free(err);
            g_free(cut);
        }
        if (f != SCENE_PLY_ASCII) /* a cut ASCII number may still parse */
            assert_int_equal(ok, 0);
        g_free(data);
    }
    scene_mesh_free(m);
}

/* Random byte corruptions of OBJ and PLY text and binary. */
static void test_corruptions(void **st)
{
    (void)st;
    SceneTeapotTess t = {3, 0};
    SceneMesh *m = scene_teapot_mesh(t, scene_color(1, 1, 1));
    SimRng r;
    sim_rng_init(&r, 42, 0);
    for (int f = -1; f <= SCENE_PLY_BINARY_BE; f++) {
        gsize len;
        guchar *data = f < 0 ? (guchar *)scene_obj_to_string(m)
                             : scene_ply_encode(m, f, &len);
        if (f < 0)
            len = strlen((char *)data);
        for (int trial = 0; trial < 200; trial++) {
            guchar *bad = g_memdup2(data, len);
            for (int k = 0; k < 4; k++)
                bad[sim_rng_below(&r, len)] = (guchar)sim_rng_below(&r, 256);
            GError *err = NULL;
            SceneMesh *x = f < 0 ? scene_obj_parse((char *)bad, len, "c", &err)
                                 : scene_ply_parse(bad, len, "c", &err);
            assert_true((x == NULL) == (err != NULL));
            if (x)
                assert_true(scene_mesh_validate(x, "c", NULL));
            scene_mesh_free(x);
            if (err)
                g_error_free(err);
            g_free(bad);
        }
        g_free(data);
    }
    scene_mesh_free(m);
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_obj_forms),
        cmocka_unit_test(test_ply_ascii),
        cmocka_unit_test(test_ply_binary_types),
        cmocka_unit_test(test_ply_wide_elements),
        cmocka_unit_test(test_obj_roundtrip),
        cmocka_unit_test(test_ply_roundtrip),
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_truncations),
        cmocka_unit_test(test_corruptions),
    };
    return cmocka_run_group_tests_name("loaders", tests, NULL, NULL);
}
