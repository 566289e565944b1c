/* test_core_edges.c — boundaries and error paths of sim/core that
 * mutation testing (make mutate, docs/testing.md) showed no test
 * reached: config errors (complex keys, non-map lookups, long values
 * described), path indices, unit parsing at its edges (signs, spaces,
 * trailing zeros, rates below 1 per second, over-long mantissas), exit
 * statuses, idle counts, and sim_rng_below's rejection step. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "sim/core/cfg_impl.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include "sim/core/result.h"
#include "sim/core/rng.h"
#include "sim/core/units.h"

static void test_cfg_errors(void **state)
{
    (void)state;
    GError *err = NULL;
    assert_null(cfg_load_string("? [a, b]\n: 1\n", "k.yaml", &err));
    assert_string_equal(err->message, "k.yaml:1:3: found a complex key, "
                                      "expected a plain key");
    g_clear_error(&err);
    assert_null(cfg_copy(NULL));
    assert_true(cfg_check_unused_except(NULL, NULL, &err));
    CfgNode *root = cfg_load_string("s: [1, 2]\nm: {a: 1}\nb: maybe\n"
                                    "d: 1e999\ne: 1.5.2\nf: 2.5\n",
                                    "k.yaml", &err);
    assert_non_null(root);
    const char *str;
    /* a lookup in a node that is not a map */
    assert_false(cfg_get_str(cfg_get(root, "s"), "a", TRUE, &str, &err));
    assert_string_equal(err->message, "k.yaml:1:4: found a sequence, "
                                      "expected a map");
    g_clear_error(&err);
    /* no map at all */
    assert_false(cfg_get_str(NULL, "k", TRUE, &str, &err));
    assert_string_equal(err->message, "found no key 'k' in this map, "
                                      "expected 'k': a string");
    g_clear_error(&err);
    str = "x";
    assert_true(cfg_get_str(NULL, "k", FALSE, &str, &err));
    gboolean flag = TRUE;
    assert_false(cfg_get_bool(root, "nope", TRUE, &flag, &err));
    assert_non_null(strstr(err->message, "no key 'nope'"));
    g_clear_error(&err);
    assert_false(cfg_get_bool(root, "b", TRUE, &flag, &err));
    assert_string_equal(err->message, "k.yaml:3:4: found 'maybe', "
                                      "expected true or false");
    g_clear_error(&err);
    double d = 7;
    assert_false(cfg_get_double(root, "d", TRUE, -1e300, 1e300, &d, &err));
    assert_non_null(strstr(err->message, "found '1e999'"));
    g_clear_error(&err);
    assert_false(cfg_get_double(root, "e", TRUE, -1e300, 1e300, &d, &err));
    g_clear_error(&err);
    assert_true(d == 7);
    assert_true(cfg_get_double(root, "f", TRUE, 2.5, 2.5, &d, &err));
    assert_true(d == 2.5);
    assert_false(cfg_get_double(root, "f", TRUE, 2.6, 3, &d, &err));
    g_clear_error(&err);
    assert_false(cfg_get_double(root, "f", TRUE, 0, 2.4, &d, &err));
    g_clear_error(&err);
    uint64_t u = 3;
    assert_false(cfg_get_size(root, "nope", TRUE, &u, &err));
    assert_non_null(strstr(err->message, "no key 'nope'"));
    g_clear_error(&err);
    assert_true(cfg_get_size(root, "nope", FALSE, &u, &err));
    assert_int_equal(u, 3);
    assert_false(cfg_set_override(root, "=3", &err));
    assert_non_null(err);
    g_clear_error(&err);
    cfg_free(root);
}

/* Values longer than 60 characters are cut to 57 and an ellipsis. */
static void test_describe_long(void **state)
{
    (void)state;
    char v60[61], v61[62];
    memset(v60, 'a', 60);
    v60[60] = '\0';
    memset(v61, 'b', 61);
    v61[61] = '\0';
    char *text = g_strdup_printf("x: %s\ny: %s\nz: \"é%s\"\n", v60, v61, v60);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "l.yaml", &err);
    char *s = cfg_describe(cfg_get(root, "x"));
    char *want = g_strdup_printf("'%s'", v60);
    assert_string_equal(s, want);
    g_free(s);
    g_free(want);
    s = cfg_describe(cfg_get(root, "y"));
    want = g_strdup_printf("'%.57s...'", v61);
    assert_string_equal(s, want);
    g_free(s);
    g_free(want);
    s = cfg_describe(cfg_get(root, "z")); /* 61 characters, 62 bytes */
    want = g_strdup_printf("'é%.56s...'", v60);
    assert_string_equal(s, want);
    g_free(s);
    g_free(want);
    cfg_free(root);
    g_free(text);
}

