/* test_sf_trav.c — §3.5 traversal priced (sf_trav.h, sf_frame.h): on a
 * small vehicle (40 structures, 4 processors, 26-primitive chunks so
 * some structures are locally empty), each `traversal` mode's time is
 * exactly its count of structure instances scanned at node_visit plus
 * its volume tests at 8 vertex transforms (costs read from the model,
 * not restated); empty flags and culling shorten the frame against the
 * plain traversal under both bookkeeping methods, images still equal
 * to the serial render; pull refuses any traversal but plain. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "tests/workload/sortfirst/sf_testutil.h"

static const char *small =
    "machine: {model: cluster-ib}\n"
    "workload: {type: sortfirst, processors: 4, granularity: 26,\n"
    "           resolution: 64, bookkeeping: maxset}\n"
    "scene: {generator: vehicle, structures: 40, triangles: 3000,\n"
    "        instances: 3, circle_radius: 6, camera_radius: 15,\n"
    "        camera_height: 5, fov: 30, degrees_per_frame: 12}\n";

static const char *const counts[] = {
    "traversal_nodes_per_frame", "traversal_nodes_flags",
    "traversal_nodes_culled", "traversal_nodes_flags_culled"};

static SimResult *run(const char *bk, const char *mode)
{
    return sf_test_run_checked(small, 6, "workload.bookkeeping", bk,
                               "workload.traversal", mode);
}

static void costs(WlSfCosts *c)
{
    GError *e = NULL;
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_model(eng, "cluster-ib", "analytic", &e);
    assert_non_null(m);
    assert_true(wl_sf_costs_from_machine(m, c, &e));
    assert_true(c->node_visit > 0);
    mach_free(m);
    sim_engine_free(eng);
}

/* traversal_ms x P = nodes x node_visit + tests x 8 x transform_vertex. */
static void test_priced(void **state)
{
    (void)state;
    WlSfCosts c;
    costs(&c);
    for (int bk = 0; bk <= 1; bk++)
        for (int mode = 0; mode < 4; mode++) {
            SimResult *r = run(wl_sf_bookkeeping_names[bk],
                               wl_sf_trav_names[mode]);
            double nodes = sf_test_metric(r, counts[mode]);
            double tests = sf_test_metric(r, "volume_tests_per_frame");
            double want = (nodes * (double)c.node_visit +
                           tests * 8.0 * (double)c.transform_vertex) /
                          (4 * 1e9);
            double got = sf_test_metric(r, "traversal_ms");
            assert_true(fabs(got - want) <= 1e-9 * want);
            assert_true((mode >= 2) == (tests > 0));
            sim_result_free(r);
        }
}

/* §3.5's saving shows in the frame time: every mode beats plain. */
static void test_saving_in_frame_time(void **state)
{
    (void)state;
    for (int bk = 0; bk <= 1; bk++) {
        SimResult *plain = run(wl_sf_bookkeeping_names[bk], "plain");
        double base = sf_test_metric(plain, "frame_ms");
        assert_true(sf_test_metric(plain, "traversal_ms") > 0);
        for (int mode = 1; mode < 4; mode++) {
            SimResult *r = run(wl_sf_bookkeeping_names[bk],
                               wl_sf_trav_names[mode]);
            if (!(sf_test_metric(r, "frame_ms") < base))
                fail_msg("%s %s: frame %g not below plain %g",
                         wl_sf_bookkeeping_names[bk], wl_sf_trav_names[mode],
                         sf_test_metric(r, "frame_ms"), base);
            sim_result_free(r);
        }
        sim_result_free(plain);
    }
}

static void test_pull_plain_only(void **state)
{
    (void)state;
    GError *e = NULL;
    const char *const o[] = {"workload.bookkeeping=minset",
                             "workload.migration=pull",
                             "workload.traversal=flags", NULL};
    assert_null(sf_test_run(small, o, 1, NULL, FALSE, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "traversal: plain"));
    g_clear_error(&e);
    const char *const bad[] = {"workload.traversal=lazy", NULL};
    assert_null(sf_test_run(small, bad, 1, NULL, FALSE, &e));
    assert_non_null(strstr(e->message, "flags_culled"));
    g_clear_error(&e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_priced),
        cmocka_unit_test(test_saving_in_frame_time),
        cmocka_unit_test(test_pull_plain_only),
    };
    return cmocka_run_group_tests_name("sf_trav", tests, NULL, NULL);
}
