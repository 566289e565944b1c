/* test_mesh_errors.c — every located error of the OBJ and PLY readers
 * (sim/scene/obj.c, ply.c) with its whole message, file:line:column
 * included, plus the boundaries next to each check (a value exactly at a
 * limit is accepted, one past it is not) and the fields the readers fill
 * (tags, padded normals and colours, every PLY scalar type).  Found by
 * make coverage and make mutate (docs/testing.md): the bad-file table of
 * test_loaders.c checks message prefixes; this one checks them whole. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/scene/obj.h"
#include "sim/scene/ply.h"
#include "tests/support.h"

typedef struct {
    const char *text, *message; /* message without the "t.obj:" prefix */
} Case;

static void check_message(const GError *err, const char *prefix,
                          const char *want)
{
    assert_non_null(err);
    char *full = g_strconcat(prefix, want, NULL);
    if (strcmp(err->message, full))
        print_error("got  %s\nwant %s\n", err->message, full);
    assert_string_equal(err->message, full);
    assert_int_equal(err->code, SIM_ERROR_INPUT);
    g_free(full);
}

static void obj_fails(const char *text, const char *want)
{
    GError *err = NULL;
    assert_null(scene_obj_parse(text, strlen(text), "t.obj", &err));
    check_message(err, "t.obj:", want);
    g_error_free(err);
}

static SceneMesh *obj_ok(const char *text)
{
    GError *err = NULL;
    SceneMesh *m = scene_obj_parse(text, strlen(text), "t.obj", &err);
    if (!m)
        print_error("%s\n", err->message);
    assert_non_null(m);
    return m;
}

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

static const Case obj_bad[] = {
    {"v 1 2 3 4 5 6 7\n",
     "1:15: found '7', expected end of line after 3, 4 or 6 numbers"},
    {"v 1 2\n", "1:6: found end of line, expected a vertex of 3, 4 or 6 "
                "numbers"},
    {"v 1 2 3 4 5\n", "1:12: found end of line, expected a vertex of 3, 4 "
                      "or 6 numbers"},
    {"v 1 2 3 0\n", "1:9: found w = 0, expected a non-zero w"},
    {"v 1 2 2e15\n", "1:7: found a coordinate 2e+15, expected a coordinate "
                     "within +-1e+15 (docs/config.md, Limits)"},
    {"v 0 -1.5e15 0\n", "1:5: found a coordinate -1.5e+15, expected a "
                        "coordinate within +-1e+15 (docs/config.md, Limits)"},
    {"v 4e15 2 3 2\n", "1:3: found a coordinate over w 2e+15, expected a "
                       "coordinate within +-1e+15 (docs/config.md, Limits)"},
    {"v 0 0 0 1.5 0 0\n", "1:9: found a colour 1.5, expected a colour "
                          "component in [0, 1]"},
    {"v 0 0 0 0 0 -0.5\n", "1:13: found a colour -0.5, expected a colour "
                           "component in [0, 1]"},
    {"v 1 nan 3\n", "1:5: found 'nan', expected a finite number"},
    {"v 1e999 0 0\n", "1:3: found '1e999', expected a finite number"},
    {"v 1 2 3 4 5 6 " "abcdefghijabcdefghijabcdefghijabcdefghijXYZ\n",
     "1:15: found 'abcdefghijabcdefghijabcdefghijabcdefghij', expected end "
     "of line after 3, 4 or 6 numbers"},
    {"vn 1 2\n", "1:7: found end of line, expected 3 numbers"},
    {"vn 1 2 3 4\n", "1:10: found '4', expected end of line"},
    {"vn 1 y 3\n", "1:6: found 'y', expected a finite number"},
    {"vn 0 0 5e15\n", "1:8: found a coordinate 5e+15, expected a coordinate "
                      "within +-1e+15 (docs/config.md, Limits)"},
    {TRI "f\n", "4:1: found an empty face, expected at least 3 corners"},
    {TRI "f 1 2 # c\n", "4:1: found a face of fewer than 3 corners, expected "
                        "at least 3 corners"},
    {TRI "f 0 1 2\n", "4:3: found '0', expected a non-zero integer index"},
    {TRI "f x 1 2\n", "4:3: found 'x', expected a non-zero integer index"},
    {TRI "f 1 2 4\n", "4:7: found '4', expected a vertex index in 1..3 or "
                      "-1..-3"},
    {TRI "f -4 1 2\n", "4:3: found '-4', expected a vertex index in 1..3 or "
                       "-1..-3"},
    {TRI "f 99999999999 1 2\n", "4:3: found '99999999999', expected a vertex "
                                "index in 1..3 or -1..-3"},
    {"f 1 2 3\n", "1:3: found '1', expected no vertex index (none defined "
                  "above)"},
    {TRI "f 1//1 2//1 3//1\n", "4:6: found '1', expected no normal index "
                               "(none defined above)"},
    {TRI "vn 0 0 1\nf 1//1 2//2 3//1\n", "5:11: found '2', expected a normal "
                                         "index in 1..1 or -1..-1"},
    {TRI "vt 0 0\nf 1/1 2/2 3/1\n", "5:9: found '2', expected a texture "
                                    "index in 1..1 or -1..-1"},
    {TRI "f 1 2 3x\n", "4:7: found '3x', expected a corner v, v/vt, v//vn or "
                       "v/vt/vn"},
    {"v 0 0 0\r\nv 1\0 0 0\r\n", "2:4: found a NUL byte, expected text"},
    {"# one\n\n  \nv 0 0\n", "4:6: found end of line, expected a vertex of "
                             "3, 4 or 6 numbers"},
};

