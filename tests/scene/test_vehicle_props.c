/* test_vehicle_props.c — invariants of the vehicle scene
 * (sim/scene/vehicle.c) that hold whatever its parts: one mesh drawn
 * `instances` times, each instance white (the database carries the
 * colours) and tagged with its copy number, the triangle count exact,
 * the camera on its orbit.  Found unchecked by make mutate
 * (docs/testing.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/scene/vehicle.h"

static void test_instances(void **st)
{
    (void)st;
    SceneVehicleParams p = scene_vehicle_defaults();
    p.structures = 20;
    p.triangles = 600;
    p.instances = 4;
    GError *err = NULL;
    Scene *s = scene_vehicle_new(&p, "t", &err);
    assert_non_null(s);
    assert_int_equal(scene_n_instances(s), 4);
    for (guint k = 0; k < 4; k++) {
        const SceneInstance *in = scene_instance(s, k);
        assert_true(in->color.r == 1 && in->color.g == 1 && in->color.b == 1);
        assert_int_equal(in->tag, k);
        assert_int_equal(in->mesh, scene_instance(s, 0)->mesh);
    }
    assert_int_equal(scene_n_triangles(s), 4 * 600);
    assert_non_null(s->path);
    assert_int_equal(scene_path_n_frames(s->path), p.frames);
    SceneCamera c0 = scene_camera_at(s, 0);
    double r = hypot(c0.eye.x - c0.target.x, c0.eye.z - c0.target.z);
    assert_true(fabs(r - p.camera_radius) < 1e-9);
    scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_instances),
    };
    return cmocka_run_group_tests_name("vehicle_props", tests, NULL, NULL);
}
