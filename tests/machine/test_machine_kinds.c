/* test_machine_kinds.c — a node kind's limits as sim/machine/machine.c
 * reads them: exactly 16M processors with zero lanes is refused at the
 * lanes, one more processor at the count, each with its message and
 * location; zero lanes alone at the lanes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "tests/support.h"

static char *build(const char *kind)
{
    char *text =
        g_strdup_printf("machine:\n  provenance: assumption\n  name: t\n"
                        "  nodes: {cpu: {%s}}\n"
                        "  network: {topology: bus, bandwidth: 1 MB/s}\n",
                        kind);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "run.yaml", &err);
    assert_non_null(root);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    char *msg = err ? g_strdup(err->message) : NULL;
    g_clear_error(&err);
    mach_free(m);
    sim_engine_free(eng);
    cfg_free(root);
    g_free(text);
    return msg;
}

static void expect(const char *kind, const char *want)
{
    char *msg = build(kind);
    if (g_strcmp0(msg, want) != 0)
        fail_msg("%s:\n got '%s'\nwant '%s'", kind, msg, want);
    g_free(msg);
}

static void test_kind_limits(void **state)
{
    (void)state;
    expect("count: 16777216, lanes: 0",
           "run.yaml:4:41: found zero lanes, expected a count in 0 .. 16M "
           "(lanes >= 1)");
    expect("count: 16777217, lanes: 0",
           "run.yaml:4:24: found more than 16M processors, expected a count in "
           "0 .. 16M (lanes >= 1)");
    expect("count: 16777217", "run.yaml:4:24: found more than 16M processors, "
                              "expected a count in 0 .. 16M (lanes >= 1)");
    expect("count: 2, lanes: 0", "run.yaml:4:34: found zero lanes, expected a "
                                 "count in 0 .. 16M (lanes >= 1)");
    expect("count: 2, lanes: 4", NULL);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kind_limits),
    };
    return cmocka_run_group_tests_name("machine_kinds", tests,
                                       support_test_models, NULL);
}
