/* test_core_mutants.c — claims of sim/core that mutation testing (make
 * mutate, docs/testing.md) found unchecked: the value of every unit each
 * unit table accepts, a cleared busy record, and the real-valued getters
 * failing (not only setting an error) on a missing or malformed value. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "sim/core/datapath.h"
#include "sim/core/engine.h"
#include "sim/core/stats.h"
#include "sim/core/units.h"
#include "tests/support.h"

typedef struct {
    const char *text;
    double value; /* base units: ps, B/s, Hz, B */
} UnitCase;

/* Written from the unit names, not copied from sim/core/units.c. */
static const UnitCase times[] = {
    {"1 ps", 1},      {"1 ns", 1e3},   {"1 us", 1e6},    {"1 \xc2\xb5s", 1e6},
    {"1 \xce\xbcs", 1e6}, {"1 ms", 1e9}, {"1 s", 1e12},  {"1 sec", 1e12},
    {"1 min", 60e12}, {"1 h", 3600e12}, {"2 h", 7200e12},
};
static const UnitCase bandwidths[] = {
    {"1 B/s", 1},      {"1 kB/s", 1e3},   {"1 KB/s", 1e3},   {"1 MB/s", 1e6},
    {"1 GB/s", 1e9},   {"1 TB/s", 1e12},  {"1 Bps", 1},      {"1 kBps", 1e3},
    {"1 KBps", 1e3},   {"1 MBps", 1e6},   {"1 GBps", 1e9},   {"1 KiB/s", 1024},
    {"1 MiB/s", 1048576}, {"1 GiB/s", 1073741824.0},         {"8 bit/s", 1},
    {"8 kbit/s", 1e3}, {"8 Kbit/s", 1e3}, {"8 Mbit/s", 1e6}, {"8 Gbit/s", 1e9},
    {"8 b/s", 1},      {"8 kb/s", 1e3},   {"8 Kb/s", 1e3},   {"8 Mb/s", 1e6},
    {"8 Gb/s", 1e9},   {"8 bps", 1},      {"8 kbps", 1e3},   {"8 Kbps", 1e3},
    {"8 Mbps", 1e6},   {"8 Gbps", 1e9},   {"3 KiB/s", 3072},
};
static const UnitCase freqs[] = {
    {"1 Hz", 1}, {"1 kHz", 1e3}, {"1 KHz", 1e3}, {"1 MHz", 1e6}, {"1 GHz", 1e9},
};
static const UnitCase sizes[] = {
    {"1 B", 1},       {"1 kB", 1e3},         {"1 KB", 1e3},
    {"1 MB", 1e6},    {"1 GB", 1e9},         {"1 TB", 1e12},
    {"1 KiB", 1024},  {"1 MiB", 1048576},    {"1 GiB", 1073741824.0},
    {"1 TiB", 1099511627776.0},              {"3 KiB", 3072},
};

static const UnitCase counts[] = {
    {"24", 24}, {"24 K", 24e3}, {"24 M", 24e6}, {"24K", 24e3}, {"3M", 3e6},
};

static void check_table(const UnitCase *c, size_t n, CfgUnitKind kind,
                        gboolean integer)
{
    for (size_t i = 0; i < n; i++) {
        const char *exp = NULL;
        double got = -1;
        uint64_t u = 0;
        gboolean ok = integer ? cfg_units_u64(c[i].text, kind, &u, &exp)
                              : cfg_units_double(c[i].text, kind, &got, &exp);
        if (integer)
            got = (double)u;
        if (!ok)
            fail_msg("'%s' rejected: expected %s", c[i].text, exp);
        if (got != c[i].value)
            fail_msg("'%s' = %.17g, expected %.17g", c[i].text, got,
                     c[i].value);
    }
}

