/* test_cfg.c — YAML trees with locations, typed getters, unknown keys,
 * overrides and merging.  Every error is checked for its exact location. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "tests/support.h"

static const char *doc = "schema_version: 1\n"          /* 1 */
                         "machine:\n"                   /* 2 */
                         "  links:\n"                   /* 3 */
                         "    bandwidth: 640 MB/s\n"    /* 4 */
                         "    latency: 350us\n"         /* 5 */
                         "  nodes: 16K\n"               /* 6 */
                         "  clock: 1.5 GHz\n"           /* 7 */
                         "  memory: 64KiB\n"            /* 8 */
                         "run:\n"                       /* 9 */
                         "  seed: 42\n"                 /* 10 */
                         "  fast: true\n"               /* 11 */
                         "  ratio: 0.25\n"              /* 12 */
                         "  fidelity: flow\n"           /* 13 */
                         "  list: [1, 'two', {a: 3}]\n" /* 14 */
                         "  nothing:\n";                /* 15 */

static CfgNode *load(const char *text)
{
    GError *e = NULL;
    CfgNode *n = cfg_load_string(text, "t.yaml", &e);
    if (!n)
        fail_msg("load failed: %s", e->message);
    return n;
}

/* Loads text expecting failure; checks the message starts with `msg`. */
static void load_fails(const char *text, const char *msg)
{
    GError *e = NULL;
    CfgNode *n = cfg_load_string(text, "t.yaml", &e);
    assert_null(n);
    assert_non_null(e);
    assert_int_equal(sim_error_exit_status(e), 2);
    if (strncmp(e->message, msg, strlen(msg)) != 0)
        fail_msg("got '%s', want prefix '%s'", e->message, msg);
    g_error_free(e);
}

static void assert_err(GError **e, const char *msg)
{
    assert_non_null(*e);
    assert_int_equal(sim_error_exit_status(*e), 2);
    if (strcmp((*e)->message, msg) != 0)
        fail_msg("got '%s', want '%s'", (*e)->message, msg);
    g_clear_error(e);
}

static void test_tree_and_locations(void **state)
{
    (void)state;
    CfgNode *r = load(doc);
    assert_int_equal(cfg_kind(r), CFG_MAP);
    assert_int_equal(cfg_map_len(r), 3);
    const CfgNode *bw = cfg_path(r, "machine.links.bandwidth");
    assert_string_equal(cfg_scalar(bw), "640 MB/s");
    assert_string_equal(cfg_file(bw), "t.yaml");
    assert_int_equal(cfg_line(bw), 4);
    assert_int_equal(cfg_col(bw), 16);
    const CfgNode *list = cfg_path(r, "run.list");
    assert_int_equal(cfg_kind(list), CFG_SEQ);
    assert_int_equal(cfg_seq_len(list), 3);
    assert_string_equal(cfg_scalar(cfg_seq_at(list, 1)), "two");
    assert_int_equal(cfg_col(cfg_seq_at(list, 1)), 13);
    assert_string_equal(cfg_scalar(cfg_path(r, "run.list.2.a")), "3");
    assert_string_equal(cfg_scalar(cfg_path(r, "run.list.0")), "1");
    assert_null(cfg_path(r, "run.list.3"));
    assert_null(cfg_path(r, "run.seed.x"));
    assert_int_equal(cfg_kind(cfg_path(r, "run.nothing")), CFG_NULL);
    assert_null(cfg_scalar(cfg_path(r, "run.nothing")));
    assert_string_equal(cfg_map_key(r, 0), "schema_version");
    assert_string_equal(cfg_scalar(cfg_map_value(r, 0)), "1");
    CfgNode *c = cfg_copy(r);
    cfg_free(r);
    assert_int_equal(cfg_line(cfg_path(c, "run.seed")), 10);
    cfg_free(c);
    cfg_free(NULL);
}

