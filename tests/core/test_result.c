/* test_result.c — the run result (sim/core/result.c) field by field:
 * metrics are found by name, replaced in place (value and unit), a
 * missing one reads NaN; idle counts add up by kind; utilisation is busy
 * over elapsed (0 before any time passed); phases are copied from the
 * engine in id order; nodes keep their name, kind and busy time. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/core/engine.h"
#include "sim/core/result.h"
#include "tests/support.h"

static void test_metrics(void **state)
{
    (void)state;
    SimResult *r = sim_result_new("wl", "mach");
    assert_string_equal(r->workload, "wl");
    assert_string_equal(r->machine, "mach");
    assert_string_equal(r->fidelity, "analytic");
    assert_true(isnan(sim_result_metric(r, "x")));
    double v = 7;
    assert_false(sim_result_get_metric(r, "x", &v));
    assert_true(v == 7);
    sim_result_set_metric(r, "x", 1.5, "s");
    sim_result_set_metric(r, "y", -2, NULL);
    sim_result_set_metric(r, "x", 2.5, "ms");
    assert_int_equal(r->metrics->len, 2);
    SimMetric *m0 = g_ptr_array_index(r->metrics, 0);
    SimMetric *m1 = g_ptr_array_index(r->metrics, 1);
    assert_string_equal(m0->name, "x");
    assert_string_equal(m0->unit, "ms");
    assert_true(m0->value == 2.5);
    assert_string_equal(m1->name, "y");
    assert_string_equal(m1->unit, "");
    assert_true(sim_result_metric(r, "y") == -2);
    assert_true(sim_result_get_metric(r, "x", NULL));
    assert_true(sim_result_get_metric(r, "x", &v));
    assert_true(v == 2.5);
    sim_result_free(r);
    sim_result_free(NULL);
}

static void test_nodes_util_idle(void **state)
{
    (void)state;
    SimResult *r = sim_result_new("wl", "mach");
    SimNodeResult *a = sim_result_add_node(r, "gp0", "gp");
    SimNodeResult *b = sim_result_add_node(r, "rn0", "rn");
    assert_int_equal(r->nodes->len, 2);
    assert_ptr_equal(g_ptr_array_index(r->nodes, 1), b);
    assert_string_equal(a->name, "gp0");
    assert_string_equal(a->kind, "gp");
    assert_true(sim_busy_add(&a->busy, 1, 250));
    assert_true(sim_result_node_util(r, a) == 0.0); /* no time yet */
    r->elapsed = 1000;
    assert_true(sim_result_node_util(r, a) == 0.25);
    assert_true(sim_result_node_util(r, b) == 0.0);
    r->elapsed = 1;
    assert_true(sim_result_node_util(r, a) == 250.0);
    sim_result_add_idle(r, "rn", 0);
    sim_result_add_idle(r, "gp", 1);
    assert_int_equal(r->idle->len, 2);
    assert_int_equal(sim_result_n_idle(r), 1);
    SimIdleResult *i0 = g_ptr_array_index(r->idle, 0);
    assert_string_equal(i0->kind, "rn");
    assert_int_equal(i0->count, 0);
    sim_result_add_frame(r, 1);
    assert_true(sim_result_mean_frame_s(r) == 1e-12);
    sim_result_add_frame(r, 2);
    sim_result_add_frame(r, 6);
    assert_true(fabs(sim_result_mean_frame_s(r) - 3e-12) < 1e-27);
    sim_result_free(r);
}

static void test_phases(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    unsigned a = sim_engine_phase(eng, "geometry");
    unsigned b = sim_engine_phase(eng, "raster");
    SimResult *r = sim_result_new("wl", "mach");
    sim_result_set_phases(r, eng);
    assert_int_equal(r->phases->len, sim_engine_phase_count(eng));
    assert_string_equal(g_ptr_array_index(r->phases, a), "geometry");
    assert_string_equal(g_ptr_array_index(r->phases, b), "raster");
    sim_result_set_phases(r, eng); /* again: replaced, not appended */
    assert_int_equal(r->phases->len, sim_engine_phase_count(eng));
    sim_result_free(r);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_metrics),
        cmocka_unit_test(test_nodes_util_idle),
        cmocka_unit_test(test_phases),
    };
    return cmocka_run_group_tests_name("result", tests, NULL, NULL);
}
