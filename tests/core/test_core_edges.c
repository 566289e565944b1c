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
#include <sys/stat.h>
#include <glib/gstdio.h>

#include "sim/core/cfg.h"
#include "sim/core/cfg_impl.h"
#include "sim/core/datapath.h"
#include "sim/core/engine.h"
#include "sim/core/error.h"
#include "sim/core/evq.h"
#include "sim/core/memlimit.h"
#include "sim/core/result.h"
#include "sim/core/rng.h"
#include "sim/core/stats.h"
#include "sim/core/units.h"
#include "tests/support.h"

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

/* Freeing nothing is allowed. */
static void test_free_null(void **state)
{
    (void)state;
    sim_evq_free(NULL);
    cfg_free(NULL);
    SimEvq *q = sim_evq_new();
    sim_evq_free(q);
}



/* Moments of 1, 2 and 3 samples (variance with n - 1), and busy time
 * per phase with its overflow refused whole. */
static void test_moments_and_busy(void **state)
{
    (void)state;
    SimMoments m = {0};
    assert_true(sim_moments_var(&m) == 0.0);
    sim_moments_add(&m, 5);
    assert_true(sim_moments_var(&m) == 0.0);
    assert_true(m.min == 5 && m.max == 5 && m.mean == 5);
    sim_moments_add(&m, 3);
    assert_true(sim_moments_var(&m) == 2.0);
    assert_true(m.min == 3 && m.max == 5 && m.mean == 4);
    sim_moments_add(&m, 7);
    assert_true(sim_moments_var(&m) == 4.0);
    assert_true(m.min == 3 && m.max == 7 && m.mean == 5);
    assert_int_equal(m.n, 3);
    SimBusy b;
    sim_busy_init(&b);
    assert_true(sim_busy_add(&b, 2, 10));
    assert_true(sim_busy_add(&b, 0, 5));
    assert_true(sim_busy_add(&b, 2, 1));
    assert_int_equal(sim_busy_phase(&b, 2), 11);
    assert_int_equal(sim_busy_phase(&b, 0), 5);
    assert_int_equal(sim_busy_phase(&b, 1), 0);
    assert_int_equal(sim_busy_phase(&b, 3), 0);
    assert_int_equal(b.total, 16);
    assert_false(sim_busy_add(&b, 1, SIM_TIME_MAX - 15));
    assert_int_equal(b.total, 16); /* nothing half-added */
    assert_int_equal(sim_busy_phase(&b, 1), 0);
    assert_true(sim_busy_add(&b, 1, SIM_TIME_MAX - 16));
    assert_int_equal(b.total, SIM_TIME_MAX);
    sim_busy_clear(&b);
    assert_int_equal(sim_busy_phase(&b, 0), 0);
    assert_int_equal(b.total, 0);
}



