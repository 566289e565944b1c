/* test_cfg_get.c — the typed getters of sim/core/cfg_get.c, value by value
 * and message by message: an absent optional key leaves the caller's
 * default, an absent required one names the key at the map, a value of
 * the wrong kind or out of range is refused at its file:line:column with
 * the expected text; every bool word, the three int range texts, count
 * ranges at both ends, enums, the unit getters and the CLI flag parsers,
 * and the description of long values. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "tests/support.h"

static CfgNode *root;

static int setup(void **state)
{
    (void)state;
    GError *err = NULL;
    root = cfg_load_string("s: hello\n"         /* line 1 */
                           "b: yes\n"           /* 2 */
                           "i: -7\n"            /* 3 */
                           "d: 2.5\n"           /* 4 */
                           "m: {x: 1}\n"        /* 5 */
                           "q: [1, 2]\n"        /* 6 */
                           "t: 3 us\n"          /* 7 */
                           "z: 2 KiB\n"         /* 8 */
                           "w: 40 MB/s\n"       /* 9 */
                           "f: 2 GHz\n"         /* 10 */
                           "c: 16K\n"           /* 11 */
                           "e: green\n"         /* 12 */
                           "n:\n"               /* 13 */
                           "bad: 5 parsecs\n",  /* 14 */
                           "g.yaml", &err);
    assert_non_null(root);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    cfg_free(root);
    return 0;
}

static void expect_msg(GError **err, const char *want)
{
    assert_non_null(*err);
    if (strcmp((*err)->message, want) != 0)
        fail_msg("got '%s'\nwant '%s'", (*err)->message, want);
    assert_int_equal(sim_error_exit_status(*err), 2);
    g_clear_error(err);
}

static void test_absent_and_present(void **state)
{
    (void)state;
    GError *err = NULL;
    const char *s = "default";
    gboolean b = 7;
    int64_t i = 99;
    double d = 9.5;
    SimTime t = 11;
    uint64_t u = 13;
    int e = 17;
    const CfgNode *m = root;
    /* absent and optional: TRUE, the default stays */
    assert_true(cfg_get_str(root, "none", FALSE, &s, &err));
    assert_true(cfg_get_bool(root, "none", FALSE, &b, &err));
    assert_true(cfg_get_int(root, "none", FALSE, 0, 9, &i, &err));
    assert_true(cfg_get_double(root, "none", FALSE, 0, 9, &d, &err));
    assert_true(cfg_get_map(root, "none", FALSE, "a map", &m, &err));
    assert_true(cfg_get_time(root, "none", FALSE, &t, &err));
    assert_true(cfg_get_size(root, "none", FALSE, &u, &err));
    assert_true(cfg_get_count(root, "none", FALSE, 0, 9, &u, &err));
    static const char *const colours[] = {"red", "green", NULL};
    assert_true(cfg_get_enum(root, "none", FALSE, colours, &e, &err));
    assert_null(err);
    assert_string_equal(s, "default");
    assert_int_equal(b, 7);
    assert_int_equal(i, 99);
    assert_true(d == 9.5);
    assert_null(m);
    assert_int_equal(t, 11);
    assert_int_equal(u, 13);
    assert_int_equal(e, 17);
    /* present */
    assert_true(cfg_get_str(root, "s", TRUE, &s, &err));
    assert_string_equal(s, "hello");
    assert_true(cfg_get_bool(root, "b", TRUE, &b, &err));
    assert_int_equal(b, TRUE);
    assert_true(cfg_get_int(root, "i", TRUE, -7, -7, &i, &err));
    assert_int_equal(i, -7);
    assert_true(cfg_get_double(root, "d", TRUE, 2.5, 2.5, &d, &err));
    assert_true(d == 2.5);
    assert_true(cfg_get_map(root, "m", TRUE, "a map", &m, &err));
    assert_string_equal(cfg_scalar(cfg_get(m, "x")), "1");
    assert_true(cfg_get_time(root, "t", TRUE, &t, &err));
    assert_int_equal(t, 3 * SIM_US);
    assert_true(cfg_get_size(root, "z", TRUE, &u, &err));
    assert_int_equal(u, 2048);
    assert_true(cfg_get_count(root, "c", TRUE, 16000, 16000, &u, &err));
    assert_int_equal(u, 16000);
    double w = 0, f = 0;
    assert_true(cfg_get_bandwidth(root, "w", TRUE, &w, &err));
    assert_true(w == 40e6);
    assert_true(cfg_get_freq(root, "f", TRUE, &f, &err));
    assert_true(f == 2e9);
    assert_true(cfg_get_enum(root, "e", TRUE, colours, &e, &err));
    assert_int_equal(e, 1);
    assert_null(err);
}