static void test_obj_errors(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(obj_bad); i++) {
        const char *t = obj_bad[i].text;
        gsize len = strlen(t);
        if (strchr(t, '\r')) /* the NUL case: its length by hand */
            len = strlen(t) + 1 + strlen(t + strlen(t) + 1);
        GError *err = NULL;
        assert_null(scene_obj_parse(t, len, "t.obj", &err));
        check_message(err, "t.obj:", obj_bad[i].message);
        g_error_free(err);
    }
}

/* The values just inside each limit are accepted. */
static void test_obj_limits(void **st)
{
    (void)st;
    SceneMesh *m = obj_ok("v 1e15 -1e15 0\nv 2e15 0 0 2\nv 0 0 0 1 0 0\n"
                          "v 0 0 0 0 1 1\nv 1 2 3 -1\n");
    assert_int_equal(scene_mesh_n_vertices(m), 5);
    Vec3 a = scene_mesh_vertex(m, 0), b = scene_mesh_vertex(m, 1),
         e = scene_mesh_vertex(m, 4);
    assert_true(a.x == 1e15 && a.y == -1e15 && a.z == 0);
    assert_true(b.x == 1e15 && b.y == 0);
    assert_true(e.x == -1 && e.y == -2 && e.z == -3); /* w = -1 */
    assert_int_equal(m->colors->len, 5);
    SceneColor c0 = g_array_index(m->colors, SceneColor, 0),
               c2 = g_array_index(m->colors, SceneColor, 2),
               c3 = g_array_index(m->colors, SceneColor, 3),
               c4 = g_array_index(m->colors, SceneColor, 4);
    assert_true(c0.r == 1 && c0.g == 1 && c0.b == 1); /* padded white */
    assert_true(c2.r == 1 && c2.g == 0 && c2.b == 0);
    assert_true(c3.r == 0 && c3.g == 1 && c3.b == 1);
    assert_true(c4.r == 1 && c4.g == 1 && c4.b == 1);
    assert_int_equal(m->normals->len, 0); /* no face */
    scene_mesh_free(m);
    obj_fails("v 1.000001e15 0 0\n", "1:3: found a coordinate 1e+15, "
              "expected a coordinate within +-1e+15 (docs/config.md, Limits)");
    obj_fails("v 0 0 0 0 1.0000001 0\n", "1:11: found a colour 1, expected a "
              "colour component in [0, 1]");
}