static void test_every_unit(void **state)
{
    (void)state;
    check_table(times, G_N_ELEMENTS(times), CFG_UNIT_TIME, TRUE);
    /* cfg_units_double reads any kind (units.h): the same values */
    check_table(times, G_N_ELEMENTS(times), CFG_UNIT_TIME, FALSE);
    check_table(sizes, G_N_ELEMENTS(sizes), CFG_UNIT_SIZE, FALSE);
    check_table(bandwidths, G_N_ELEMENTS(bandwidths), CFG_UNIT_BANDWIDTH,
                FALSE);
    check_table(freqs, G_N_ELEMENTS(freqs), CFG_UNIT_FREQ, FALSE);
    check_table(sizes, G_N_ELEMENTS(sizes), CFG_UNIT_SIZE, TRUE);
    check_table(counts, G_N_ELEMENTS(counts), CFG_UNIT_COUNT, TRUE);
    check_table(counts, G_N_ELEMENTS(counts), CFG_UNIT_COUNT, FALSE);
}

static void test_busy_clear(void **state)
{
    (void)state;
    SimBusy b;
    sim_busy_init(&b);
    assert_true(sim_busy_add(&b, 2, 5));
    assert_int_equal(b.total, 5);
    sim_busy_clear(&b);
    assert_int_equal(b.total, 0);
    assert_null(b.per_phase);
}

/* A real-valued getter that sets an error must also return FALSE, so that
 * a chain `a && b && c` stops at the first error. */
static void test_real_getters_fail(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *map = cfg_load_string("bw: fast\nf: 3 parsecs\n", "t.yaml", &err);
    assert_non_null(map);
    double v = 7;
    assert_false(cfg_get_bandwidth(map, "bw", FALSE, &v, &err));
    assert_non_null(strstr(err->message, "t.yaml:1:5: found 'fast'"));
    g_clear_error(&err);
    assert_false(cfg_get_freq(map, "f", FALSE, &v, &err));
    assert_non_null(strstr(err->message, "t.yaml:2:4: found '3 parsecs'"));
    g_clear_error(&err);
    assert_false(cfg_get_bandwidth(map, "missing", TRUE, &v, &err));
    assert_non_null(err);
    g_clear_error(&err);
    assert_false(cfg_get_freq(map, "missing", TRUE, &v, &err));
    assert_non_null(err);
    g_clear_error(&err);
    assert_true(v == 7); /* untouched on failure */
    cfg_free(map);
}

/* $PGSIM_MAX_INPUT: bytes with an optional k, M or G (powers of 1024);
 * anything else means the default. */
static void test_input_limit_env(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        guint64 bytes;
    } cases[] = {
        {"5000", 5000},        {"3k", 3072},  {"3M", 3u << 20},
        {"3G", 3ull << 30},    {"3T", 0},     {"3kB", 0},
        {"x", 0},              {"", 0},
        {"17179869183G", 17179869183ull << 30},  {"17179869184G", 0},
        {"18446744073709551615", G_MAXUINT64}, {"18446744073709551616", 0},
    };
    sim_file_set_limit(0);
    for (size_t i = 0; i < G_N_ELEMENTS(cases); i++) {
        g_setenv("PGSIM_MAX_INPUT", cases[i].text, TRUE);
        guint64 want = cases[i].bytes ? cases[i].bytes : SIM_FILE_LIMIT_DEFAULT;
        if (sim_file_limit() != want)
            fail_msg("PGSIM_MAX_INPUT=%s: %" G_GUINT64_FORMAT ", expected %"
                     G_GUINT64_FORMAT, cases[i].text, sim_file_limit(), want);
    }
    g_unsetenv("PGSIM_MAX_INPUT");
    assert_true(sim_file_limit() == SIM_FILE_LIMIT_DEFAULT);
}

/* Zero is exact at any exponent: "0e-30 B" is 0 bytes, not a fraction of
 * a byte (sizes must be whole); a true fraction is still refused. */