static void test_required_and_kinds(void **state)
{
    (void)state;
    GError *err = NULL;
    const char *s = NULL;
    const CfgNode *m = NULL;
    SimTime t = 0;
    assert_false(cfg_get_str(root, "none", TRUE, &s, &err));
    expect_msg(&err, "g.yaml:1:1: found no key 'none' in this map, expected "
                     "'none': a string");
    assert_false(cfg_get_str(NULL, "none", TRUE, &s, &err));
    expect_msg(&err, "found no key 'none' in this map, expected 'none': a "
                     "string");
    assert_true(cfg_get_str(NULL, "none", FALSE, &s, &err));
    assert_null(err);
    assert_false(cfg_get_str(cfg_get(root, "s"), "x", FALSE, &s, &err));
    expect_msg(&err, "g.yaml:1:4: found 'hello', expected a map");
    assert_false(cfg_get_str(root, "m", TRUE, &s, &err));
    expect_msg(&err, "g.yaml:5:4: found a map, expected a string");
    assert_false(cfg_get_str(root, "q", TRUE, &s, &err));
    expect_msg(&err, "g.yaml:6:4: found a sequence, expected a string");
    assert_false(cfg_get_str(root, "n", TRUE, &s, &err));
    expect_msg(&err, "g.yaml:13:3: found an empty value, expected a string");
    assert_false(cfg_get_map(root, "s", TRUE, "a map of things", &m, &err));
    expect_msg(&err, "g.yaml:1:4: found 'hello', expected a map of things");
    assert_false(cfg_get_time(root, "bad", TRUE, &t, &err));
    expect_msg(&err, "g.yaml:14:6: found '5 parsecs', expected a non-negative "
                     "time with a unit (ps, ns, us, \xc2\xb5s, ms, s, min, h)");
    assert_false(cfg_get_time(root, "none", TRUE, &t, &err));
    expect_msg(&err, "g.yaml:1:1: found no key 'none' in this map, expected "
                     "'none': a non-negative time with a unit (ps, ns, us, "
                     "\xc2\xb5s, ms, s, min, h)");
}

static void test_bool_words(void **state)
{
    (void)state;
    static const char *const yes[] = {"true", "True", "TRUE", "yes", "on"};
    static const char *const no[] = {"false", "False", "FALSE", "no", "off"};
    for (guint k = 0; k < 2; k++)
        for (guint i = 0; i < 5; i++) {
            char *text = g_strdup_printf("v: %s\n", k ? no[i] : yes[i]);
            GError *err = NULL;
            CfgNode *r = cfg_load_string(text, "b.yaml", &err);
            gboolean b = 5;
            assert_true(cfg_get_bool(r, "v", TRUE, &b, &err));
            assert_int_equal(b, k ? FALSE : TRUE);
            cfg_free(r);
            g_free(text);
        }
    GError *err = NULL;
    gboolean b = 5;
    assert_false(cfg_get_bool(root, "s", TRUE, &b, &err));
    expect_msg(&err, "g.yaml:1:4: found 'hello', expected true or false");
    assert_int_equal(b, 5);
}

