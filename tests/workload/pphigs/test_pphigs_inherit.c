/* test_pphigs_inherit.c — distribute-by-structure's two ways of giving
 * a GP its pieces' inherited attributes (seed 001 §2.1,
 * pphigs_bystruct.c), through the runner on the flock (a root of 144
 * boid instances, each after its own matrix) and the human figures
 * (deep, broken-up structures): both draw the serial painter's image;
 * the ancestor skeleton sends every GP the root's matrices before its
 * instances and each GP traverses them again ("duplication of
 * computation"), so it sends more attribute elements and its
 * distribution efficiency is lower than the host's pre-computed state,
 * which sends a GP one matrix per instance it holds.  The option is
 * refused with another algorithm.  Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/run/run.h"
#include "tests/workload/pphigs/pphigs_rig.h"

typedef struct {
    double attrs, elems, bytes, eff, img;
} Inh;

static Inh run_inherit(const char *db, const char *inherit, const char *gps)
{
    char *d = g_strdup_printf("workload.database=%s", db);
    char *i = g_strdup_printf("workload.inheritance=%s", inherit);
    char *g = g_strdup_printf("workload.gps=%s", gps);
    const char *sets[] = {d, i, g, "workload.algorithm=by_structure",
                          "run.frames=1", "run.fidelity=analytic",
                          "workload.edits_per_frame=0",
                          "workload.rebalance.enabled=false", NULL};
    CfgRun *run = NULL;
    SimResult *r = pphigs_rig_run_flock(sets, &run);
    Inh out;
    assert_true(sim_result_get_metric(r, "distribution_attributes",
                                      &out.attrs));
    assert_true(sim_result_get_metric(r, "distribution_elements",
                                      &out.elems));
    assert_true(sim_result_get_metric(r, "distribution_bytes", &out.bytes));
    assert_true(sim_result_get_metric(r, "distribution_efficiency_pct",
                                      &out.eff));
    assert_true(sim_result_get_metric(r, "image_matches_serial", &out.img));
    sim_result_free(r);
    cfg_run_free(run);
    g_free(d);
    g_free(i);
    g_free(g);
    return out;
}

static void test_direction(void **st)
{
    (void)st;
    static const char *const dbs[] = {"flock_old_well", "two_human_figures"};
    for (int k = 0; k < 2; k++) {
        Inh s = run_inherit(dbs[k], "skeleton", "16");
        Inh p = run_inherit(dbs[k], "precompute", "16");
        assert_true(s.img == 1 && p.img == 1); /* the same image */
        assert_true(s.attrs > p.attrs);
        assert_true(s.eff < p.eff);
        assert_true(s.bytes == s.elems * 80 && p.bytes == p.elems * 80);
    }
    /* one GP: the skeleton is the host's list, nothing to pre-compute
     * beyond it */
    Inh s1 = run_inherit("flock_old_well", "skeleton", "1");
    assert_true(s1.img == 1);
}

static void test_refused_by_primitive(void **st)
{
    (void)st;
    const char *sets[] = {"workload.inheritance=precompute",
                          "workload.algorithm=complex", NULL};
    GError *err = NULL;
    CfgRun *run = cfg_run_load("configs/pphigs-flock.yaml", sets, &err);
    assert_null(run);
    assert_non_null(strstr(err->message, "inheritance without algorithm "
                                         "by_structure"));
    g_clear_error(&err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_direction),
        cmocka_unit_test(test_refused_by_primitive),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