static void test_zero_any_exponent(void **state)
{
    (void)state;
    const char *exp = NULL;
    uint64_t v = 9;
    assert_true(cfg_units_u64("0e-30 B", CFG_UNIT_SIZE, &v, &exp));
    assert_int_equal(v, 0);
    v = 9;
    assert_true(cfg_units_u64("0.000e-25 KB", CFG_UNIT_SIZE, &v, &exp));
    assert_int_equal(v, 0);
    assert_false(cfg_units_u64("1e-30 B", CFG_UNIT_SIZE, &v, &exp));
    assert_false(cfg_units_u64("5e-50 B", CFG_UNIT_SIZE, &v, &exp));
    /* far below a picosecond: 1.8e19 x 1e-40 s = 1.8e-9 ps rounds to 0
     * (a divisor of 10^28 does not fit 64 bits: no wrapped division) */
    v = 9;
    assert_true(cfg_units_u64("18446744073709551615e-40 s", CFG_UNIT_TIME, &v,
                              &exp));
    assert_int_equal(v, 0);
}

/* Keys an override creates (the leaf and every map on its path) are
 * located at the override itself, line 1 column 1 of "--set ...". */
static void check_created_key(const char *assignment, const char *want)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string("a: {k: 1}\n", "t.yaml", &err);
    assert_non_null(cfg_get(root, "a"));
    assert_non_null(cfg_get(cfg_get(root, "a"), "k"));
    assert_true(cfg_set_override(root, assignment, &err));
    assert_false(cfg_check_unused(root, &err));
    if (!g_str_has_prefix(err->message, want))
        fail_msg("%s: got '%s', want '%s...'", assignment, err->message, want);
    g_clear_error(&err);
    cfg_free(root);
}

static void test_override_locations(void **state)
{
    (void)state;
    check_created_key("a.b.c=1", "--set a.b.c=1:1:1: found unknown key 'b'");
    check_created_key("a.z=1", "--set a.z=1:1:1: found unknown key 'z'");
    /* the map created on the path is located there too */
    GError *err = NULL;
    CfgNode *root = cfg_load_string("a: {k: 1}\n", "t.yaml", &err);
    assert_true(cfg_set_override(root, "a.n.x=1", &err));
    int64_t v = 0;
    assert_false(cfg_get_int(cfg_get(root, "a"), "n", FALSE, 0, 9, &v, &err));
    if (!g_str_has_prefix(err->message, "--set a.n.x=1:1:1: found a map"))
        fail_msg("got '%s'", err->message);
    g_clear_error(&err);
    cfg_free(root);
}

/* A 21st significant digit that is 0 loses nothing (1 s exactly); any
 * other digit there cannot be kept in a whole number of picoseconds. */
static void test_digit_past_twenty(void **state)
{
    (void)state;
    uint64_t v = 0;
    const char *exp = NULL;
    assert_true(cfg_units_u64("1.00000000000000000000 s", CFG_UNIT_TIME, &v,
                              &exp));
    assert_int_equal(v, 1000000000000ull);
    assert_false(cfg_units_u64("1.00000000000000000001 s", CFG_UNIT_TIME, &v,
                               &exp));
    assert_string_equal(exp, "a number with at most 20 significant digits");
}

static void count_call(SimEngine *e, void *ctx)
{
    (void)e;
    (*(int *)ctx)++;
}

static void no_op(SimEngine *e, void *ctx, void *arg)
{
    (void)e;
    (void)ctx;
    (void)arg;
}

/* Progress every 2 events calls back twice in 4 events; a NULL callback
 * turns progress off whatever `every` says. */
static void test_progress_off(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    int calls = 0;
    sim_engine_set_progress(e, 2, count_call, &calls);
    for (int i = 0; i < 4; i++)
        sim_schedule_in(e, (SimTime)i, no_op, NULL, NULL);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(calls, 2);
    sim_engine_set_progress(e, 1, NULL, &calls);
    for (int i = 0; i < 3; i++)
        sim_schedule_in(e, (SimTime)i, no_op, NULL, NULL);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(calls, 2);
    sim_engine_free(e);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_unit),
        cmocka_unit_test(test_busy_clear),
        cmocka_unit_test(test_real_getters_fail),
        cmocka_unit_test(test_input_limit_env),
        cmocka_unit_test(test_zero_any_exponent),
        cmocka_unit_test(test_override_locations),
        cmocka_unit_test(test_digit_past_twenty),
        cmocka_unit_test(test_progress_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