static void test_int_double_ranges(void **state)
{
    (void)state;
    GError *err = NULL;
    int64_t i = 3;
    assert_false(cfg_get_int(root, "i", TRUE, -6, 10, &i, &err));
    expect_msg(&err, "g.yaml:3:4: found '-7', expected an integer in [-6, 10]");
    assert_false(cfg_get_int(root, "i", TRUE, 0, INT64_MAX, &i, &err));
    expect_msg(&err, "g.yaml:3:4: found '-7', expected an integer >= 0");
    assert_false(cfg_get_int(root, "d", TRUE, INT64_MIN, INT64_MAX, &i, &err));
    expect_msg(&err, "g.yaml:4:4: found '2.5', expected an integer");
    assert_false(cfg_get_int(root, "i", TRUE, -8, -8, &i, &err));
    g_clear_error(&err);
    assert_int_equal(i, 3);
    assert_true(cfg_get_int(root, "i", TRUE, INT64_MIN, -7, &i, &err));
    assert_int_equal(i, -7);
    double d = 1;
    assert_false(cfg_get_double(root, "d", TRUE, 0, 2.4, &d, &err));
    expect_msg(&err, "g.yaml:4:4: found '2.5', expected a number in [0, 2.4]");
    assert_false(cfg_get_double(root, "d", TRUE, 2.6, 3, &d, &err));
    expect_msg(&err, "g.yaml:4:4: found '2.5', expected a number in [2.6, 3]");
    assert_false(cfg_get_double(root, "t", TRUE, 0, 9, &d, &err));
    expect_msg(&err, "g.yaml:7:4: found '3 us', expected a number in [0, 9]");
    assert_true(d == 1);
    static const char *const bad[] = {"inf", "nan", "0x10", "1e999", "", "1.5x"};
    for (guint k = 0; k < G_N_ELEMENTS(bad); k++) {
        char *text = g_strdup_printf("v: '%s'\n", bad[k]);
        CfgNode *r = cfg_load_string(text, "d.yaml", &err);
        assert_false(cfg_get_double(r, "v", TRUE, -1e300, 1e300, &d, &err));
        g_clear_error(&err);
        cfg_free(r);
        g_free(text);
    }
    CfgNode *r = cfg_load_string("v: -1.25e2\n", "d.yaml", &err);
    assert_true(cfg_get_double(r, "v", TRUE, -125, -125, &d, &err));
    assert_true(d == -125.0);
    cfg_free(r);
}

static void test_count_enum(void **state)
{
    (void)state;
    GError *err = NULL;
    uint64_t u = 1;
    assert_false(cfg_get_count(root, "c", TRUE, 16001, 20000, &u, &err));
    expect_msg(&err, "g.yaml:11:4: found '16K', expected a count in "
                     "[16001, 20000]");
    assert_false(cfg_get_count(root, "c", TRUE, 0, 15999, &u, &err));
    expect_msg(&err, "g.yaml:11:4: found '16K', expected a count in "
                     "[0, 15999]");
    assert_false(cfg_get_count(root, "t", TRUE, 0, 9, &u, &err));
    expect_msg(&err, "g.yaml:7:4: found '3 us', expected a non-negative "
                     "integer, optionally with K (1e3) or M (1e6)");
    assert_false(cfg_get_count(root, "none", TRUE, 0, 9, &u, &err));
    g_clear_error(&err);
    assert_int_equal(u, 1);
    static const char *const words[] = {"red", "blue", NULL};
    int e = 4;
    assert_false(cfg_get_enum(root, "e", TRUE, words, &e, &err));
    expect_msg(&err, "g.yaml:12:4: found 'green', expected one of: red, blue");
    assert_int_equal(e, 4);
    static const char *const first[] = {"green", NULL};
    assert_true(cfg_get_enum(root, "e", TRUE, first, &e, &err));
    assert_int_equal(e, 0);
}