/* Booleans, integer ranges and their texts, enums, maps. */
static void test_getters_edges(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "b: [true, True, TRUE, yes, on, false, False, FALSE, no, off, Yes]\n"
        "i: {lo: -5, hi: 7, big: 9223372036854775807, x: 1.5}\n"
        "e: {first: red, last: blue, other: pink}\n"
        "m: {k: 1}\n",
        "g.yaml", &err);
    assert_non_null(root);
    const CfgNode *bl = cfg_get(root, "b");
    for (guint k = 0; k < 11; k++) {
        char *text = g_strdup_printf("v: %s\n", cfg_scalar(cfg_seq_at(bl, k)));
        CfgNode *wrap = cfg_load_string(text, "w.yaml", &err);
        g_free(text);
        gboolean v = 7;
        gboolean ok = cfg_get_bool(wrap, "v", TRUE, &v, &err);
        if (k < 10) {
            assert_true(ok);
            assert_int_equal(v, k < 5);
        } else {
            assert_false(ok);
            assert_string_equal(err->message,
                                "w.yaml:1:4: found 'Yes', expected true or "
                                "false");
            g_clear_error(&err);
        }
        cfg_free(wrap);
    }
    const CfgNode *in = cfg_get(root, "i");
    int64_t x = 99;
    assert_true(cfg_get_int(in, "lo", TRUE, -5, 7, &x, &err));
    assert_int_equal(x, -5);
    assert_true(cfg_get_int(in, "hi", TRUE, -5, 7, &x, &err));
    assert_int_equal(x, 7);
    assert_false(cfg_get_int(in, "lo", TRUE, -4, 7, &x, &err));
    assert_string_equal(err->message,
                        "g.yaml:2:9: found '-5', expected an integer in "
                        "[-4, 7]");
    g_clear_error(&err);
    assert_false(cfg_get_int(in, "hi", TRUE, 8, INT64_MAX, &x, &err));
    assert_string_equal(err->message,
                        "g.yaml:2:17: found '7', expected an integer >= 8");
    g_clear_error(&err);
    assert_false(cfg_get_int(in, "x", TRUE, INT64_MIN, INT64_MAX, &x, &err));
    assert_non_null(strstr(err->message, "found '1.5', expected an integer"));
    assert_null(strstr(err->message, "integer "));
    g_clear_error(&err);
    assert_true(cfg_get_int(in, "big", TRUE, 0, INT64_MAX, &x, &err));
    assert_int_equal(x, INT64_MAX);
    x = 3;
    assert_true(cfg_get_int(in, "none", FALSE, 0, 1, &x, &err));
    assert_int_equal(x, 3);
    static const char *const words[] = {"red", "green", "blue", NULL};
    int w = -1;
    const CfgNode *en = cfg_get(root, "e");
    assert_true(cfg_get_enum(en, "first", TRUE, words, &w, &err));
    assert_int_equal(w, 0);
    assert_true(cfg_get_enum(en, "last", TRUE, words, &w, &err));
    assert_int_equal(w, 2);
    assert_false(cfg_get_enum(en, "other", TRUE, words, &w, &err));
    assert_string_equal(err->message, "g.yaml:3:36: found 'pink', expected "
                                      "one of: red, green, blue");
    g_clear_error(&err);
    assert_int_equal(w, 2);
    const CfgNode *m = NULL;
    assert_true(cfg_get_map(root, "m", TRUE, "a map of k", &m, &err));
    assert_non_null(m);
    assert_false(cfg_get_map(root, "b", TRUE, "a map of k", &m, &err));
    assert_string_equal(err->message,
                        "g.yaml:1:4: found a sequence, expected a map of k");
    g_clear_error(&err);
    assert_true(cfg_get_map(root, "zz", FALSE, "a map", &m, &err));
    assert_null(m);
    cfg_free(root);
}

/* A FIFO is refused as a pipe, not read (it might never end). */
static void test_fifo_refused(void **state)
{
    (void)state;
    char *tmp = g_dir_make_tmp("pgsim-fifo-XXXXXX", NULL);
    char *f = g_build_filename(tmp, "p", NULL);
    assert_int_equal(mkfifo(f, 0600), 0);
    char *text = NULL;
    GError *err = NULL;
    assert_false(sim_file_read(f, &text, NULL, &err));
    char *want = g_strdup_printf("%s:0:0: found a pipe, expected a regular "
                                 "file", f);
    assert_string_equal(err->message, want);
    g_free(want);
    g_clear_error(&err);
    g_unlink(f);
    g_rmdir(tmp);
    g_free(f);
    g_free(tmp);
}

static void nothing(SimEngine *e, void *ctx, void *arg)
{
    (void)e;
    (void)ctx;
    (void)arg;
}

static void fail_twice(SimEngine *e, void *ctx, void *arg)
{
    (void)ctx;
    (void)arg;
    sim_engine_fail(e, g_error_new(SIM_ERROR, SIM_ERROR_INPUT, "first"));
    sim_engine_fail(e, g_error_new(SIM_ERROR, SIM_ERROR_INPUT, "second"));
}

