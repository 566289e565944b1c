/* test_teapot.c — Newell's teapot: embedded data, tessellation rule,
 * exact polygon counts, welding and orientation.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>

#include "sim/scene/teapot.h"
#include "tests/scene/mesh_check.h"

/* The embedded table equals data/teapot.txt (tests run from the root). */
static void test_data_matches_file(void **st)
{
    (void)st;
    FILE *f = fopen("data/teapot.txt", "r");
    assert_non_null(f);
    char line[256];
    int mode = 0, row = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        if (!strncmp(line, "patches", 7) || !strncmp(line, "points", 6)) {
            mode++;
            row = 0;
            continue;
        }
        if (mode == 1) {
            int v[16];
            assert_int_equal(sscanf(line,
                                    "%d %d %d %d %d %d %d %d %d %d %d %d %d "
                                    "%d %d %d",
                                    &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                                    &v[6], &v[7], &v[8], &v[9], &v[10], &v[11],
                                    &v[12], &v[13], &v[14], &v[15]),
                             16);
            for (int k = 0; k < 16; k++)
                assert_int_equal(v[k], scene_teapot_patches[row][k]);
        } else {
            double p[3];
            assert_int_equal(sscanf(line, "%lf %lf %lf", &p[0], &p[1], &p[2]),
                             3);
            for (int k = 0; k < 3; k++)
                assert_true(p[k] == scene_teapot_points[row][k]);
        }
        row++;
    }
    fclose(f);
    assert_int_equal(mode, 2);
    assert_int_equal(row, SCENE_TEAPOT_POINTS);
}

static void test_rule(void **st)
{
    (void)st;
    SceneTeapotTess t;
    assert_true(scene_teapot_tess_for(3751, "x", &t, NULL));
    assert_int_equal(t.n, 10);
    assert_int_equal(t.split, 551);
    assert_true(scene_teapot_tess_for(3200, "x", &t, NULL));
    assert_int_equal(t.n, 10);
    assert_int_equal(t.split, 0);
    assert_true(scene_teapot_tess_for(3871, "x", &t, NULL));
    assert_int_equal(t.n, 10);
    assert_true(scene_teapot_tess_for(3872, "x", &t, NULL));
    assert_int_equal(t.n, 11);
    GError *err = NULL;
    assert_false(scene_teapot_tess_for(287, "pots.yaml:3:5", &t, &err));
    assert_non_null(strstr(err->message, "pots.yaml:3:5: found 287"));
    g_error_free(err);
}

static void test_3751(void **st)
{
    (void)st;
    SceneTeapotTess t;
    assert_true(scene_teapot_tess_for(3751, "x", &t, NULL));
    SceneMesh *m = scene_teapot_mesh(t, scene_color(1, 0, 0));
    assert_int_equal(scene_mesh_n_polys(m), 3751);
    assert_int_equal(scene_mesh_count_ngons(m, 4), 2569);
    assert_int_equal(scene_mesh_count_ngons(m, 3), 1182);
    assert_true(scene_mesh_validate(m, "teapot", NULL));
    assert_int_equal(m->normals->len, scene_mesh_n_vertices(m));
    /* Open only at the pot's mouth, the lid's rim, the two ends of the
     * handle and of the spout: 4 boundaries of 4 patch edges each. */
    assert_int_equal(mesh_check_open_edges(m), 16 * t.n);
    assert_true(mesh_check_volume(m) > 20); /* outward winding */
    SceneBox b = scene_mesh_bbox(m);
    assert_true(fabs(b.min.x + 3.0) < 1e-6 && fabs(b.max.y - 3.15) < 1e-6);
    assert_true(fabs(b.min.y) < 1e-6 && b.max.x > 3.4 && b.max.x < 3.525);
    scene_mesh_free(m);
}

static void test_counts_exact(void **st)
{
    (void)st;
    const uint64_t counts[] = {288, 511, 1000, 3751, 5000, 12345};
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
        SceneTeapotTess t;
        assert_true(scene_teapot_tess_for(counts[i], "x", &t, NULL));
        SceneMesh *m = scene_teapot_mesh(t, scene_color(1, 1, 1));
        assert_int_equal(scene_mesh_n_polys(m), counts[i]);
        assert_int_equal(scene_mesh_count_ngons(m, 3) - 8 * t.n, 2 * t.split);
        assert_int_equal(mesh_check_open_edges(m), 16 * t.n);
        scene_mesh_free(m);
    }
}

static void test_eval(void **st)
{
    (void)st;
    /* Patch 0 corner (u, v) = (0, 0) is control point 1 = (1.4, 0, 2.4),
     * y-up: (1.4, 2.4, -0). */
    Vec3 p = scene_teapot_eval(0, 0, 0);
    assert_true(fabs(p.x - 1.4) < 1e-7 && fabs(p.y - 2.4) < 1e-7);
    /* The bottom pole. */
    p = scene_teapot_eval(28, 0, 0.37);
    assert_true(vec3_len(p) == 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_data_matches_file),
        cmocka_unit_test(test_rule),
        cmocka_unit_test(test_3751),
        cmocka_unit_test(test_counts_exact),
        cmocka_unit_test(test_eval),
    };
    return cmocka_run_group_tests_name("teapot", tests, NULL, NULL);
}