static void test_getters(void **state)
{
    (void)state;
    CfgNode *r = load(doc);
    const CfgNode *m = cfg_get(r, "machine"), *run = cfg_get(r, "run");
    GError *e = NULL;
    double bw = 0, hz = 0, ratio = 0;
    SimTime lat = 0;
    uint64_t nodes = 0, mem = 0;
    int64_t seed = 0;
    gboolean fast = FALSE;
    int fid = -1;
    const char *s = NULL;
    const char *const fids[] = {"analytic", "flow", "packet", NULL};
    assert_true(
        cfg_get_bandwidth(cfg_get(m, "links"), "bandwidth", TRUE, &bw, &e));
    assert_true(bw == 640e6);
    assert_true(cfg_get_time(cfg_get(m, "links"), "latency", TRUE, &lat, &e));
    assert_int_equal(lat, 350 * SIM_US);
    assert_true(cfg_get_count(m, "nodes", TRUE, 1, 1 << 20, &nodes, &e));
    assert_int_equal(nodes, 16000);
    assert_true(cfg_get_freq(m, "clock", TRUE, &hz, &e));
    assert_true(hz == 1.5e9);
    assert_true(cfg_get_size(m, "memory", TRUE, &mem, &e));
    assert_int_equal(mem, 65536);
    assert_true(cfg_get_int(run, "seed", TRUE, 0, 100, &seed, &e));
    assert_int_equal(seed, 42);
    assert_true(cfg_get_bool(run, "fast", TRUE, &fast, &e));
    assert_true(fast);
    assert_true(cfg_get_double(run, "ratio", TRUE, 0, 1, &ratio, &e));
    assert_true(ratio == 0.25);
    assert_true(cfg_get_enum(run, "fidelity", TRUE, fids, &fid, &e));
    assert_int_equal(fid, 1);
    assert_true(cfg_get_str(run, "fidelity", TRUE, &s, &e));
    assert_string_equal(s, "flow");
    /* absent optional keys keep the default */
    seed = 7;
    assert_true(cfg_get_int(run, "absent", FALSE, 0, 100, &seed, &e));
    assert_int_equal(seed, 7);
    assert_null(e);
    cfg_free(r);
}

static void test_getter_errors(void **state)
{
    (void)state;
    CfgNode *r = load(doc);
    const CfgNode *run = cfg_get(r, "run"), *m = cfg_get(r, "machine");
    GError *e = NULL;
    int64_t i = 0;
    uint64_t u = 0;
    double d = 0;
    SimTime t = 0;
    gboolean b;
    int k;
    const char *const words[] = {"analytic", "packet", NULL};
    assert_false(cfg_get_int(run, "seed", TRUE, 0, 10, &i, &e));
    assert_err(&e, "t.yaml:10:9: found '42', expected an integer in [0, 10]");
    assert_false(cfg_get_int(run, "ratio", TRUE, 0, 10, &i, &e));
    assert_err(&e, "t.yaml:12:10: found '0.25', expected an integer in "
                   "[0, 10]");
    assert_false(cfg_get_int(run, "list", TRUE, 0, 10, &i, &e));
    assert_err(&e, "t.yaml:14:9: found a sequence, expected an integer in "
                   "[0, 10]");
    assert_false(cfg_get_int(run, "frames", TRUE, 1, INT64_MAX, &i, &e));
    assert_err(&e, "t.yaml:10:3: found no key 'frames' in this map, "
                   "expected 'frames': an integer >= 1");
    assert_false(cfg_get_bool(run, "seed", TRUE, &b, &e));
    assert_err(&e, "t.yaml:10:9: found '42', expected true or false");
    assert_false(cfg_get_double(run, "ratio", TRUE, 0.5, 1, &d, &e));
    assert_err(&e, "t.yaml:12:10: found '0.25', expected a number in "
                   "[0.5, 1]");
    assert_false(cfg_get_enum(run, "fidelity", TRUE, words, &k, &e));
    assert_err(&e, "t.yaml:13:13: found 'flow', expected one of: analytic, "
                   "packet");
    assert_false(cfg_get_count(m, "nodes", TRUE, 1, 1024, &u, &e));
    assert_err(&e, "t.yaml:6:10: found '16K', expected a count in "
                   "[1, 1024]");
    assert_false(cfg_get_time(m, "clock", TRUE, &t, &e));
    assert_err(&e, "t.yaml:7:10: found '1.5 GHz', expected a non-negative "
                   "time with a unit (ps, ns, us, \xc2\xb5s, ms, s, min, h)");
    assert_false(cfg_get_str(run, "nothing", TRUE, NULL, &e));
    assert_err(&e, "t.yaml:15:11: found an empty value, expected a string");
    assert_false(cfg_get_size(run, "seed", FALSE, &u, &e));
    assert_non_null(strstr(e->message, "t.yaml:10:9: found '42', expected "
                                       "a non-negative size"));
    g_clear_error(&e);
    cfg_free(r);
}