/* A run keeps its first error; an empty queue moves the clock to
 * `until` but never back; a dry run reports a scheduling error first;
 * pending events are bounded by the memory limit. */
static void test_engine_edges(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    sim_schedule_at(e, 5, fail_twice, NULL, NULL);
    sim_schedule_at(e, 6, nothing, NULL, NULL);
    GError *err = NULL;
    assert_false(sim_engine_run(e, SIM_TIME_MAX, &err));
    assert_string_equal(err->message, "first");
    g_clear_error(&err);
    assert_int_equal(sim_now(e), 5);
    assert_int_equal(sim_engine_pending(e), 1);
    assert_true(sim_engine_run(e, 100, &err));
    assert_int_equal(sim_now(e), 100);
    assert_true(sim_engine_run(e, 50, &err));
    assert_int_equal(sim_now(e), 100);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, &err));
    assert_int_equal(sim_now(e), 100);
    assert_int_equal(sim_engine_events(e), 2);
    sim_engine_free(e);
    e = sim_engine_new(1);
    sim_engine_set_dry_run(e, TRUE);
    sim_schedule_at(e, 1, nothing, NULL, NULL);
    assert_false(sim_engine_run(e, SIM_TIME_MAX, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_DRY_RUN));
    g_clear_error(&err);
    assert_int_equal(sim_engine_events(e), 0);
    sim_engine_free(e);
    /* 1,024 pending events fit in 32 KiB; 2,048 do not */
    sim_mem_set_limit(1024 * 2 * sizeof(SimEvKey));
    e = sim_engine_new(1);
    sim_engine_set_dry_run(e, TRUE);
    for (int i = 0; i < 1024; i++)
        assert_true(sim_schedule_at(e, (SimTime)i, nothing, NULL, NULL));
    assert_false(sim_schedule_at(e, 7, nothing, NULL, NULL));
    assert_int_equal(sim_engine_pending(e), 1024);
    assert_false(sim_engine_run(e, SIM_TIME_MAX, &err));
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_INPUT));
    assert_non_null(strstr(err->message, "found 2048 pending events"));
    g_clear_error(&err);
    sim_engine_free(e);
    sim_mem_set_limit(0);
}

/* Plain null spellings are empty values; quoted ones, and near misses,
 * are strings; an alias copies its anchor's tree at its own place. */
static void test_nulls_and_aliases(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "a: ~\nb: null\nc: Null\nd: NULL\ne:\nf: \"null\"\ng: nul\nh: 'NULL'\n"
        "i: nULL\nj: &x {k: [1, 2]}\nl: *x\n",
        "n.yaml", &err);
    assert_non_null(root);
    static const char *const nulls[] = {"a", "b", "c", "d", "e"};
    for (guint i = 0; i < G_N_ELEMENTS(nulls); i++)
        assert_int_equal(cfg_kind(cfg_get(root, nulls[i])), CFG_NULL);
    static const char *const strs[] = {"f", "g", "h", "i"};
    static const char *const text[] = {"null", "nul", "NULL", "nULL"};
    for (guint i = 0; i < G_N_ELEMENTS(strs); i++) {
        const CfgNode *v = cfg_get(root, strs[i]);
        assert_int_equal(cfg_kind(v), CFG_SCALAR);
        assert_string_equal(cfg_scalar(v), text[i]);
    }
    const CfgNode *l = cfg_get(root, "l");
    assert_int_equal(cfg_kind(l), CFG_MAP);
    assert_int_equal(cfg_line(l), 11);
    assert_int_equal(cfg_col(l), 4);
    const CfgNode *k = cfg_path(root, "l.k");
    assert_int_equal(cfg_seq_len(k), 2);
    assert_string_equal(cfg_scalar(cfg_seq_at(k, 1)), "2");
    CfgNode *copy = cfg_copy(cfg_get(root, "j"));
    assert_int_equal(cfg_seq_len(cfg_get(copy, "k")), 2);
    assert_string_equal(cfg_scalar(cfg_seq_at(cfg_get(copy, "k"), 0)), "1");
    cfg_free(copy);
    cfg_free(root);
}