static void test_units_getters_refuse(void **state)
{
    (void)state;
    GError *err = NULL;
    uint64_t u = 0;
    double x = 0;
    assert_false(cfg_get_size(root, "t", TRUE, &u, &err));
    expect_msg(&err, "g.yaml:7:4: found '3 us', expected a non-negative size "
                     "with a unit (B, kB, KB, MB, GB, TB, KiB, MiB, GiB, TiB)");
    assert_false(cfg_get_bandwidth(root, "f", TRUE, &x, &err));
    expect_msg(&err, "g.yaml:10:4: found '2 GHz', expected a non-negative "
                     "bandwidth with a unit (B/s, kB/s, MB/s, GB/s, MBps, "
                     "KiB/s, MiB/s, GiB/s, bit/s, Mbit/s, Gbit/s, Mb/s, Gbps "
                     "...)");
    assert_false(cfg_get_freq(root, "w", TRUE, &x, &err));
    expect_msg(&err, "g.yaml:9:4: found '40 MB/s', expected a non-negative "
                     "frequency with a unit (Hz, kHz, MHz, GHz)");
    assert_false(cfg_get_bandwidth(root, "none", TRUE, &x, &err));
    g_clear_error(&err);
    assert_true(x == 0);
    assert_int_equal(u, 0);
}

static void test_flags(void **state)
{
    (void)state;
    GError *err = NULL;
    uint64_t u = 0;
    double x = 0;
    SimTime t = 0;
    assert_true(cfg_parse_count("2M", "--n", &u, &err));
    assert_int_equal(u, 2000000);
    assert_true(cfg_parse_size("3 KiB", "--b", &u, &err));
    assert_int_equal(u, 3072);
    assert_true(cfg_parse_time("2 ns", "--t", &t, &err));
    assert_int_equal(t, 2000);
    assert_true(cfg_parse_bandwidth("8 Mbit/s", "--w", &x, &err));
    assert_true(x == 1e6);
    assert_null(err);
    assert_false(cfg_parse_size("1.5 B", "--bytes", &u, &err));
    expect_msg(&err, "--bytes: found '1.5 B', expected a whole number of "
                     "bytes");
    assert_false(cfg_parse_bandwidth("0.5 B/s", "--bw", &x, &err));
    expect_msg(&err, "--bw: found '0.5 B/s', expected 0 or at least 1 B/s");
    assert_false(cfg_parse_time("1e30 s", "--t", &t, &err));
    expect_msg(&err, "--t: found '1e30 s', expected a time below 2^64 ps "
                     "(about 213 days)");
    assert_false(cfg_parse_count("x", "--n", &u, &err));
    expect_msg(&err, "--n: found 'x', expected a non-negative integer, "
                     "optionally with K (1e3) or M (1e6)");
}

/* Values up to 60 characters are quoted whole; longer ones are cut to
 * 57 characters (not bytes) and "...". */
static void test_describe(void **state)
{
    (void)state;
    GError *err = NULL;
    char sixty[61], sixty1[62];
    memset(sixty, 'a', 60);
    sixty[60] = '\0';
    memset(sixty1, 'b', 61);
    sixty1[61] = '\0';
    char *text = g_strdup_printf("a: %s\nb: %s\nc: \xc3\xa9%s\n", sixty,
                                 sixty1, sixty1);
    CfgNode *r = cfg_load_string(text, "l.yaml", &err);
    char *da = cfg_describe(cfg_get(r, "a"));
    char *want = g_strdup_printf("'%s'", sixty);
    assert_string_equal(da, want);
    char *db = cfg_describe(cfg_get(r, "b"));
    assert_int_equal(strlen(db), 1 + 57 + 4);
    assert_true(g_str_has_prefix(db, "'bbbb") && g_str_has_suffix(db, "b...'"));
    char *dc = cfg_describe(cfg_get(r, "c"));
    assert_int_equal(g_utf8_strlen(dc, -1), 1 + 57 + 4);
    assert_true(g_str_has_prefix(dc, "'\xc3\xa9"));
    char *dm = cfg_describe(root);
    assert_string_equal(dm, "a map");
    g_free(da);
    g_free(want);
    g_free(db);
    g_free(dc);
    g_free(dm);
    cfg_free(r);
    g_free(text);
}

