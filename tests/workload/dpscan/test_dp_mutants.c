/* test_dp_mutants.c — claims of the data-parallel scan workload that
 * mutation testing (make mutate, docs/testing.md) found unchecked:
 * "#rrggbb" palette colours read channel by channel, and a NEWS move's
 * time is its coefficients times the machine's unit costs (dp_cost.h:
 * "tests can check sums"). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/workload/dpscan/dp_color.h"
#include "sim/workload/dpscan/dp_cost.h"

static void test_hex_palette(void **state)
{
    (void)state;
    GString *y = g_string_new("[");
    for (int i = 0; i < WL_DP_COLORS; i++)
        g_string_append_printf(y, "%s\"#%02x8040\"", i ? ", " : "", i * 16);
    g_string_append(y, "]\n");
    GError *err = NULL;
    CfgNode *seq = cfg_load_string(y->str, "p.yaml", &err);
    assert_non_null(seq);
    float pal[WL_DP_COLORS][3];
    assert_true(wl_dp_palette_from_cfg(seq, pal, &err));
    for (int i = 0; i < WL_DP_COLORS; i++) {
        assert_true(fabsf(pal[i][0] - i * 16 / 255.0f) < 1e-6);
        assert_true(fabsf(pal[i][1] - 0x80 / 255.0f) < 1e-6);
        assert_true(fabsf(pal[i][2] - 0x40 / 255.0f) < 1e-6);
    }
    cfg_free(seq);
    g_string_free(y, TRUE);
}

static void test_news_cost_sum(void **state)
{
    (void)state;
    WlDpMachine m = {0};
    m.arch = WL_DP_SIMD;
    m.procs = 1024;
    m.step = 3 * SIM_US;
    m.news_slice = 5 * SIM_US;
    for (uint64_t n = 1; n <= 5000; n += 1337) {
        WlDpCoef k = {0};
        SimTime t = wl_dp_news_cost(&m, n, &k);
        assert_true(k.steps == 1);
        assert_true(k.news_slices == (double)wl_dp_vp_ratio(&m, n));
        assert_true((double)t == (double)m.step * k.steps +
                                     (double)m.news_slice * k.news_slices);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hex_palette),
        cmocka_unit_test(test_news_cost_sum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