static void test_path_index(void **state)
{
    (void)state;
    assert_int_equal(cfg_path_index("", 0), -1);
    assert_int_equal(cfg_path_index("0", 1), 0);
    assert_int_equal(cfg_path_index("9", 1), 9);
    assert_int_equal(cfg_path_index("123456789", 9), 123456789);
    assert_int_equal(cfg_path_index("1234567890", 10), -1);
    assert_int_equal(cfg_path_index("12a", 3), -1);
    assert_int_equal(cfg_path_index("/", 1), -1);
    assert_int_equal(cfg_path_index(":", 1), -1);
    assert_int_equal(cfg_path_index("12a", 2), 12);
}

static uint64_t u64_of(const char *s, CfgUnitKind k)
{
    uint64_t v = 0;
    const char *exp = NULL;
    if (!cfg_units_u64(s, k, &v, &exp))
        fail_msg("'%s' refused: %s", s, exp);
    return v;
}

static double dbl_of(const char *s, CfgUnitKind k)
{
    double v = 0;
    const char *exp = NULL;
    if (!cfg_units_double(s, k, &v, &exp))
        fail_msg("'%s' refused: %s", s, exp);
    return v;
}

static const char *refused(const char *s, CfgUnitKind k)
{
    double v = 0;
    const char *exp = NULL;
    if (cfg_units_double(s, k, &v, &exp))
        fail_msg("'%s' accepted as %g", s, v);
    return exp;
}