static void test_unknown_keys(void **state)
{
    (void)state;
    CfgNode *r = load("a: 1\nsub:\n  x: 1\n  y: [ {p: 1, q: 2} ]\n");
    GError *e = NULL;
    int64_t v;
    assert_true(cfg_get_int(r, "a", TRUE, 0, 9, &v, &e));
    assert_false(cfg_check_unused(r, &e));
    assert_err(&e, "t.yaml:2:1: found unknown key 'sub', expected one of: a");
    const CfgNode *sub = cfg_get(r, "sub");
    assert_true(cfg_get_int(sub, "x", TRUE, 0, 9, &v, &e));
    assert_true(cfg_get_int(sub, "z", FALSE, 0, 9, &v, &e));
    const char *const skip[] = {"sub", NULL};
    assert_true(cfg_check_unused_except(r, skip, &e));
    assert_false(cfg_check_unused(r, &e));
    assert_err(&e, "t.yaml:4:3: found unknown key 'y', expected one of: x, z");
    const CfgNode *y = cfg_get(sub, "y");
    assert_true(cfg_get_int(cfg_seq_at(y, 0), "p", TRUE, 0, 9, &v, &e));
    assert_false(cfg_check_unused(r, &e));
    assert_err(&e, "t.yaml:4:15: found unknown key 'q', expected one of: p");
    cfg_mark_read(y);
    assert_true(cfg_check_unused(r, &e));
    cfg_free(r);
}

static void test_load_errors(void **state)
{
    (void)state;
    load_fails("a: 1\nb: 2\na: 3\n",
               "t.yaml:3:1: found duplicate key 'a' "
               "(first at line 1), expected each key once per map");
    load_fails("a: [1, 2\nb: 3\n", "t.yaml:");
    load_fails("a: b: c\n", "t.yaml:1:5: found YAML syntax error");
    load_fails("a: 1\n---\nb: 2\n", "t.yaml:2:1: found a second YAML "
                                    "document");
    load_fails("a: *nope\n", "t.yaml:1:4: found alias '*nope'");
    /* a syntax error before the first node: the document start fails */
    load_fails("]\n", "t.yaml:1:1: found YAML syntax error");
    load_fails("base: &b {x: 1}\nd:\n  <<: *b\n", "t.yaml:3:3: found "
                                                  "merge key '<<'");
    GString *deep = g_string_new("");
    for (int i = 0; i < 300; i++)
        g_string_append_c(deep, '[');
    load_fails(deep->str, "t.yaml:1:");
    g_string_free(deep, TRUE);
    GString *bomb = g_string_new("a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n");
    for (int i = 1; i < 8; i++)
        g_string_append_printf(bomb,
                               "a%d: &a%d [*a%d, *a%d, *a%d, *a%d, "
                               "*a%d, *a%d, *a%d, *a%d, *a%d, *a%d]\n",
                               i, i, i - 1, i - 1, i - 1, i - 1, i - 1, i - 1,
                               i - 1, i - 1, i - 1, i - 1);
    load_fails(bomb->str, "t.yaml:");
    g_string_free(bomb, TRUE);
    GError *e = NULL;
    assert_null(cfg_load_file("/nonexistent/x.yaml", &e));
    assert_int_equal(sim_error_exit_status(e), 2);
    assert_non_null(strstr(e->message, "/nonexistent/x.yaml:0:0: found an "
                                       "unreadable file"));
    g_clear_error(&e);
    CfgNode *empty = load("");
    assert_int_equal(cfg_kind(empty), CFG_NULL);
    cfg_free(empty);
    CfgNode *al = load("a: &x {p: 1}\nb: *x\n");
    assert_string_equal(cfg_scalar(cfg_path(al, "b.p")), "1");
    assert_int_equal(cfg_line(cfg_path(al, "b")), 2);
    cfg_free(al);
}

static void test_overrides(void **state)
{
    (void)state;
    CfgNode *r = load(doc);
    GError *e = NULL;
    assert_true(cfg_set_override(r, "run.seed=7", &e));
    assert_string_equal(cfg_scalar(cfg_path(r, "run.seed")), "7");
    assert_true(cfg_set_override(r, "machine.links.bandwidth=2.8MB/s", &e));
    double bw = 0;
    assert_true(cfg_get_bandwidth(cfg_path(r, "machine.links"), "bandwidth",
                                  TRUE, &bw, &e));
    assert_true(bw == 2.8e6);
    assert_true(cfg_set_override(r, "new.deep.key=[1, 2]", &e));
    assert_int_equal(cfg_seq_len(cfg_path(r, "new.deep.key")), 2);
    assert_true(cfg_set_override(r, "run.list.1={b: 2}", &e));
    assert_string_equal(cfg_scalar(cfg_path(r, "run.list.1.b")), "2");
    assert_true(cfg_set_override(r, "run.list.0=zero", &e)); /* first item */
    assert_string_equal(cfg_scalar(cfg_path(r, "run.list.0")), "zero");
    assert_int_equal(cfg_seq_len(cfg_path(r, "run.list")), 3);
    assert_true(cfg_set_override(r, "run.fast=", &e));
    assert_int_equal(cfg_kind(cfg_path(r, "run.fast")), CFG_NULL);
    /* errors name the override */
    assert_false(cfg_set_override(r, "run.seed", &e));
    assert_err(&e, "--set: found 'run.seed', expected key.path=value");
    assert_false(cfg_set_override(r, "run..seed=1", &e));
    assert_err(&e, "--set: found 'run..seed=1', expected key.path=value");
    assert_false(cfg_set_override(r, "run.seed.x=1", &e));
    assert_err(&e, "--set run.seed.x=1:1:1: found 'x' below a scalar, "
                   "expected a path through maps");
    assert_false(cfg_set_override(r, "run.list.9=1", &e));
    assert_err(&e, "--set run.list.9=1:1:1: found '9' below a sequence, "
                   "expected an index in range");
    assert_false(cfg_set_override(r, "run.list.3=1", &e)); /* one past */
    assert_err(&e, "--set run.list.3=1:1:1: found '3' below a sequence, "
                   "expected an index in range");
    assert_false(cfg_set_override(r, "run.seed=[1", &e));
    assert_non_null(strstr(e->message, "--set run.seed=[1:"));
    g_clear_error(&e);
    /* a value from an override is located at the override */
    assert_true(cfg_set_override(r, "run.ratio=x", &e));
    double d;
    assert_false(
        cfg_get_double(cfg_get(r, "run"), "ratio", TRUE, 0, 1, &d, &e));
    assert_err(&e, "--set run.ratio=x:1:1: found 'x', expected a number in "
                   "[0, 1]");
    cfg_free(r);
}

