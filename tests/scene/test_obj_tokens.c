/* test_obj_tokens.c — the OBJ tokenizer's edges (sim/scene/obj.c): a
 * number token of 63 bytes is read whole and one of 64 is refused whole
 * (not read in pieces); the reader never looks past `len` (a buffer that
 * goes on with digits, slashes or a '#' right after the last byte parses
 * exactly as the same text cut there, successes and errors alike); the last line needs no newline;
 * columns count from 1 after tabs and CRs; corners v/vt/vn read each
 * index; an index as large as the counter allows is refused, not wrapped. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/obj.h"
#include "tests/support.h"

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

static SceneMesh *parse(const char *text, gsize len, GError **err)
{
    return scene_obj_parse(text, len, "t.obj", err);
}

static void fails(const char *text, const char *want)
{
    GError *err = NULL;
    assert_null(parse(text, strlen(text), &err));
    if (strcmp(err->message, want))
        print_error("got  %s\nwant %s\n", err->message, want);
    assert_string_equal(err->message, want);
    g_error_free(err);
}

static void test_long_numbers(void **st)
{
    (void)st;
    /* 0.000...01 of 63 bytes: 1e-61, read whole */
    GString *t = g_string_new("v 0.");
    for (int i = 0; i < 60; i++)
        g_string_append_c(t, '0');
    g_string_append(t, "1 2 3\n");
    GError *err = NULL;
    SceneMesh *m = parse(t->str, t->len, &err);
    assert_non_null(m);
    Vec3 v = scene_mesh_vertex(m, 0);
    assert_true(v.x == 1e-61 && v.y == 2 && v.z == 3);
    scene_mesh_free(m);
    /* one digit more: 64 bytes, refused at its first byte */
    g_string_insert_c(t, 4, '0');
    fails(t->str, "t.obj:1:3: found '0.00000000000000000000000000000000000000',"
                  " expected a finite number");
    g_string_free(t, TRUE);
}

/* `full` cut to its first `len` bytes parses like the cut copy (whose
 * end is a NUL) and like an exact-size heap copy (whose end a sanitizer
 * guards): same vertices, faces and normals, or the same error. */
static void same_as_cut(const char *full, gsize len)
{
    char *cut = g_strndup(full, len), *exact = g_memdup2(full, len);
    GError *e[3] = {NULL, NULL, NULL};
    SceneMesh *m[3] = {parse(full, len, &e[0]), parse(cut, len, &e[1]),
                       parse(exact, len, &e[2])};
    for (guint k = 1; k < 3; k++) {
        SceneMesh *a = m[0], *b = m[k];
        if (!a || !b) {
            if (a || b || strcmp(e[0]->message, e[k]->message))
                fail_msg("'%s' (%" G_GSIZE_FORMAT "): %s | %s", full, len,
                         e[0] ? e[0]->message : "-",
                         e[k] ? e[k]->message : "-");
            continue;
        }
        assert_int_equal(scene_mesh_n_vertices(a), scene_mesh_n_vertices(b));
        assert_int_equal(scene_mesh_n_polys(a), scene_mesh_n_polys(b));
        for (guint i = 0; i < scene_mesh_n_vertices(a); i++) {
            Vec3 p = scene_mesh_vertex(a, i), q = scene_mesh_vertex(b, i);
            assert_memory_equal(&p, &q, sizeof p);
        }
        for (guint i = 0; i < scene_mesh_n_polys(a); i++)
            assert_memory_equal(scene_mesh_poly(a, i), scene_mesh_poly(b, i),
                                scene_mesh_poly_len(a, i) * sizeof(uint32_t));
        assert_int_equal(a->normals->len, b->normals->len);
    }
    for (guint k = 0; k < 3; k++) {
        scene_mesh_free(m[k]);
        g_clear_error(&e[k]);
    }
    g_free(cut);
    g_free(exact);
}

static void test_nothing_past_len(void **st)
{
    (void)st;
    /* each: the text, then bytes a reader must not see */
    const char *cases[][2] = {
        {TRI "f 1 2 3", "1"},           /* an index going on */
        {TRI "f 1 2 3", "/1/1"},        /* a corner going on */
        {TRI "f 1 2 -1", "2"},          /* a negative index */
        {TRI "vn 0 0 1\nf 1//1 2//1 3//1", "1"},
        {TRI "vt 0 0\nf 1/1 2/1 3/1", "/1"},
        {TRI "f 1 2 3\nv 0 0 2", "5"},  /* a coordinate going on */
        {TRI "f 1 2 3\nvn 0 0 1", "7"},
        {TRI "f 1 2 3\nv 0 0 2", " 7 8 9"},
        {TRI "f 1 2 3\nv 0 0 2", "#"},
        {TRI "f 1 2 3 ", "4"},          /* a blank, then a corner */
        {TRI "f 1 2 3\n# v", " 1 2 3"}, /* a comment going on */
        {TRI "f 1 2 3\nf", "  1 2 3"},  /* a keyword going on */
        {TRI "f 1 2 3\nv", "n 0 0 1"},
        {TRI "f 1 2 3 \t", "4"},        /* blanks, then a corner */
        {TRI "vn 0 0 1\nf 1//1 2//1 3//", "-1"}, /* an empty last index */
        {TRI "f 1 2 3\nv 0 0 -", "1"},  /* a bare sign */
        {TRI "vt 0 0\nf 1/1 2/1 3/", "1"}, /* an empty last texture index */
    };
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        char *full = g_strconcat(cases[i][0], cases[i][1], NULL);
        same_as_cut(full, strlen(cases[i][0]));
        g_free(full);
    }
}

