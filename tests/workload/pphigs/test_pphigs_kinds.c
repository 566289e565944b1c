/* test_pphigs_kinds.c — every PPHIGS primitive type (issue 37 point 6):
 * lines and spheres besides polygons, strips and ODPs, each type with
 * its own colour attribute (configs/pphigs/kinds.yaml).  Through the
 * runner the frame equals the serial painter's at 1, 3, 4 and 16 GPs
 * with every algorithm, §3.5's attribute_send both ways and §2.1's
 * inheritance both ways (with insert and delete edits and rebalancing
 * by primitive); sending colours only with their own type (by_kind)
 * sends fewer attributes than with every primitive (all).  A sphere is
 * a shaded disc of about pi r^2 pixels drawn by 5 quadratic
 * expressions; a line a one-pixel-wide run of 4 edge + z + 3 colour
 * linear expressions; the GP prices both by their own costs.  Run from
 * the repository root (make test does). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/run/run.h"
#include "tests/workload/pphigs/pphigs_rig.h"
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/workload/pphigs/pphigs_pixels.h"

#define KINDS "workload.database=configs/pphigs/kinds.yaml"

/* One run of the flock config on kinds.yaml with `extra` settings: the
 * metric `name`, after checking the image. */
static double run_kinds(const char *const *extra, const char *name)
{
    const char *sets[16] = {KINDS, "run.frames=2", "run.fidelity=analytic",
                            "workload.edits_per_frame=0"};
    guint n = 4;
    for (guint i = 0; extra[i]; i++)
        sets[n++] = extra[i];
    sets[n] = NULL;
    CfgRun *run = NULL;
    SimResult *r = pphigs_rig_run_flock(sets, &run);
    double img = 0, v = 0;
    assert_true(sim_result_get_metric(r, "image_matches_serial", &img));
    assert_true(img == 1);
    assert_true(sim_result_get_metric(r, name, &v));
    sim_result_free(r);
    cfg_run_free(run);
    return v;
}

static void test_images_equal_serial(void **st)
{
    (void)st;
    static const char *const gps[] = {"workload.gps=1", "workload.gps=3",
                                      "workload.gps=4", "workload.gps=16"};
    static const char *const edits = "workload.edits={insert: 3, delete: 3}";
    for (int g = 0; g < 4; g++) {
        const char *simple[] = {gps[g], "workload.algorithm=simple", edits,
                                NULL};
        const char *all[] = {gps[g], "workload.algorithm=complex", edits,
                             "workload.attribute_send=all", NULL};
        const char *kind[] = {gps[g], "workload.algorithm=complex", edits,
                              "workload.attribute_send=by_kind", NULL};
        const char *skel[] = {gps[g], "workload.algorithm=by_structure",
                              "workload.rebalance.enabled=false",
                              "workload.inheritance=skeleton", NULL};
        const char *pre[] = {gps[g], "workload.algorithm=by_structure",
                             "workload.rebalance.enabled=false",
                             "workload.inheritance=precompute", NULL};
        const char *const *cases[] = {simple, all, kind, skel, pre};
        for (int c = 0; c < 5; c++)
            assert_true(run_kinds(cases[c], "commands_per_frame") > 0);
    }
}

static void test_by_kind_sends_less(void **st)
{
    (void)st;
    const char *all[] = {"workload.gps=16", "workload.algorithm=complex",
                         "workload.attribute_send=all", NULL};
    const char *kind[] = {"workload.gps=16", "workload.algorithm=complex",
                          "workload.attribute_send=by_kind", NULL};
    double a = run_kinds(all, "distribution_attributes");
    double k = run_kinds(kind, "distribution_attributes");
    assert_true(k < a);
    double ea = run_kinds(all, "distribution_elements");
    double ek = run_kinds(kind, "distribution_elements");
    assert_true(ea - ek == a - k); /* the primitives are the same */
}