static void test_merge(void **state)
{
    (void)state;
    CfgNode *base = load("a: 1\nm: {x: 1, y: 2}\ns: [1, 2]\n");
    GError *e = NULL;
    CfgNode *over =
        cfg_load_string("m: {y: 3, z: 4}\ns: [9]\nb: 5\n", "o.yaml", &e);
    cfg_merge(base, over);
    cfg_free(over);
    assert_string_equal(cfg_scalar(cfg_path(base, "a")), "1");
    assert_string_equal(cfg_scalar(cfg_path(base, "m.x")), "1");
    assert_string_equal(cfg_scalar(cfg_path(base, "m.y")), "3");
    assert_string_equal(cfg_file(cfg_path(base, "m.y")), "o.yaml");
    assert_string_equal(cfg_scalar(cfg_path(base, "m.z")), "4");
    assert_int_equal(cfg_seq_len(cfg_path(base, "s")), 1);
    assert_string_equal(cfg_scalar(cfg_path(base, "b")), "5");
    cfg_free(base);
    /* unknown keys that came from the override are located there */
    base = load("m: {x: 1, y: 2}\n");
    over = cfg_load_string("m: {y: 3, z: 4}\n", "o.yaml", &e);
    cfg_merge(base, over);
    cfg_free(over);
    const CfgNode *m = cfg_get(base, "m");
    assert_false(cfg_check_unused(m, &e));
    assert_err(&e, "t.yaml:1:5: found unknown key 'x', expected no key here "
                   "(nothing reads this map)");
    assert_non_null(cfg_get(m, "x"));
    assert_non_null(cfg_get(m, "y"));
    assert_false(cfg_check_unused(m, &e));
    assert_err(&e, "o.yaml:1:11: found unknown key 'z', expected one of: x, "
                   "y");
    /* a non-map replaces the whole node */
    over = load("7");
    cfg_merge(base, over);
    cfg_free(over);
    assert_string_equal(cfg_scalar(base), "7");
    cfg_free(base);
}

static void test_get_map(void **state)
{
    (void)state;
    CfgNode *n = load("m: {a: 1}\ns: 3\n");
    const CfgNode *out = NULL;
    GError *e = NULL;
    assert_true(cfg_get_map(n, "m", TRUE, "a map {a}", &out, &e));
    assert_non_null(out);
    assert_string_equal(cfg_scalar(cfg_get(out, "a")), "1");
    assert_true(cfg_get_map(n, "absent", FALSE, "a map {a}", &out, &e));
    assert_null(out);
    assert_false(cfg_get_map(n, "absent", TRUE, "a map {a}", &out, &e));
    assert_err(&e, "t.yaml:1:1: found no key 'absent' in this map, "
                   "expected 'absent': a map {a}");
    assert_false(cfg_get_map(n, "s", FALSE, "a map {a}", &out, &e));
    assert_err(&e, "t.yaml:2:4: found '3', expected a map {a}");
    cfg_free(n);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tree_and_locations),
        cmocka_unit_test(test_getters),
        cmocka_unit_test(test_getter_errors),
        cmocka_unit_test(test_unknown_keys),
        cmocka_unit_test(test_load_errors),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_merge),
        cmocka_unit_test(test_get_map),
    };
    return cmocka_run_group_tests_name("cfg", tests, NULL, NULL);
}