/* Columns after tabs and CRs; the token quoted up to a tab or CR. */
static void test_columns(void **st)
{
    (void)st;
    fails(TRI "f\t1 2\t4\r\n", "t.obj:4:7: found '4', expected a vertex "
                               "index in 1..3 or -1..-3");
    fails(TRI "f 1 2 3x\t\n", "t.obj:4:7: found '3x', expected a corner v, "
                              "v/vt, v//vn or v/vt/vn");
    fails("v\t1 2 y\r\n", "t.obj:1:7: found 'y', expected a finite number");
    fails("v 1 2 3 z\r\n", "t.obj:1:9: found 'z', expected a finite number");
    fails(TRI "f 1/x 2 3\n", "t.obj:4:5: found 'x', expected a non-zero "
                             "integer index");
    fails(TRI "f 1/1/1 2 3\n", "t.obj:4:5: found '1/1', expected no texture "
                               "index (none defined above)");
    fails(TRI "f 4294967295 1 2\n", "t.obj:4:3: found '4294967295', expected "
                                    "a vertex index in 1..3 or -1..-3");
    fails(TRI "f 1 2 4294967299\n", "t.obj:4:7: found '4294967299', expected "
                                    "a vertex index in 1..3 or -1..-3");
    /* a comment right after a corner ends the face */
    GError *err = NULL;
    const char *t = TRI "f 1 2 3# c\n";
    SceneMesh *m = parse(t, strlen(t), &err);
    assert_non_null(m);
    assert_int_equal(scene_mesh_n_polys(m), 1);
    scene_mesh_free(m);
    /* an empty texture field at the line's end is allowed; vp (parameter
     * vertices) are not texture coordinates */
    t = TRI "vt 0 0\nf 1/1 2/1 3/\n";
    m = parse(t, strlen(t), &err);
    assert_non_null(m);
    assert_int_equal(scene_mesh_n_polys(m), 1);
    scene_mesh_free(m);
    fails(TRI "vp 0 0\nf 1/1 2 3\n", "t.obj:5:5: found '1', expected no "
                                     "texture index (none defined above)");
    /* v/vt/vn: the normal index is the third field */
    t = TRI "vt 0 0\nvt 1 1\nvn 1 0 0\nvn 0 0 1\nf 1/2/2 2/1/2 3/2/2\n";
    m = parse(t, strlen(t), &err);
    assert_non_null(m);
    Vec3 n = g_array_index(m->normals, Vec3, 1);
    assert_true(n.x == 0 && n.z == 1);
    scene_mesh_free(m);
}

/* Faces read are white; a one-vertex mesh writes its colour and normal
 * (present means at least one, not more than one). */
static void test_faces_and_writer(void **st)
{
    (void)st;
    const char *t = TRI "f 1 2 3\nf 3 2 1\n";
    GError *err = NULL;
    SceneMesh *m = parse(t, strlen(t), &err);
    assert_non_null(m);
    for (guint i = 0; i < 2; i++) {
        SceneColor c = g_array_index(m->poly_color, SceneColor, i);
        assert_true(c.r == 1 && c.g == 1 && c.b == 1);
    }
    scene_mesh_free(m);
    m = scene_mesh_new();
    scene_mesh_add_vertex(m, vec3(1, 2, 3));
    SceneColor c = {0.5f, 0.25f, 1};
    g_array_append_val(m->colors, c);
    Vec3 n = vec3(0, 0, 1);
    g_array_append_val(m->normals, n);
    char *text = scene_obj_to_string(m);
    assert_string_equal(text, "# pgsim OBJ\nv 1 2 3 0.5 0.25 1\nvn 0 0 1\n");
    g_free(text);
    scene_mesh_free(m);
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_long_numbers),
        cmocka_unit_test(test_nothing_past_len),
        cmocka_unit_test(test_columns),
        cmocka_unit_test(test_faces_and_writer),
    };
    return cmocka_run_group_tests_name("obj_tokens", tests, NULL, NULL);
}
