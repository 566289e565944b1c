/* test_ply_tokens.c — the PLY tokenizer's edges (sim/scene/ply.c): an
 * ASCII number of 63 bytes is read whole and one of 64 is refused (not
 * read cut to its first 63); and the reader never looks past `len`: each
 * file, good or bad, parses from an exact-size heap copy (whose end a
 * sanitizer guards) and from a copy followed by more bytes exactly as
 * from the NUL-terminated text -- same mesh or the same error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/ply.h"
#include "tests/support.h"

#define HA "ply\nformat ascii 1.0\n"
#define VXYZ "property double x\nproperty double y\nproperty double z\n"

static SceneMesh *parse(const char *t, gsize len, GError **err)
{
    return scene_ply_parse((const guchar *)t, len, "t.ply", err);
}

static void test_long_numbers(void **st)
{
    (void)st;
    GString *num = g_string_new("0.");
    for (int i = 0; i < 60; i++)
        g_string_append_c(num, '0');
    g_string_append_c(num, '1'); /* 63 bytes: 1e-61 */
    char *t = g_strdup_printf(HA "element vertex 1\n" VXYZ "end_header\n"
                              "%s 2 3\n", num->str);
    GError *err = NULL;
    SceneMesh *m = parse(t, strlen(t), &err);
    assert_non_null(m);
    Vec3 v = scene_mesh_vertex(m, 0);
    assert_true(v.x == 1e-61 && v.y == 2 && v.z == 3);
    scene_mesh_free(m);
    g_free(t);
    g_string_insert_c(num, 2, '0'); /* 64 bytes: refused */
    t = g_strdup_printf(HA "element vertex 1\n" VXYZ "end_header\n%s 2 3\n",
                        num->str);
    assert_null(parse(t, strlen(t), &err));
    assert_string_equal(err->message,
                        "t.ply:8:1: found '0.00000000000000000000000000000000"
                        "000000', expected a finite number");
    g_clear_error(&err);
    g_free(t);
    g_string_free(num, TRUE);
}

/* The same outcome from the string, an exact-size copy and a copy that
 * goes on with `more`. */
static void same_outcome(const char *text, const char *more)
{
    gsize len = strlen(text);
    char *exact = g_memdup2(text, len), *longer = g_strconcat(text, more, NULL);
    const char *src[3] = {text, exact, longer};
    SceneMesh *m[3];
    GError *e[3] = {NULL, NULL, NULL};
    for (guint k = 0; k < 3; k++)
        m[k] = parse(src[k], len, &e[k]);
    for (guint k = 1; k < 3; k++) {
        if (!m[0] || !m[k]) {
            if (m[0] || m[k] || strcmp(e[0]->message, e[k]->message))
                fail_msg("case %u: %s | %s\n%s", k,
                         e[0] ? e[0]->message : "-",
                         e[k] ? e[k]->message : "-", text);
            continue;
        }
        /* the same mesh: the same bytes written back */
        gsize na, nb;
        guchar *a = scene_ply_encode(m[0], SCENE_PLY_BINARY_LE, &na);
        guchar *b = scene_ply_encode(m[k], SCENE_PLY_BINARY_LE, &nb);
        assert_int_equal(na, nb);
        assert_memory_equal(a, b, na);
        g_free(a);
        g_free(b);
    }
    for (guint k = 0; k < 3; k++) {
        scene_mesh_free(m[k]);
        g_clear_error(&e[k]);
    }
    g_free(exact);
    g_free(longer);
}

