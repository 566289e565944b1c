/* test_roles.c — a workload's node kinds carved from the kinds that play
 * them (sim/machine/roles.h): the only kind plays a missing one whole;
 * several roles of one kind take one processor each or their set counts,
 * and the kind keeps the rest; roles: names the player; a missing kind
 * without a player carves nothing; too few processors and a role naming
 * no kind are located errors.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "sim/machine/roles.h"
#include "tests/support.h"

/* The machine built from `section` (YAML) after carving `needed`; NULL
 * with *err on failure.  *notes gets the notes. */
static MachMachine *carve(SimEngine *eng, const char *section,
                          const char *const *needed, GPtrArray *notes,
                          GError **err)
{
    CfgNode *sec = cfg_load_string(section, "<test>", err);
    MachMachine *m = NULL;
    if (sec && mach_section_roles(sec, NULL, needed, notes, err))
        m = mach_new_from_cfg(eng, sec, "analytic", err);
    cfg_free(sec);
    return m;
}

static guint count(const MachMachine *m, const char *kind)
{
    const MachKindInfo *k = mach_kind(m, kind);
    return k ? k->count : G_MAXUINT;
}

static void test_only_kind_plays_whole(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    GPtrArray *notes = g_ptr_array_new_with_free_func(g_free);
    static const char *const need[] = {"cpu", NULL};
    GError *err = NULL;
    MachMachine *m = carve(eng, "model: ipsc2\n", need, notes, &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(count(m, "cpu"), 16);
    assert_int_equal(count(m, "node"), 0);
    assert_int_equal(mach_kind(m, "cpu")->first, 0);
    assert_int_equal(mach_proc_total(m), 16);
    /* the player's description and costs come along */
    assert_non_null(mach_cost_info(m, "cpu", "polygon"));
    assert_true(mach_kind(m, "cpu")->clock_hz > 0);
    assert_int_equal(notes->len, 1);
    assert_non_null(strstr(g_ptr_array_index(notes, 0), "'cpu' by 16 'node'"));
    mach_free(m);
    /* a kind the machine has is not carved */
    static const char *const have[] = {"node", NULL};
    g_ptr_array_set_size(notes, 0);
    m = carve(eng, "model: ipsc2\n", have, notes, &err);
    assert_int_equal(count(m, "node"), 16);
    assert_int_equal(notes->len, 0);
    mach_free(m);
    g_ptr_array_free(notes, TRUE);
    sim_engine_free(eng);
}

static void test_several_roles_share(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    GPtrArray *notes = g_ptr_array_new_with_free_func(g_free);
    static const char *const need[] = {"gp", "renderer", "host", "gp", NULL};
    GError *err = NULL;
    MachMachine *m = carve(eng, "model: ipsc2\nnodes: {gp: {count: 4}}\n",
                           need, notes, &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(count(m, "gp"), 4);
    assert_int_equal(count(m, "renderer"), 1);
    assert_int_equal(count(m, "host"), 1);
    assert_int_equal(count(m, "node"), 10);
    assert_int_equal(mach_proc_total(m), 16);
    mach_free(m);
    /* too few: located at the player's count */
    m = carve(eng, "model: ipsc2\nnodes: {gp: {count: 15}}\n", need, notes,
              &err);
    assert_null(m);
    assert_non_null(strstr(err->message, "found 16 'node' processors, "
                                         "expected at least 17"));
    assert_non_null(strstr(err->message, "ipsc2.yaml:"));
    g_clear_error(&err);
    g_ptr_array_free(notes, TRUE);
    sim_engine_free(eng);
}

static void test_roles_name_the_player(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    GPtrArray *notes = g_ptr_array_new_with_free_func(g_free);
    static const char *const node[] = {"node", NULL};
    GError *err = NULL;
    /* Pixel-Planes 5's GPs play node, first in processor order */
    MachMachine *m = carve(eng, "model: pixel-planes-5\n", node, notes, &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(count(m, "node"), 16);
    assert_int_equal(count(m, "gp"), 0);
    assert_int_equal(mach_kind(m, "node")->first, 0);
    mach_free(m);
    /* no player for one of them: nothing carved, no error */
    static const char *const two[] = {"node", "pipe", NULL};
    g_ptr_array_set_size(notes, 0);
    m = carve(eng, "model: pixel-planes-5\n", two, notes, &err);
    assert_non_null(m);
    assert_null(mach_kind(m, "node"));
    assert_int_equal(notes->len, 0);
    mach_free(m);
    /* a role naming no kind */
    m = carve(eng, "model: pixel-planes-5\nroles: {pipe: teapot}\n", two,
              notes, &err);
    assert_null(m);
    if (!strstr(err->message, "<test>:2:15: found role 'pipe' played by "
                              "'teapot'"))
        fail_msg("%s", err->message);
    g_clear_error(&err);
    g_ptr_array_free(notes, TRUE);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_only_kind_plays_whole),
        cmocka_unit_test(test_several_roles_share),
        cmocka_unit_test(test_roles_name_the_player),
    };
    return cmocka_run_group_tests_name("roles", tests, NULL, NULL);
}
