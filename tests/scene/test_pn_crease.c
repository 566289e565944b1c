/* test_pn_crease.c — curved sharp edges for PN triangles (pn_crease.h,
 * pn_triangles.h; Vlachos et al. 2001, "two normals per vertex"): a
 * rounded cube whose 6 faces carry their own vertices and normals (3
 * normals at each corner, 2 along each edge) stays watertight when
 * tessellated at levels 1..4 — every edge of the refined mesh is shared
 * by exactly two triangles with bit-identical end positions — while the
 * same mesh with the crease treatment switched off (each side curving
 * the edge by its own normals) opens cracks; the creases are curved, not
 * straightened, and keep two normals (sharp shading); a mesh without
 * creases tessellates to the same bits either way.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/scene/pn_crease.h"
#include "tests/scene/pn_cube.h"

static const ScenePnNormals kinds[] = {SCENE_PN_LINEAR, SCENE_PN_QUADRATIC};

/* A cube of 6 faces, each with its own 4 vertices split into 2
 * triangles (or a 2 x 2 grid of quads, 8 triangles, when `grid`); the
 * normal at a face vertex leans from the face normal towards the radial
 * direction (`lean`), so each face bulges and each corner has 3
 * normals.  lean = 0 gives the flat cube. */
static SceneMesh *creased_cube(double lean, gboolean grid)
{
    SceneMesh *m = scene_mesh_new();
    SceneColor white = scene_color(1, 1, 1);
    for (int f = 0; f < 6; f++) {
        Vec3 c[4];
        for (int i = 0; i < 4; i++)
            c[i] = pn_cube_corner(pn_cube_quads[f][i]);
        Vec3 face = vec3_norm(
            vec3_cross(vec3_sub(c[1], c[0]), vec3_sub(c[3], c[0])));
        guint n = grid ? 2 : 1, base = scene_mesh_n_vertices(m);
        for (guint j = 0; j <= n; j++)
            for (guint i = 0; i <= n; i++) {
                double s = (double)i / n, t = (double)j / n;
                Vec3 a = vec3_add(vec3_scale(c[0], 1 - s), vec3_scale(c[1], s));
                Vec3 b = vec3_add(vec3_scale(c[3], 1 - s), vec3_scale(c[2], s));
                Vec3 p = vec3_add(vec3_scale(a, 1 - t), vec3_scale(b, t));
                Vec3 nrm =
                    vec3_norm(vec3_add(face, vec3_scale(vec3_norm(p), lean)));
                scene_mesh_add_vertex(m, p);
                g_array_append_val(m->normals, nrm);
            }
        for (guint j = 0; j < n; j++)
            for (guint i = 0; i < n; i++) {
                uint32_t v = base + j * (n + 1) + i;
                scene_mesh_add_tri(m, v, v + 1, v + n + 2, white, 0);
                scene_mesh_add_tri(m, v, v + n + 2, v + n + 1, white, 0);
            }
    }
    return m;
}

/* Edges of m (by their end positions, bitwise) used by other than
 * exactly two triangles. */
static guint open_edges(const SceneMesh *m)
{
    GHashTable *h = g_hash_table_new_full(g_bytes_hash, g_bytes_equal,
                                          (GDestroyNotify)g_bytes_unref, NULL);
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *ix = scene_mesh_poly(m, i);
        for (guint e = 0; e < 3; e++) {
            Vec3 ends[2] = {scene_mesh_vertex(m, ix[e]),
                            scene_mesh_vertex(m, ix[(e + 1) % 3])};
            if (scene_pn_vec_after(ends[0], ends[1])) {
                Vec3 t = ends[0];
                ends[0] = ends[1], ends[1] = t;
            }
            GBytes *k = g_bytes_new(ends, sizeof ends);
            guint n = GPOINTER_TO_UINT(g_hash_table_lookup(h, k));
            g_hash_table_replace(h, k, GUINT_TO_POINTER(n + 1));
        }
    }
    guint bad = 0;
    GHashTableIter it;
    gpointer k, v;
    g_hash_table_iter_init(&it, h);
    while (g_hash_table_iter_next(&it, &k, &v))
        bad += GPOINTER_TO_UINT(v) != 2;
    g_hash_table_destroy(h);
    return bad;
}