static void test_nothing_past_len(void **st)
{
    (void)st;
    const char *tri = HA "element vertex 3\n" VXYZ
                      "element face 1\nproperty list uchar int vertex_indices\n"
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2";
    const char *cases[][2] = {
        {tri, "1"},                           /* an index going on */
        {tri, " 1\n"},
        {tri, "\n"},
        {HA "element vertex 1\n" VXYZ "end_header\n1 2 3", "4"},
        {HA "element vertex 1\n" VXYZ "end_header\n1 2 3 ", "4"},
        {HA "element vertex 1\n" VXYZ "end_header\n1 2", " 3"},
        {HA "comment no end", "\nend_header\n"},
        {HA "element vertex 1\n" VXYZ "end_header", "\n1 2 3\n"},
        {HA "element vertex 1\n" VXYZ "end_header  ", "\n1 2 3\n"},
        {HA "element vertex 1\nproperty double", " x\n"},
        {HA "element vertex 1\nproperty list", " uchar int x\n"},
        {HA "element vertex", " 1\n"},
        {"ply\nformat ascii 1.0", "\n"},
        {"ply", "\n"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
         "property uchar x\nproperty uchar y\nproperty uchar z\nend_header\n"
         "\1\2",
         "\3"},
        {"ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
         "property uchar x\nproperty uchar y\nproperty uchar z\nend_header\n"
         "\1\2\3",
         "\4"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++)
        same_outcome(cases[i][0], cases[i][1]);
}

/* A header error stops the reader even when the rest of the file is
 * good: each case is a whole valid file but for one line. */
static void test_errors_stop(void **st)
{
    (void)st;
    const char *rest = VXYZ "end_header\n0 0 0\n";
    const char *cases[][2] = {
        {HA "element vertex 1 2\n", "t.ply:3:18: found '2', expected end "
                                    "of line"},
        {HA "element vertex 1\nproperty double w q\n",
         "t.ply:4:19: found 'q', expected end of line"},
        {"ply\nformat ascii 1.0 x\nelement vertex 1\n",
         "t.ply:2:18: found 'x', expected end of line"},
        {"ply\nformat ascii 2.0\nelement vertex 1\n",
         "t.ply:2:14: found '2.0', expected version 1.0"},
        {HA "element vertex 1\nproperty list flt int w\n",
         "t.ply:4:15: found 'flt', expected a type (char uchar short ushort "
         "int uint float double or int8 ... float64)"},
        {HA "element vertex 1\nproperty list float int w\n",
         "t.ply:4:15: found 'float', expected an integer list-count type"},
        {HA "element vertex 1\nproperty list uchar flt w\n",
         "t.ply:4:21: found 'flt', expected a type (char uchar short ushort "
         "int uint float double or int8 ... float64)"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        char *t = g_strconcat(cases[i][0], rest, NULL);
        GError *err = NULL;
        SceneMesh *m = parse(t, strlen(t), &err);
        if (m)
            fail_msg("accepted: %s", t);
        assert_string_equal(err->message, cases[i][1]);
        g_error_free(err);
        g_free(t);
        same_outcome(cases[i][0], rest); /* and cut before the rest */
    }
    same_outcome(HA "element vertex 1\nproperty li", "st uchar int x\n");
}

/* A face without colour properties is white; one with them keeps its
 * own (integers over 255). */
static void test_face_colour(void **st)
{
    (void)st;
    const char *t = HA "element vertex 3\n" VXYZ "element face 2\n"
                    "property list uchar int vertex_indices\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n";
    GError *err = NULL;
    SceneMesh *m = parse(t, strlen(t), &err);
    assert_non_null(m);
    for (guint i = 0; i < 2; i++) {
        SceneColor c = g_array_index(m->poly_color, SceneColor, i);
        assert_true(c.r == 1 && c.g == 1 && c.b == 1);
        assert_int_equal(g_array_index(m->poly_tag, uint32_t, i), 0);
    }
    scene_mesh_free(m);
    t = HA "element vertex 3\n" VXYZ "element face 1\n"
        "property list uchar int vertex_indices\nproperty uchar red\n"
        "property uchar green\nproperty uchar blue\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 51\n";
    m = parse(t, strlen(t), &err);
    assert_non_null(m);
    SceneColor c = g_array_index(m->poly_color, SceneColor, 0);
    assert_true(c.r == 1 && c.g == 0 && c.b == 0.2f);
    /* written back as bytes, clamped to [0, 1] first */
    g_array_index(m->poly_color, SceneColor, 0) =
        (SceneColor){1.5f, -0.5f, 0.2f};
    gsize n;
    guchar *b = scene_ply_encode(m, SCENE_PLY_ASCII, &n);
    char *text = g_strndup((const char *)b, n);
    assert_non_null(strstr(text, "\n 3 0 1 2 255 0 51\n"));
    g_free(text);
    g_free(b);
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
        cmocka_unit_test(test_errors_stop),
        cmocka_unit_test(test_face_colour),
    };
    return cmocka_run_group_tests_name("ply_tokens", tests, NULL, NULL);
}
