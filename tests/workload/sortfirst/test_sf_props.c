/* test_sf_props.c — bounds every sort-first run keeps whatever its
 * bookkeeping and mastership (issue 21; properties, not values, so they
 * hold across the workload's ongoing rework): a chunk has one master and
 * only its master hands it over, so a frame has at most `chunks`
 * handovers; counts are sums of positive sizes and never wrap (a frame of
 * a small scene moves less than every polygon to every processor at
 * 1 KiB each). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/workload/sortfirst/sf_testutil.h"

static const char *const small = SF_TEST_SMALL;

static void check_bounds(const char *workload)
{
    const char *const o[] = {workload, NULL};
    GError *err = NULL;
    SimResult *r = sf_test_run(small, o, 5, NULL, FALSE, &err);
    if (!r)
        fail_msg("%s: %s", workload, err->message);
    double chunks = sf_test_metric(r, "chunks");
    double h = sf_test_metric(r, "handovers_per_frame");
    if (!(h > 0 && h <= chunks))
        fail_msg("%s: %.3f handovers a frame, %.0f chunks", workload, h,
                 chunks);
    double procs = sf_test_metric(r, "processors");
    double polys = sf_test_metric(r, "max_set_polygons");
    const char *bytes[] = {"migrated_bytes_per_frame", "initial_bytes"};
    for (guint i = 0; i < G_N_ELEMENTS(bytes); i++) {
        double b = sf_test_metric(r, bytes[i]);
        if (!(b > 0 && b <= procs * polys * 1024))
            fail_msg("%s: %s %.0f", workload, bytes[i], b);
    }
    double mp = sf_test_metric(r, "migrated_polygons_per_frame");
    assert_true(mp >= 0 && mp <= procs * polys);
    sim_result_free(r);
}

static void test_dynamic_mastership_bounds(void **state)
{
    (void)state;
    const char *base = "workload={type: sortfirst, processors: 4, "
                       "granularity: 5, resolution: 64, mastership: dynamic, "
                       "bookkeeping: ";
    char *max = g_strconcat(base, "maxset}", NULL);
    char *min = g_strconcat(base, "minset}", NULL);
    check_bounds(max);
    check_bounds(min);
    g_free(max);
    g_free(min);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dynamic_mastership_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
