/* test_partition_edges.c — mach_partition() on inline models at its
 * edges: a partition to the model's own size overrides nothing; a
 * hypercube's stated dimension follows a power-of-two N (and only then);
 * the CM-200 rule picks the first of equally wide kinds, counts a kind
 * without `lanes` as one lane, sets router_nodes when the model states it,
 * and refuses lanes that are not procs_per_router x a power of two, and
 * (through the model check) a kind name that is no step of a key path. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/partition.h"
#include "tests/support.h"

static CfgNode *machine(const char *kinds, const char *network)
{
    GError *err = NULL;
    char *text = g_strdup_printf("machine:\n  provenance: assumption\n"
                                 "  name: t\n  nodes: {%s}\n"
                                 "  network: {%s}\n",
                                 kinds, network);
    CfgNode *root = cfg_load_string(text, "run.yaml", &err);
    g_free(text);
    assert_non_null(root);
    return root;
}

/* The partition's description, or NULL with *msg the error. */
static char *part(CfgNode *root, guint n, char **msg)
{
    GError *err = NULL;
    char *desc = NULL;
    gboolean ok = mach_partition(root, n, &desc, &err);
    assert_true(ok == (err == NULL));
    *msg = err ? g_strdup(err->message) : NULL;
    g_clear_error(&err);
    return desc;
}

static const char *at(const CfgNode *root, const char *path)
{
    const CfgNode *c = cfg_path(root, path);
    if (cfg_kind(c) == CFG_MAP)
        c = cfg_get(c, "value");
    return c ? cfg_scalar(c) : NULL;
}

#define NET "topology: crossbar, bandwidth: 1 MB/s"

static void test_own_size_overrides_nothing(void **state)
{
    (void)state;
    CfgNode *root = machine("a: {count: 3}, b: {count: 5}", NET);
    char *msg = NULL, *desc = part(root, 8, &msg);
    assert_string_equal(desc, "a 3, b 5");
    /* the partition wrote no count: the section's nodes are the model's */
    assert_string_equal(at(root, "machine.nodes.a.count"), "3");
    assert_string_equal(at(root, "machine.nodes.b.count"), "5");
    const CfgNode *a = cfg_path(root, "machine.nodes.a");
    assert_int_equal(cfg_map_len(a), 1);
    g_free(desc);
    desc = part(root, 16, &msg);
    assert_string_equal(desc, "a 6, b 10");
    assert_string_equal(at(root, "machine.nodes.a.count"), "6");
    g_free(desc);
    cfg_free(root);
}

static void test_hypercube_dimension(void **state)
{
    (void)state;
    static const struct {
        guint n;
        const char *dim;
    } cases[] = {{8, "3"}, {1, "0"}, {2, "1"}, {16, "4"}, {6, "2"}, {7, "2"}};
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        CfgNode *root = machine("node: {count: 4}",
                                "topology: hypercube, bandwidth: 1 MB/s, "
                                "dimension: 2");
        char *msg = NULL, *desc = part(root, cases[i].n, &msg);
        if (!desc)
            fail_msg("%u: %s", cases[i].n, msg);
        const char *d = at(root, "machine.network.dimension");
        if (g_strcmp0(d, cases[i].dim) != 0)
            fail_msg("%u nodes: dimension %s, want %s", cases[i].n, d,
                     cases[i].dim);
        g_free(desc);
        cfg_free(root);
    }
    /* without a stated dimension none is added */
    CfgNode *root = machine("node: {count: 4}", NET);
    char *msg = NULL, *desc = part(root, 8, &msg);
    assert_null(cfg_path(root, "machine.network.dimension"));
    g_free(desc);
    cfg_free(root);
}

#define CM "topology: cm-router, bandwidth: 1 MB/s, procs_per_router: 4"