static const char *at(const CfgNode *r, const char *path)
{
    const char *v = cfg_scalar(cfg_path(r, path));
    return v ? v : "(none)";
}

/* --set: an index within a sequence, a new path of maps, a replaced
 * value; refusals of a bad path, an index past the end and a key below a
 * scalar, located at the override. */
static void test_override(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *r = cfg_load_string("q: [1, 2]\ns: x\nm: {a: 1}\n", "o.yaml", &err);
    assert_true(cfg_set_override(r, "q.1=9", &err));
    assert_string_equal(at(r, "q.1"), "9");
    assert_string_equal(at(r, "q.0"), "1");
    assert_true(cfg_set_override(r, "q.0=7", &err));
    assert_string_equal(at(r, "q.0"), "7");
    assert_true(cfg_set_override(r, "new.deep.key=3", &err));
    assert_string_equal(at(r, "new.deep.key"), "3");
    assert_true(cfg_set_override(r, "m.b=4", &err));
    assert_string_equal(at(r, "m.a"), "1");
    assert_string_equal(at(r, "m.b"), "4");
    assert_true(cfg_set_override(r, "m.a=[5, 6]", &err));
    assert_string_equal(at(r, "m.a.1"), "6");
    assert_false(cfg_set_override(r, "q.2=9", &err));
    expect_msg(&err, "--set q.2=9:1:1: found '2' below a sequence, expected "
                     "an index in range");
    assert_false(cfg_set_override(r, "s.x=1", &err));
    expect_msg(&err, "--set s.x=1:1:1: found 'x' below a scalar, expected a "
                     "path through maps");
    static const char *const bad[] = {"noequals", "=5", "a..b=1", "a b=1",
                                      ".a=1", "a.=1"};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        assert_false(cfg_set_override(r, bad[i], &err));
        char *want = g_strdup_printf("--set: found '%s', expected "
                                     "key.path=value", bad[i]);
        expect_msg(&err, want);
        g_free(want);
    }
    assert_true(cfg_set_override(r, "A_z-9=1", &err));
    assert_string_equal(at(r, "A_z-9"), "1");
    cfg_free(r);
}

/* Maps merge key by key (recursively); anything else replaces. */
static void test_merge(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *base = cfg_load_string("a: 1\nm: {x: 1, y: 2, k: {p: 1}}\nq: [1]\n",
                                    "b.yaml", &err);
    CfgNode *over = cfg_load_string("m: {y: 3, z: 4, k: {r: 2}}\nb: 5\n"
                                    "q: [7, 8]\n", "o.yaml", &err);
    cfg_merge(base, over);
    assert_string_equal(at(base, "a"), "1");
    assert_string_equal(at(base, "m.x"), "1");
    assert_string_equal(at(base, "m.y"), "3");
    assert_string_equal(at(base, "m.z"), "4");
    assert_string_equal(at(base, "m.k.p"), "1");
    assert_string_equal(at(base, "m.k.r"), "2");
    assert_string_equal(at(base, "b"), "5");
    assert_string_equal(at(base, "q.1"), "8");
    assert_string_equal(cfg_file(cfg_path(base, "m.z")), "o.yaml");
    cfg_free(base);
    cfg_free(over);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_absent_and_present),
        cmocka_unit_test(test_required_and_kinds),
        cmocka_unit_test(test_bool_words),
        cmocka_unit_test(test_int_double_ranges),
        cmocka_unit_test(test_count_enum),
        cmocka_unit_test(test_units_getters_refuse),
        cmocka_unit_test(test_flags),
        cmocka_unit_test(test_describe),
        cmocka_unit_test(test_override),
        cmocka_unit_test(test_merge),
    };
    return cmocka_run_group_tests_name("cfg_get", tests, setup, teardown);
}