/* Indices: negative ones count back from the last vertex defined so far;
 * the last valid index either way is accepted. */
static void test_obj_indices(void **st)
{
    (void)st;
    SceneMesh *m = obj_ok(TRI "f -1 -2 -3\nf 3 1 2\nv 5 5 5\nf -1 -4 1 2\n");
    assert_int_equal(scene_mesh_n_polys(m), 3);
    const uint32_t *f0 = scene_mesh_poly(m, 0), *f1 = scene_mesh_poly(m, 1),
                   *f2 = scene_mesh_poly(m, 2);
    assert_true(f0[0] == 2 && f0[1] == 1 && f0[2] == 0);
    assert_true(f1[0] == 2 && f1[1] == 0 && f1[2] == 1);
    assert_int_equal(scene_mesh_poly_len(m, 2), 4);
    assert_true(f2[0] == 3 && f2[1] == 0 && f2[2] == 0 && f2[3] == 1);
    scene_mesh_free(m);
}

/* o and g start a new tag only once a face was read; every face of an
 * object has its tag. */
static void test_obj_tags(void **st)
{
    (void)st;
    SceneMesh *m = obj_ok("o a\ng b\n" TRI "f 1 2 3\nf 1 2 3\ng c\no d\n"
                          "f 1 2 3\ng e\nf 3 2 1\n");
    assert_int_equal(scene_mesh_n_polys(m), 4);
    const uint32_t *tag = (const uint32_t *)m->poly_tag->data;
    assert_true(tag[0] == 0 && tag[1] == 0 && tag[2] == 2 && tag[3] == 3);
    scene_mesh_free(m);
}

/* Normals: kept only when every corner of every face names one; a vertex
 * no face touches gets a zero normal; the vn are normalised. */
static void test_obj_normals(void **st)
{
    (void)st;
    SceneMesh *m = obj_ok(TRI "v 5 5 5\nvn 0 0 3\nvn 4 0 0\n"
                          "f 1//1 2//2 3//1\n");
    assert_int_equal(m->normals->len, 4);
    Vec3 n0 = g_array_index(m->normals, Vec3, 0),
         n1 = g_array_index(m->normals, Vec3, 1),
         n3 = g_array_index(m->normals, Vec3, 3);
    assert_true(n0.x == 0 && n0.y == 0 && n0.z == 1);
    assert_true(n1.x == 1 && n1.y == 0 && n1.z == 0);
    assert_true(n3.x == 0 && n3.y == 0 && n3.z == 0);
    scene_mesh_free(m);
    m = obj_ok(TRI "vn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n");
    assert_int_equal(m->normals->len, 0);
    scene_mesh_free(m);
    m = obj_ok(TRI "vn 0 0 1\nf 1//1 2 3//1\n");
    assert_int_equal(m->normals->len, 0);
    scene_mesh_free(m);
}

/* Vertex colours are written out and read back; a save to a directory
 * that does not exist is an I/O error naming the path. */