static void test_units_edges(void **state)
{
    (void)state;
    assert_int_equal(u64_of("  5 us", CFG_UNIT_TIME), 5 * SIM_US);
    assert_int_equal(u64_of("+5 us", CFG_UNIT_TIME), 5 * SIM_US);
    assert_int_equal(u64_of("1.50 us", CFG_UNIT_TIME), 1500000);
    assert_int_equal(u64_of("1.500000 ns", CFG_UNIT_TIME), 1500);
    assert_int_equal(u64_of("0.000 s", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_of("2e3 ps", CFG_UNIT_TIME), 2000);
    assert_int_equal(u64_of("2e+3 ps", CFG_UNIT_TIME), 2000);
    assert_int_equal(u64_of("2000e-3 ns", CFG_UNIT_TIME), 2000);
    assert_true(dbl_of("1 B/s", CFG_UNIT_BANDWIDTH) == 1.0);
    assert_true(dbl_of("0 B/s", CFG_UNIT_BANDWIDTH) == 0.0);
    assert_true(dbl_of("1 Hz", CFG_UNIT_FREQ) == 1.0);
    assert_string_equal(refused("0.5 B/s", CFG_UNIT_BANDWIDTH),
                        "0 or at least 1 B/s");
    assert_string_equal(refused("0.5 Hz", CFG_UNIT_FREQ),
                        "0 or at least 1 Hz");
    assert_string_equal(refused("0.999 B/s", CFG_UNIT_BANDWIDTH),
                        "0 or at least 1 B/s");
    /* more than 20 significant digits: fine for a rate, not a time */
    assert_true(dbl_of("1.000000000000000000000001 MB/s", CFG_UNIT_BANDWIDTH) ==
                1e6);
    assert_true(dbl_of("123456789012345678901234 B/s", CFG_UNIT_BANDWIDTH) ==
                123456789012345678901234.0);
    uint64_t v;
    const char *exp = NULL;
    assert_false(cfg_units_u64("1.000000000000000000000001 us", CFG_UNIT_TIME,
                               &v, &exp));
    assert_non_null(strstr(exp, "at most 20 significant"));
    assert_false(cfg_units_u64("-1 us", CFG_UNIT_TIME, &v, &exp));
    assert_false(cfg_units_u64("1e us", CFG_UNIT_TIME, &v, &exp));
    assert_false(cfg_units_u64("1e+ us", CFG_UNIT_TIME, &v, &exp));
}

static void test_exit_status(void **state)
{
    (void)state;
    assert_int_equal(sim_error_exit_status(NULL), 0);
    GError *e = g_error_new(SIM_ERROR, SIM_ERROR_INTERNAL, "x");
    assert_int_equal(sim_error_exit_status(e), 1);
    g_error_free(e);
    e = g_error_new(SIM_ERROR, SIM_ERROR_INPUT, "x");
    assert_int_equal(sim_error_exit_status(e), 2);
    g_error_free(e);
    e = g_error_new(G_FILE_ERROR, SIM_ERROR_INTERNAL, "x");
    assert_int_equal(sim_error_exit_status(e), 2);
    g_error_free(e);
    GError *err = NULL;
    sim_error_located(&err, NULL, 3, 4, "a", "b");
    assert_string_equal(err->message, "<input>:3:4: found a, expected b");
    g_error_free(err);
}

static void test_result_edges(void **state)
{
    (void)state;
    SimResult *r = sim_result_new("w", "m");
    assert_true(sim_result_mean_frame_s(r) == 0.0);
    assert_int_equal(sim_result_n_idle(r), 0);
    sim_result_add_idle(r, "gp", 3);
    sim_result_add_idle(r, "rn", 4);
    sim_result_add_idle(r, "gp", 5);
    assert_int_equal(r->idle->len, 2);
    assert_int_equal(((SimIdleResult *)g_ptr_array_index(r->idle, 0))->count,
                     8);
    assert_int_equal(((SimIdleResult *)g_ptr_array_index(r->idle, 1))->count,
                     4);
    assert_int_equal(sim_result_n_idle(r), 12);
    sim_result_add_frame(r, 2 * SIM_MS);
    sim_result_add_frame(r, 4 * SIM_MS);
    assert_true(sim_result_mean_frame_s(r) == 0.003);
    sim_result_free(r);
}

/* Lemire's nearly divisionless method ("Fast random integer generation in
 * an interval", ACM TOMACS 29(1), 2019), written out here: for n just
 * above 2^63 about half the draws are rejected. */
static uint64_t lemire(SimRng *r, uint64_t n)
{
    for (;;) {
        unsigned __int128 m = (unsigned __int128)sim_rng_u64(r) * n;
        uint64_t lo = (uint64_t)m;
        if (lo >= n || lo >= (0 - n) % n)
            return (uint64_t)(m >> 64);
    }
}

static void test_rng_below_rejection(void **state)
{
    (void)state;
    static const uint64_t ns[] = {(1ull << 63) + 1, (1ull << 63) + 12345,
                                  UINT64_MAX, 3, 1, (1ull << 62) * 3};
    for (guint k = 0; k < G_N_ELEMENTS(ns); k++) {
        SimRng a, b;
        sim_rng_init(&a, 77 + k, 5);
        sim_rng_init(&b, 77 + k, 5);
        for (int i = 0; i < 200; i++) {
            uint64_t x = sim_rng_below(&a, ns[k]);
            assert_true(x < ns[k]);
            assert_int_equal(x, lemire(&b, ns[k]));
        }
        assert_int_equal(sim_rng_u64(&a), sim_rng_u64(&b)); /* same draws */
    }
}

static void test_mem_limit_env(void **state)
{
    (void)state;
    sim_mem_set_limit(0);
    g_setenv("PGSIM_MEM_LIMIT", "3G", TRUE);
    assert_int_equal(sim_mem_limit(), 3ull << 30);
    g_setenv("PGSIM_MEM_LIMIT", "512M", TRUE);
    assert_int_equal(sim_mem_limit(), 512ull << 20);
    g_unsetenv("PGSIM_MEM_LIMIT");
    assert_true(sim_mem_limit() > (64ull << 20));
    sim_mem_set_limit(1234);
    assert_int_equal(sim_mem_limit(), 1234);
    sim_mem_set_limit(0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cfg_errors),
        cmocka_unit_test(test_describe_long),
        cmocka_unit_test(test_path_index),
        cmocka_unit_test(test_units_edges),
        cmocka_unit_test(test_exit_status),
        cmocka_unit_test(test_result_edges),
        cmocka_unit_test(test_rng_below_rejection),
        cmocka_unit_test(test_mem_limit_env),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