static guint open_after(const SceneMesh *in, guint L, ScenePnNormals kind,
                        gboolean ignore)
{
    ScenePnParams p = {L, kind, ignore};
    SceneMesh *out = scene_pn_tessellate(in, &p);
    assert_int_equal(scene_mesh_n_triangles(out),
                     scene_mesh_n_triangles(in) * (L + 1) * (L + 1));
    guint n = open_edges(out);
    scene_mesh_free(out);
    return n;
}

static void test_creased_cube_watertight(void **st)
{
    (void)st;
    for (int g = 0; g < 2; g++) {
        SceneMesh *cube = creased_cube(0.6, g);
        assert_int_equal(open_edges(cube), 0);
        for (guint L = 1; L <= 4; L++)
            for (int k = 0; k < 2; k++) {
                if (open_after(cube, L, kinds[k], FALSE))
                    fail_msg("grid %d level %u normals %d: cracks", g, L, k);
                /* each side's own normals: the seams open */
                assert_true(open_after(cube, L, kinds[k], TRUE) > 0);
            }
        scene_mesh_free(cube);
    }
}

/* The crease between two faces is curved (its midpoint leaves the
 * straight cube edge) and carries each face's own normal there. */
static void test_crease_curved_and_sharp(void **st)
{
    (void)st;
    SceneMesh *cube = creased_cube(0.6, FALSE);
    ScenePnParams p = {1, SCENE_PN_QUADRATIC, FALSE};
    SceneMesh *out = scene_pn_tessellate(cube, &p);
    /* the points at the middle of the edge x in [-1, 1], y = z = -1 */
    Vec3 mid = {0, -1, -1}, first = {0, 0, 0}, nfirst = {0, 0, 0};
    double best = INFINITY;
    guint found = 0;
    for (guint i = 0; i < scene_mesh_n_vertices(out); i++) {
        Vec3 v = scene_mesh_vertex(out, i);
        double d = vec3_len(vec3_sub(v, mid));
        if (d < 0.5 && fabs(v.x) < 1e-9) {
            Vec3 n = g_array_index(out->normals, Vec3, i);
            if (!found++)
                first = v, nfirst = n;
            else if (memcmp(&v, &first, sizeof v) == 0)
                assert_true(vec3_len(vec3_sub(n, nfirst)) > 0.1);
            best = fmin(best, d);
        }
    }
    assert_true(found >= 2); /* both faces' copies of the point */
    assert_true(best > 1e-3); /* bulged off the straight edge */
    scene_mesh_free(out);
    scene_mesh_free(cube);
}

/* The flat cube (face normals) is watertight either way; a mesh with
 * shared vertices has no crease and tessellates to the same bits. */
static void test_no_crease_unchanged(void **st)
{
    (void)st;
    SceneMesh *flat = creased_cube(0, TRUE);
    assert_int_equal(open_after(flat, 3, SCENE_PN_QUADRATIC, TRUE), 0);
    scene_mesh_free(flat);
    SceneMesh *m = pn_cube_smooth();
    GArray *cr = scene_pn_find_creases(m);
    assert_int_equal(cr->len, 12);
    for (guint i = 0; i < cr->len; i++)
        for (int e = 0; e < 3; e++)
            assert_false(g_array_index(cr, ScenePnCreases, i).crease[e]);
    g_array_free(cr, TRUE);
    ScenePnParams a = {3, SCENE_PN_QUADRATIC, FALSE}, b = a;
    b.ignore_creases = TRUE;
    SceneMesh *ta = scene_pn_tessellate(m, &a), *tb = scene_pn_tessellate(m, &b);
    assert_int_equal(scene_mesh_n_vertices(ta), scene_mesh_n_vertices(tb));
    assert_memory_equal(ta->pos->data, tb->pos->data,
                        scene_mesh_n_vertices(ta) * sizeof(Vec3));
    scene_mesh_free(ta);
    scene_mesh_free(tb);
    scene_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_creased_cube_watertight),
        cmocka_unit_test(test_crease_curved_and_sharp),
        cmocka_unit_test(test_no_crease_unchanged),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