static void test_cm_widest(void **state)
{
    (void)state;
    static const struct {
        const char *kinds;
        const char *desc;
    } cases[] = {
        {"front: {count: 1, lanes: 4}, back: {count: 1, lanes: 4}",
         "front lanes 16 = 4 routers x 4"},
        {"front: {count: 1}, back: {count: 1, lanes: 1}",
         "front lanes 16 = 4 routers x 4"},
        {"front: {count: 1, lanes: 2}, back: {count: 1, lanes: 3}",
         "back lanes 16 = 4 routers x 4"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        CfgNode *root = machine(cases[i].kinds, CM);
        char *msg = NULL, *desc = part(root, 16, &msg);
        if (!desc)
            fail_msg("%s: %s", cases[i].kinds, msg);
        assert_string_equal(desc, cases[i].desc);
        g_free(desc);
        cfg_free(root);
    }
    CfgNode *root = machine("array: {count: 1, lanes: 8}",
                            CM ", router_nodes: 2");
    char *msg = NULL, *desc = part(root, 32, &msg);
    assert_string_equal(desc, "array lanes 32 = 8 routers x 4");
    assert_string_equal(at(root, "machine.network.router_nodes"), "8");
    assert_string_equal(at(root, "machine.nodes.array.lanes"), "32");
    g_free(desc);
    cfg_free(root);
}

static void test_cm_refused(void **state)
{
    (void)state;
    static const struct {
        const char *net;
        guint n;
        const char *group;
    } cases[] = {
        {CM, 12, "4"}, /* 3 routers */
        {CM, 10, "4"}, /* not a multiple */
        {CM, 2, "4"},  /* no router */
        {"topology: cm-router, bandwidth: 1 MB/s", 16, "0"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(cases); i++) {
        CfgNode *root = machine("array: {count: 1, lanes: 8}", cases[i].net);
        char *msg = NULL, *desc = part(root, cases[i].n, &msg);
        assert_null(desc);
        char *want = g_strdup_printf("found %u lanes for a cm-router of %s "
                                     "per router, expected procs_per_router x "
                                     "a power of two",
                                     cases[i].n, cases[i].group);
        if (!msg || strcmp(msg, want) != 0)
            fail_msg("got '%s'\nwant '%s'", msg, want);
        g_free(want);
        g_free(msg);
        cfg_free(root);
    }
    /* a kind name that is no step of a key path is refused by the model
     * check, at the kind, before a partition writes its lanes; a name of
     * letters, digits, '_' and '-' partitions */
    const char *names[] = {"'a b'", "'a.b'", "''", "'a-b_2'"};
    for (guint i = 0; i < G_N_ELEMENTS(names); i++) {
        char *kinds = g_strdup_printf("%s: {count: 1, lanes: 4}", names[i]);
        CfgNode *root = machine(kinds, CM);
        char *msg = NULL, *desc = part(root, 16, &msg);
        if (i + 1 < G_N_ELEMENTS(names)) {
            char *want = g_strdup_printf(
                "run.yaml:4:%u: found node kind name '%.*s', expected a "
                "name of letters, digits, '_' and '-' (a step of --set "
                "machine.nodes.KIND.count)",
                (unsigned)(strlen(names[i]) + 13),
                (int)strlen(names[i]) - 2, names[i] + 1);
            assert_null(desc);
            if (!msg || strcmp(msg, want) != 0)
                fail_msg("got '%s'\nwant '%s'", msg, want);
            g_free(want);
        } else {
            assert_string_equal(desc, "a-b_2 lanes 16 = 4 routers x 4");
        }
        g_free(desc);
        g_free(msg);
        g_free(kinds);
        cfg_free(root);
    }
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_own_size_overrides_nothing),
        cmocka_unit_test(test_hypercube_dimension),
        cmocka_unit_test(test_cm_widest),
        cmocka_unit_test(test_cm_refused),
    };
    return cmocka_run_group_tests_name("partition_edges", tests,
                                       support_test_models, NULL);
}