static void test_obj_colours_and_save(void **st)
{
    (void)st;
    SceneMesh *m = obj_ok("v 0 0 0 0.5 0.25 1\nv 1 0 0\nv 0 1 0 0 0 0\n"
                          "f 1 2 3\n");
    char *text = scene_obj_to_string(m);
    assert_non_null(strstr(text, "\nv 0 0 0 0.5 0.25 1\nv 1 0 0 1 1 1\n"));
    SceneMesh *r = obj_ok(text);
    assert_int_equal(r->colors->len, 3);
    for (guint i = 0; i < 3; i++) {
        SceneColor a = g_array_index(m->colors, SceneColor, i),
                   b = g_array_index(r->colors, SceneColor, i);
        assert_true(a.r == b.r && a.g == b.g && a.b == b.b);
    }
    GError *err = NULL;
    assert_false(scene_obj_save(m, "/nonexistent-pgsim-dir/m.obj", &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    assert_true(g_str_has_prefix(err->message, "/nonexistent-pgsim-dir/m.obj: "));
    g_clear_error(&err);
    assert_false(scene_ply_save(m, "/nonexistent-pgsim-dir/m.ply",
                                SCENE_PLY_ASCII, &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    assert_true(g_str_has_prefix(err->message, "/nonexistent-pgsim-dir/m.ply: "));
    g_clear_error(&err);
    g_free(text);
    scene_mesh_free(r);
    scene_mesh_free(m);
}

/* ---- PLY ---------------------------------------------------------------- */

static void ply_fails(const char *text, gsize len, const char *want)
{
    GError *err = NULL;
    SceneMesh *m = scene_ply_parse((const guchar *)text, len, "t.ply", &err);
    if (m)
        print_error("parsed, expected %s\n", want);
    assert_null(m);
    check_message(err, "t.ply", want);
    g_error_free(err);
}

static SceneMesh *ply_ok(const char *text, gsize len)
{
    GError *err = NULL;
    SceneMesh *m = scene_ply_parse((const guchar *)text, len, "t.ply", &err);
    if (!m)
        print_error("%s\n", err->message);
    assert_non_null(m);
    return m;
}

#define HA "ply\nformat ascii 1.0\n"
#define VXYZ "property float x\nproperty float y\nproperty float z\n"
#define FACE "element face 1\nproperty list uchar int vertex_indices\n"
#define BODY3 "0 0 0\n1 0 0\n0 1 0\n"

#define Q10 "qqqqqqqqqq"
#define Q40 Q10 Q10 Q10 Q10

static const Case ply_bad[] = {
    /* a 100-character token: read into a 64-byte buffer, cut, quoted
     * to its first 40 */
    {HA Q40 Q40 Q10 Q10 "\n", ":3:1: found '" Q40 "', expected format, "
     "comment, obj_info, element, property or end_header"},
    {"ply extra\n", ":1:5: found 'extra', expected end of line"},
    {"plyx\n", ":1:1: found 'plyx', expected 'ply' (the PLY magic line)"},
    {HA "property float x\n", ":3:1: found 'property', expected an "
                              "'element' line before it"},
    {HA "element face 1\nproperty list float int vertex_indices\n",
     ":4:15: found 'float', expected an integer list-count type"},
    {HA "element face 1\nproperty list double int vertex_indices\n",
     ":4:15: found 'double', expected an integer list-count type"},
    {HA "element vertex 1\nproperty float\n", ":4:15: found end of line, "
                                              "expected a property name"},
    {HA "element vertex 1\nproperty float x y\n", ":4:18: found 'y', "
                                                  "expected end of line"},
    {HA "element vertex 1\nproperty flt x\n", ":4:10: found 'flt', expected "
     "a type (char uchar short ushort int uint float double or int8 ... "
     "float64)"},
    {HA "element\n", ":3:8: found end of line, expected an element name"},
    {HA "element vertex\n", ":3:15: found end of line, expected an element "
                            "count"},
    {HA "element vertex x1\n", ":3:16: found 'x1', expected an element "
                               "count"},
    {HA "element vertex -1\n", ":3:16: found '-1', expected an element "
                               "count"},
    {HA "element vertex 1x\n", ":3:16: found '1x', expected an element "
                               "count"},
    /* the same in a file that is whole otherwise: still refused */
    {HA "element vertex 3x\n" VXYZ FACE "end_header\n" BODY3 "3 0 1 2\n",
     ":3:16: found '3x', expected an element count"},
    {HA "element vertex 99\n", ":3:16: found '99', expected a count the "
                               "file size can hold"},
    {HA "element vertex 1 2\n", ":3:18: found '2', expected end of line"},
    {"ply\nformat ascii\n", ":2:13: found end of line, expected version 1.0"},
    {"ply\nformat text 1.0\n", ":2:8: found 'text', expected ascii, "
     "binary_little_endian or binary_big_endian"},
    {"ply\nformat ascii 1.0 x\n", ":2:18: found 'x', expected end of line"},
    {"ply\nelement vertex 0\nend_header\n", ":3:1: found 'end_header', "
                                            "expected a 'format' line before "
                                            "end_header"},
    {HA "vertex 3\n", ":3:1: found 'vertex', expected format, comment, "
                      "obj_info, element, property or end_header"},
    {HA "element vertex 1\nproperty int x\nproperty int y\nproperty int z\n"
        "end_header\n0 1.5 0\n", ":8:3: found '1.5', expected an integer"},
    {HA "element vertex 1\n" VXYZ "property float nx\nproperty float ny\n"
        "end_header\n0 0 0 0 0\n", ":3:1: found element 'vertex' without "
                                   "them, expected all of nx, ny, nz or none"},
    {HA "element vertex 1\n" VXYZ "property float nx\nproperty float nz\n"
        "end_header\n0 0 0 0 0\n", ":3:1: found element 'vertex' without "
                                   "them, expected all of nx, ny, nz or none"},
    {HA "element vertex 1\n" VXYZ "property uchar red\nproperty uchar blue\n"
        "end_header\n0 0 0 0 0\n", ":3:1: found element 'vertex' without "
                                   "them, expected all of red, green, blue "
                                   "or none"},
    {HA "element vertex 1\n" VXYZ "property uchar green\n"
        "end_header\n0 0 0 0\n", ":3:1: found element 'vertex' without "
                                 "them, expected all of red, green, blue or "
                                 "none"},
    {HA "element vertex 1\n" VXYZ "property float ny\n"
        "end_header\n0 0 0 0\n", ":3:1: found element 'vertex' without "
                                 "them, expected all of nx, ny, nz or none"},
    {HA "element vertex 3\n" VXYZ FACE "property float blue\n"
        "end_header\n" BODY3 "3 0 1 2 1\n",
     ":7:1: found element 'face' without them, expected all of red, green, "
     "blue or none"},
    {HA "element vertex 1\nproperty float x\nproperty float z\n"
        "end_header\n0 0\n", ":3:1: found element 'vertex' without them, "
                             "expected vertex properties x, y and z"},
    {HA "element vertex 3\n" VXYZ "element face 1\nproperty int "
        "vertex_indices\nend_header\n" BODY3 "0\n",
     ":7:1: found element 'face' without them, expected a face list "
     "property vertex_indices"},
    {HA "element vertex 3\n" VXYZ "element face 1\nproperty list uchar int "
        "corners\nend_header\n" BODY3 "3 0 1 2\n",
     ":7:1: found element 'face' without them, expected a face list "
     "property vertex_indices"},
    {HA "element vertex 3\n" VXYZ FACE "end_header\n" BODY3 "3 0 1 3\n",
     ":13:1: found a vertex index out of range, expected vertex indices in "
     "0..2"},
    {HA "element vertex 0\n" VXYZ FACE "end_header\n\n3 0 1 2\n",
     ":11:1: found a vertex index out of range, expected vertex indices in "
     "0..0"},
    {HA "element vertex 3\n" VXYZ FACE "end_header\n" BODY3 "  2 0 1\n",
     ":13:3: found a face of fewer than 3 vertices, expected at least 3 "
     "vertex indices"},
    {HA "element vertex 3\n" VXYZ FACE "end_header\n" BODY3 "3 0 1 -1\n",
     ":13:1: found a vertex index out of range, expected vertex indices in "
     "0..2"},
    {HA "element vertex 3\n" VXYZ FACE "end_header\n" BODY3 "200 0 1 2\n",
     ":13:1: found an impossible list count, expected a count the file "
     "holds"},
    {HA "element vertex 3\n" VXYZ "element face 1\nproperty list char int "
        "vertex_indices\nend_header\n" BODY3 "-1 0 1 2\n",
     ":13:1: found an impossible list count, expected a count the file "
     "holds"},
    {HA "element vertex 3\n" VXYZ FACE "end_header\n" BODY3 "3 0 1 2\n7\n",
     ":14:1: found 2 bytes more, expected the end of the file after the last "
     "element"},
    {HA "element vertex 1\n" VXYZ "end_header\n0 2e15 0\n",
     ":8:3: found a coordinate 2e+15, expected a coordinate within +-1e+15 "
     "(docs/config.md, Limits)"},
    {HA "element vertex 1\n" VXYZ "property float nx\nproperty float ny\n"
        "property float nz\nend_header\n0 0 0 0 0 -3e15\n",
     ":11:11: found a coordinate -3e+15, expected a coordinate within "
     "+-1e+15 (docs/config.md, Limits)"},
    {HA "element vertex 1\n" VXYZ "property uchar red\nproperty uchar green\n"
        "property uchar blue\nend_header\n0 0 0 255 256 0\n",
     ":11:11: found a colour 256, expected a colour in [0, 1] (float) or "
     "0..255 (integer)"},
    {HA "element vertex 1\n" VXYZ "property float red\nproperty float green\n"
        "property float blue\nend_header\n0 0 0 1 0 1.5\n",
     ":11:11: found a colour 1.5, expected a colour in [0, 1] (float) or "
     "0..255 (integer)"},
    {HA "element vertex 1\n" VXYZ "property short red\nproperty short green\n"
        "property short blue\nend_header\n0 0 0 -1 0 0\n",
     ":11:7: found a colour -1, expected a colour in [0, 1] (float) or "
     "0..255 (integer)"},
    {HA "element vertex 3\n" VXYZ FACE "property float red\nproperty float "
        "green\nproperty float blue\nend_header\n" BODY3 "3 0 1 2 0 2 0\n",
     ":16:11: found a colour 2, expected a colour in [0, 1] (float) or "
     "0..255 (integer)"},
    {HA "element vertex 1\n" VXYZ "end_header\n0 0\n",
     ":9:1: found end of file, expected a number"},
};

static void test_ply_errors(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(ply_bad); i++)
        ply_fails(ply_bad[i].text, strlen(ply_bad[i].text), ply_bad[i].message);
}

/* Binary bodies: errors by byte offset; the header's still by line. */
static void test_ply_binary_errors(void **st)
{
    (void)st;
    const char h[] = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                     "property uchar x\nproperty uchar y\nproperty uchar z\n"
                     "end_header\n";
    gsize hl = strlen(h);
    char buf[256];
    memcpy(buf, h, hl);
    memcpy(buf + hl, "\1\2\3\4\5", 5);
    char *want = g_strdup_printf(": byte offset %zu: found 2 bytes more, "
                                 "expected the end of the file after the "
                                 "last element",
                                 hl + 3);
    ply_fails(buf, hl + 5, want);
    g_free(want);
    SceneMesh *m = ply_ok(buf, hl + 3);
    Vec3 v = scene_mesh_vertex(m, 0);
    assert_true(v.x == 1 && v.y == 2 && v.z == 3);
    scene_mesh_free(m);
    want = g_strdup_printf(": byte offset %zu: found end of file, expected "
                           "1 more bytes (a uchar)",
                           hl + 2);
    ply_fails(buf, hl + 2, want);
    g_free(want);
    /* a list count may take every byte left: uchar indices 0 1 2 last */
    const char fh[] = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                      "property uchar x\nproperty uchar y\nproperty uchar z\n"
                      "element face 1\nproperty list uchar uchar "
                      "vertex_indices\nend_header\n";
    gsize fl = strlen(fh);
    memcpy(buf, fh, fl);
    memcpy(buf + fl, "\0\0\0\1\0\0\0\1\0\3\0\1\2", 13);
    m = ply_ok(buf, fl + 13);
    assert_int_equal(scene_mesh_n_polys(m), 1);
    assert_int_equal(scene_mesh_poly(m, 0)[2], 2);
    scene_mesh_free(m);
    buf[fl + 9] = 4; /* one more than the bytes left: read, then missed */
    want = g_strdup_printf(": byte offset %zu: found end of file, expected "
                           "1 more bytes (a uchar)",
                           fl + 13);
    ply_fails(buf, fl + 13, want);
    g_free(want);
    buf[fl + 9] = 5; /* two more: impossible */
    want = g_strdup_printf(": byte offset %zu: found an impossible list "
                           "count, expected a count the file holds",
                           fl + 9);
    ply_fails(buf, fl + 13, want);
    g_free(want);
    const char bad[] = "ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
                       "property uchar x\nproperty uchar y\nproperty\n";
    ply_fails(bad, strlen(bad), ":6:9: found end of line, expected a type "
              "(char uchar short ushort int uint float double or int8 ... "
              "float64)");
}

/* Every scalar type, both byte orders: signed and unsigned of each width
 * read from the same all-ones bit pattern differ. */
static void test_ply_scalar_types(void **st)
{
    (void)st;
    static const char *const names[] = {"char", "uchar", "int16", "ushort",
                                        "int", "uint32", "float", "float64"};
    static const double want[] = {-1, 255, -1, 65535, -1, 4294967295.0,
                                  -2, -2};
    static const guint size[] = {1, 1, 2, 2, 4, 4, 4, 8};
    for (int be = 0; be < 2; be++)
        for (int t = 0; t < 8; t++) {
            char *h = g_strdup_printf(
                "ply\nformat binary_%s_endian 1.0\nelement vertex 1\n"
                "property %s x\nproperty uchar y\nproperty uchar z\n"
                "element extra 1\nproperty %s w\nend_header\n",
                be ? "big" : "little", names[t], names[t]);
            GByteArray *b = g_byte_array_new();
            g_byte_array_append(b, (const guchar *)h, strlen(h));
            guchar x[8] = {0};
            if (t == 6) { /* float -2.0: 0xc0000000 */
                x[be ? 0 : 3] = 0xc0;
            } else if (t == 7) { /* double -2.0: 0xc000000000000000 */
                x[be ? 0 : 7] = 0xc0;
            } else {
                memset(x, 0xff, size[t]);
            }
            g_byte_array_append(b, x, size[t]);
            g_byte_array_append(b, (const guchar *)"\7\11", 2);
            g_byte_array_append(b, x, size[t]); /* the extra element */
            SceneMesh *m = ply_ok((const char *)b->data, b->len);
            Vec3 v = scene_mesh_vertex(m, 0);
            assert_true(v.x == want[t]);
            assert_true(v.y == 7 && v.z == 9);
            scene_mesh_free(m);
            g_byte_array_free(b, TRUE);
            g_free(h);
        }
}

/* Colours: integer types are scaled by 1/255, float ones kept; 0 and the
 * top of each range are accepted; normals and colours are read per
 * vertex and per face. */
static void test_ply_colours(void **st)
{
    (void)st;
    const char t[] = HA "element vertex 3\n" VXYZ
        "property float nx\nproperty float ny\nproperty float nz\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        "element face 1\nproperty float red\nproperty float green\n"
        "property float blue\nproperty list uint8 uint vertex_indices\n"
        "end_header\n"
        "0 0 0 0 0 1 255 0 51\n1e15 0 0 1 0 0 0 255 0\n0 -1e15 0 0 1 0 0 0 0\n"
        "1 0 0.5 3 2 1 0\n";
    SceneMesh *m = ply_ok(t, strlen(t));
    assert_int_equal(m->normals->len, 3);
    assert_int_equal(m->colors->len, 3);
    SceneColor c0 = g_array_index(m->colors, SceneColor, 0),
               c1 = g_array_index(m->colors, SceneColor, 1);
    assert_true(c0.r == 1.0f && c0.g == 0 && c0.b == 0.2f);
    assert_true(c1.r == 0 && c1.g == 1.0f);
    Vec3 n1 = g_array_index(m->normals, Vec3, 1),
         n2 = g_array_index(m->normals, Vec3, 2);
    assert_true(n1.x == 1 && n1.y == 0 && n2.y == 1);
    assert_true(scene_mesh_vertex(m, 1).x == 1e15);
    assert_true(scene_mesh_vertex(m, 2).y == -1e15);
    SceneColor f = g_array_index(m->poly_color, SceneColor, 0);
    assert_true(f.r == 1 && f.g == 0 && f.b == 0.5f);
    const uint32_t *v = scene_mesh_poly(m, 0);
    assert_true(v[0] == 2 && v[1] == 1 && v[2] == 0);
    /* written with vertex colours and read back, in every format */
    for (int fmt = SCENE_PLY_ASCII; fmt <= SCENE_PLY_BINARY_BE; fmt++) {
        gsize len;
        guchar *data = scene_ply_encode(m, fmt, &len);
        assert_non_null(g_strstr_len((char *)data, len,
                                     "property uchar red\nproperty uchar "
                                     "green\nproperty uchar blue\nelement "
                                     "face 1\n"));
        SceneMesh *r = ply_ok((char *)data, len);
        assert_int_equal(r->colors->len, 3);
        for (guint i = 0; i < 3; i++) {
            SceneColor a = g_array_index(m->colors, SceneColor, i),
                       b = g_array_index(r->colors, SceneColor, i);
            assert_true(a.r == b.r && a.g == b.g && a.b == b.b);
        }
        assert_int_equal(r->normals->len, 3);
        scene_mesh_free(r);
        g_free(data);
    }
    scene_mesh_free(m);
}

/* Roles by name, wherever they sit: each of x, y, z, nx, ny, nz, red,
 * green and blue in turn as the first property of the vertex. */
static void test_ply_property_order(void **st)
{
    (void)st;
    static const char *const role[] = {"x",  "y",  "z",     "nx",  "ny",
                                       "nz", "red", "green", "blue"};
    static const char *const value[] = {"1", "2", "3", "0", "1",
                                        "0", "51", "102", "255"};
    for (guint first = 0; first < 9; first++) {
        GString *t = g_string_new(HA "element vertex 3\n");
        for (guint k = 0; k < 9; k++)
            g_string_append_printf(t, "property %s %s\n",
                                   (first + k) % 9 >= 6 ? "uchar" : "float",
                                   role[(first + k) % 9]);
        g_string_append(t, FACE "end_header\n");
        for (guint v = 0; v < 3; v++) {
            for (guint k = 0; k < 9; k++)
                g_string_append_printf(t, "%s ", value[(first + k) % 9]);
            g_string_append(t, "\n");
        }
        g_string_append(t, "3 0 1 2\n");
        SceneMesh *m = ply_ok(t->str, t->len);
        Vec3 p = scene_mesh_vertex(m, 2);
        assert_true(p.x == 1 && p.y == 2 && p.z == 3);
        Vec3 n = g_array_index(m->normals, Vec3, 1);
        assert_true(n.x == 0 && n.y == 1 && n.z == 0);
        SceneColor c = g_array_index(m->colors, SceneColor, 0);
        assert_true(c.r == 0.2f && c.g == 0.4f && c.b == 1);
        scene_mesh_free(m);
        g_string_free(t, TRUE);
    }
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_obj_errors),
        cmocka_unit_test(test_obj_limits),
        cmocka_unit_test(test_obj_indices),
        cmocka_unit_test(test_obj_tags),
        cmocka_unit_test(test_obj_normals),
        cmocka_unit_test(test_obj_colours_and_save),
        cmocka_unit_test(test_ply_errors),
        cmocka_unit_test(test_ply_binary_errors),
        cmocka_unit_test(test_ply_scalar_types),
        cmocka_unit_test(test_ply_colours),
        cmocka_unit_test(test_ply_property_order),
    };
    return cmocka_run_group_tests_name("mesh_errors", tests, NULL, NULL);
}
