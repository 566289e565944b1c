/* test_partition_split.c — the counts mach_partition() gives the kinds of
 * a machine, worked out by hand from partition.c's rule (one each to the
 * scalable kinds, the rest by largest remainder of rest * count / sum,
 * ties to the earlier kind; kinds of one processor stay, unless no kind
 * has more, when the first largest scales), on inline models; the least N
 * and the message below it; the CM-200's widest kind. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/partition.h"
#include "tests/support.h"

/* An inline crossbar machine with the given node kinds (YAML flow map
 * body, e.g. "a: {count: 1}, b: {count: 3}"). */
static CfgNode *machine(const char *kinds, const char *topology)
{
    GError *err = NULL;
    char *text = g_strdup_printf(
        "machine:\n  provenance: assumption\n  name: t\n"
        "  nodes: {%s}\n"
        "  network: {topology: %s, bandwidth: 1 MB/s}\n",
        kinds, topology);
    CfgNode *root = cfg_load_string(text, "run.yaml", &err);
    g_free(text);
    assert_non_null(root);
    return root;
}

/* Each "name count" of the description is the count the partition set
 * (a --set override when it differs from the model's, the model's own
 * count otherwise). */
static void check_applied(const CfgNode *root, const char *desc)
{
    char **parts = g_strsplit(desc, ", ", -1);
    for (char **p = parts; *p; p++) {
        char **kv = g_strsplit(*p, " ", 2);
        char *path = g_strdup_printf("machine.nodes.%s.count", kv[0]);
        const CfgNode *c = cfg_path(root, path);
        if (cfg_kind(c) == CFG_MAP)
            c = cfg_get(c, "value");
        assert_non_null(c);
        assert_string_equal(cfg_scalar(c), kv[1]);
        g_free(path);
        g_strfreev(kv);
    }
    g_strfreev(parts);
}

/* Partitions to n; the description, or the error message (owned). */
static char *split_desc(const char *kinds, guint n, gboolean *ok)
{
    CfgNode *root = machine(kinds, "crossbar");
    GError *err = NULL;
    char *desc = NULL;
    *ok = mach_partition(root, n, &desc, &err);
    if (*ok)
        check_applied(root, desc);
    char *out = *ok ? desc : g_strdup(err->message);
    if (!*ok) {
        assert_null(desc);
        g_error_free(err);
    }
    cfg_free(root);
    return out;
}

static void expect_split(const char *kinds, guint n, const char *want)
{
    gboolean ok;
    char *got = split_desc(kinds, n, &ok);
    if (!ok || strcmp(got, want) != 0)
        fail_msg("%s to %u: got '%s', want '%s'", kinds, n, got, want);
    g_free(got);
}

static void test_largest_remainder(void **state)
{
    (void)state;
    /* a stays 1; rest 19: b and c one each, then 17 x 3/9 = 5 r 6 and
     * 17 x 6/9 = 11 r 3, one extra to the larger remainder (b) */
    expect_split("a: {count: 1}, b: {count: 3}, c: {count: 6}", 20,
                 "a 1, b 7, c 12");
    /* the model's own counts come back when N is their sum */
    expect_split("a: {count: 1}, b: {count: 3}, c: {count: 6}", 10,
                 "a 1, b 3, c 6");
    /* equal remainders: the earlier kind gets the extra (3 x 2/4 = 1 r 2
     * each) */
    expect_split("b: {count: 2}, c: {count: 2}", 5, "b 3, c 2");
    expect_split("c: {count: 2}, b: {count: 2}", 5, "c 3, b 2");
    /* a: 4 x 2/8 = 1 r 0; b, c: 4 x 3/8 = 1 r 4; the one extra goes to b,
     * never to a kind whose share came out exact */
    expect_split("a: {count: 2}, b: {count: 3}, c: {count: 3}", 7,
                 "a 2, b 3, c 2");
    /* exact shares: no extras */
    expect_split("b: {count: 2}, c: {count: 6}", 10, "b 3, c 7");
    /* the least N: one of each scalable kind plus the single ones */
    expect_split("a: {count: 1}, b: {count: 3}, c: {count: 6}", 3,
                 "a 1, b 1, c 1");
}

/* No kind of more than one processor: the first largest scales (the
 * first, on a tie), the others stay. */
static void test_single_kinds(void **state)
{
    (void)state;
    expect_split("x: {count: 1}, y: {count: 1}", 6, "x 5, y 1");
    expect_split("x: {count: 0}, y: {count: 1}", 6, "x 0, y 6");
    expect_split("x: {count: 1}", 4, "x 4");
    expect_split("x: {count: 0}, y: {count: 0}", 3, "x 3, y 0");
}

static void test_too_few(void **state)
{
    (void)state;
    gboolean ok;
    char *msg = split_desc("a: {count: 1}, b: {count: 3}, c: {count: 6}", 2,
                           &ok);
    assert_false(ok);
    assert_string_equal(msg, "found 2 nodes for a crossbar, expected at least "
                             "3 (the single-processor kinds plus one of each "
                             "other kind)");
    g_free(msg);
    msg = split_desc("x: {count: 1}, y: {count: 1}", 1, &ok);
    assert_false(ok);
    assert_non_null(strstr(msg, "found 1 nodes for a crossbar, expected at "
                                "least 2 "));
    g_free(msg);
    /* a kind whose name no --set path can spell is refused by the model
     * check, at the kind, not skipped */
    msg = split_desc("a b: {count: 2}, c: {count: 2}", 6, &ok);
    assert_false(ok);
    assert_string_equal(msg, "run.yaml:4:16: found node kind name 'a b', "
                             "expected a name of letters, digits, '_' and "
                             "'-' (a step of --set machine.nodes.KIND.count)");
    g_free(msg);
    CfgNode *root = cfg_load_string("run: {}\n", "run.yaml", NULL);
    GError *err = NULL;
    char *desc = (char *)"x";
    assert_false(mach_partition(root, 4, &desc, &err));
    assert_null(desc);
    assert_string_equal(err->message, "found a config without machine:, "
                                      "expected machine: {model: NAME}");
    g_clear_error(&err);
    cfg_free(root);
}

/* CM-200: the widest kind takes the lanes; a kind without `lanes` counts
 * as one lane, so an array of two lanes is still the widest. */
static void test_widest_kind(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine:\n  model: cm200\n  nodes: {array: {lanes: 2}}\n",
        "run.yaml", &err);
    char *desc = NULL;
    assert_true(mach_partition(root, 32, &desc, &err));
    assert_string_equal(desc, "array lanes 32 = 2 routers x 16");
    assert_string_equal(cfg_scalar(cfg_path(root, "machine.nodes.array.lanes")),
                        "32");
    assert_null(cfg_path(root, "machine.nodes.front_end.lanes"));
    g_free(desc);
    cfg_free(root);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_largest_remainder),
        cmocka_unit_test(test_single_kinds),
        cmocka_unit_test(test_too_few),
        cmocka_unit_test(test_widest_kind),
    };
    return cmocka_run_group_tests_name("partition_split", tests, support_test_models,
                                       NULL);
}