/* An empty document is an empty value at line 1, column 1; a file whose
 * size says more than it holds (a /sys attribute, 4096 bytes that read
 * short) is refused as one that shrank. */
static void test_empty_and_short(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("", "e.yaml", &err);
    assert_non_null(root);
    assert_int_equal(cfg_kind(root), CFG_NULL);
    assert_int_equal(cfg_line(root), 1);
    assert_int_equal(cfg_col(root), 1);
    assert_string_equal(cfg_file(root), "e.yaml");
    cfg_free(root);
    const char *f = "/sys/kernel/mm/transparent_hugepage/enabled";
    if (!g_file_test(f, G_FILE_TEST_IS_REGULAR))
        return; /* no sysfs here */
    char *text = NULL;
    assert_false(sim_file_read(f, &text, NULL, &err));
    char *want = g_strdup_printf("%s:0:0: found a file that shrank, expected "
                                 "a readable file", f);
    assert_string_equal(err->message, want);
    g_free(want);
    g_clear_error(&err);
}

/* Trailing blanks after a bare number are not a unit; the integer
 * getter's expectation names the range it checks, or none. */
static void test_value_text_edges(void **state)
{
    (void)state;
    uint64_t v = 0;
    const char *exp = NULL;
    assert_true(cfg_units_u64("16 ", CFG_UNIT_COUNT, &v, &exp));
    assert_int_equal(v, 16);
    assert_true(cfg_units_u64("0  ", CFG_UNIT_TIME, &v, &exp));
    assert_int_equal(v, 0);
    assert_true(cfg_units_u64("5 us \t", CFG_UNIT_TIME, &v, &exp));
    assert_int_equal(v, 5 * SIM_US);
    double d = 0;
    assert_true(cfg_units_double("2 MB/s  ", CFG_UNIT_BANDWIDTH, &d, &exp));
    assert_true(d == 2e6);
    GError *err = NULL;
    CfgNode *r = cfg_load_string("i: x\nj: 5\n", "v.yaml", &err);
    assert_non_null(r);
    int64_t x = 0;
    assert_false(cfg_get_int(r, "i", TRUE, INT64_MIN, INT64_MAX, &x, &err));
    assert_string_equal(err->message, "v.yaml:1:4: found 'x', expected an "
                                      "integer");
    g_clear_error(&err);
    assert_false(cfg_get_int(r, "i", TRUE, -3, INT64_MAX, &x, &err));
    assert_string_equal(err->message, "v.yaml:1:4: found 'x', expected an "
                                      "integer >= -3");
    g_clear_error(&err);
    assert_false(cfg_get_int(r, "j", TRUE, INT64_MIN, 4, &x, &err));
    assert_string_equal(err->message,
                        "v.yaml:2:4: found '5', expected an integer in "
                        "[-9223372036854775808, 4]");
    g_clear_error(&err);
    assert_true(cfg_get_int(r, "j", TRUE, 5, 5, &x, &err));
    assert_int_equal(x, 5);
    cfg_free(r);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cfg_errors),
        cmocka_unit_test(test_describe_long),
        cmocka_unit_test(test_path_index),
        cmocka_unit_test(test_exit_status),
        cmocka_unit_test(test_result_edges),
        cmocka_unit_test(test_rng_below_rejection),
        cmocka_unit_test(test_mem_limit_env),
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_moments_and_busy),
        cmocka_unit_test(test_getters_edges),
        cmocka_unit_test(test_fifo_refused),
        cmocka_unit_test(test_engine_edges),
        cmocka_unit_test(test_nulls_and_aliases),
        cmocka_unit_test(test_value_text_edges),
        cmocka_unit_test(test_empty_and_short),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