/* The commands of one primitive seen head-on by an orthographic-like
 * view (identity: NDC = world) on a 200 x 200 screen. */
static GArray *cmds_of(SceneElemKind kind, const Vec3 *v, guint n, Vec3 col)
{
    SceneElem e = scene_elem_prim(kind, v, n);
    ScenePrimInst pi = {0, 0, &e, mat4_identity(), col, 0, 1, 0};
    GArray *out = g_array_new(FALSE, FALSE, sizeof(WlPphigsCmd));
    wl_pphigs_cmds(&pi, mat4_identity(), 200, 200, out);
    return out;
}

static void test_sphere_and_line_pixels(void **st)
{
    (void)st;
    /* a sphere of radius 0.25 at the centre: a disc of 25 pixels radius */
    Vec3 s[2] = {vec3(0, 0, 0), vec3(0.25, 0, 0)};
    GArray *c = cmds_of(SCENE_EL_SPHERE, s, 2, vec3(1, 0, 0));
    assert_int_equal(c->len, 1);
    const WlPphigsCmd *sc = &g_array_index(c, WlPphigsCmd, 0);
    assert_int_equal(wl_pphigs_cmd_quads(sc), 5);
    assert_int_equal(wl_pphigs_cmd_exprs(sc), 0);
    WlPphigsRegion *r = wl_pphigs_region_new(0, 0, 200, 200, 0xff000000u);
    uint64_t won = wl_pphigs_region_draw(r, sc);
    assert_true(fabs((double)won - G_PI * 25 * 25) < 0.05 * G_PI * 25 * 25);
    /* shaded: the centre is brighter than a pixel near the rim */
    uint32_t mid = r->rgba[100 * 200 + 100], rim = r->rgba[100 * 200 + 123];
    assert_true((mid & 0xff) > (rim & 0xff) && (rim & 0xff) > 0);
    wl_pphigs_region_free(r);
    g_array_unref(c);
    /* a horizontal line across half the screen: one pixel high */
    Vec3 l[2] = {vec3(-0.5, 0.005, 0), vec3(0.5, 0.005, 0)};
    c = cmds_of(SCENE_EL_LINE, l, 2, vec3(0, 1, 0));
    assert_int_equal(c->len, 1);
    const WlPphigsCmd *lc = &g_array_index(c, WlPphigsCmd, 0);
    assert_int_equal(wl_pphigs_cmd_exprs(lc), 4 + 1 + 3);
    assert_int_equal(wl_pphigs_cmd_quads(lc), 0);
    r = wl_pphigs_region_new(0, 0, 200, 200, 0xff000000u);
    won = wl_pphigs_region_draw(r, lc);
    assert_true(won >= 99 && won <= 101);
    wl_pphigs_region_free(r);
    g_array_unref(c);
}

static void test_gp_costs(void **st)
{
    (void)st;
    const WlPphigsCosts c = {.poly = 5 * SIM_US, .vertex = SIM_US,
                             .color = 2 * SIM_US, .line = 3 * SIM_US,
                             .sphere = 7 * SIM_US};
    Vec3 v[2] = {vec3(0, 0, 0), vec3(1, 0, 0)};
    SceneElem l = scene_elem_prim(SCENE_EL_LINE, v, 2);
    SceneElem s = scene_elem_prim(SCENE_EL_SPHERE, v, 2);
    assert_true(wl_pphigs_elem_cost(&c, &l) == 5 * SIM_US);
    assert_true(wl_pphigs_elem_cost(&c, &s) == 9 * SIM_US);
    SceneElem lc = scene_elem_kind_color(SCENE_EL_LINE_COLOR, vec3(1, 1, 1));
    assert_true(wl_pphigs_elem_cost(&c, &lc) == 2 * SIM_US);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_images_equal_serial),
        cmocka_unit_test(test_by_kind_sends_less),
        cmocka_unit_test(test_sphere_and_line_pixels),
        cmocka_unit_test(test_gp_costs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
