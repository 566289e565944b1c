/* test_costs.c — the pricing home (sim/machine/costs.h): a declared cost
 * set, every missing cost in one located error, each cost's provenance,
 * and the one saturating "count x cost" (sim/core/time.h) at its
 * boundary.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/costs.h"
#include "sim/machine/machine.h"
#include "tests/support.h"

#define TINY "tests/data/models/tiny.yaml"

typedef struct {
    SimEngine *eng;
    MachMachine *m;
    CfgNode *tree;
} Fix;

/* The tiny model (its file is the machine section itself), with the
 * overrides `sets` (NULL-terminated, may be NULL). */
static Fix *fix_new(const char *const *sets)
{
    Fix *f = g_new0(Fix, 1);
    GError *err = NULL;
    f->tree = cfg_load_file(TINY, &err);
    for (; f->tree && sets && *sets; sets++)
        if (!cfg_set_override(f->tree, *sets, &err))
            break;
    f->eng = sim_engine_new(1);
    f->m = f->tree && !err
               ? mach_new_from_cfg(f->eng, f->tree, "analytic", &err)
               : NULL;
    if (!f->m)
        fail_msg("%s", err->message);
    return f;
}

static void fix_free(Fix *f)
{
    mach_free(f->m);
    sim_engine_free(f->eng);
    cfg_free(f->tree);
    g_free(f);
}

/* n x unit saturates exactly when the product passes SIM_TIME_MAX: each
 * of the saturated cases wraps to a small time (0, or 2^64 - 2 ...) if
 * the check is dropped, and the exact ones saturate if it is too eager. */
static void test_mul_sat_boundary(void **state)
{
    (void)state;
    assert_int_equal(sim_time_mul_sat(SIM_TIME_MAX, 0), 0);
    assert_int_equal(sim_time_mul_sat(0, UINT64_MAX), 0);
    assert_int_equal(sim_time_mul_sat(SIM_TIME_MAX, 1), SIM_TIME_MAX);
    assert_int_equal(sim_time_mul_sat(SIM_TIME_MAX / 2, 2),
                     SIM_TIME_MAX - 1);
    assert_int_equal(sim_time_mul_sat(SIM_TIME_MAX / 2 + 1, 2), SIM_TIME_MAX);
    assert_int_equal(sim_time_mul_sat((SimTime)1 << 32, (uint64_t)1 << 32),
                     SIM_TIME_MAX);
    assert_int_equal(sim_time_mul_sat(SIM_TIME_MAX / 3, 3), SIM_TIME_MAX);
    assert_int_equal(sim_time_mul_sat(SIM_TIME_MAX / 3 + 1, 3), SIM_TIME_MAX);
    assert_int_equal(sim_time_mul_sat(7, 3), 21);
}

static const char *const cpu_ops[] = {"work", "tiny_op", NULL};
static const MachNeed tiny_needs[] = {{"cpu", cpu_ops, NULL}, {NULL, NULL, NULL}};

/* Prices from the set: a cost, n of them (saturating at the boundary,
 * as the machine's processors price the same counts). */
static void test_prices(void **state)
{
    (void)state;
    Fix *f = fix_new(NULL);
    GError *err = NULL;
    MachCosts *c = mach_costs_new(f->m, tiny_needs, &err);
    assert_non_null(c);
    assert_int_equal(mach_costs_get(c, "cpu", "work"), 10 * SIM_US);
    assert_int_equal(mach_costs_times(c, "cpu", "tiny_op", 1000),
                     3 * SIM_US);
    uint64_t edge = SIM_TIME_MAX / (3 * SIM_NS);
    assert_int_equal(mach_costs_times(c, "cpu", "tiny_op", edge),
                     edge * 3 * SIM_NS);
    assert_int_equal(mach_costs_times(c, "cpu", "tiny_op", edge + 1),
                     SIM_TIME_MAX);
    MachOps o = {.op = {{"tiny_op", edge + 1}}, .n = 1};
    assert_int_equal(mach_proc_ops_cost(mach_proc(f->m, "cpu", 0), &o),
                     SIM_TIME_MAX);
    SimTime w = 0, t = 0;
    SimTime *const dst[] = {&w, &t};
    mach_costs_fill(c, "cpu", cpu_ops, dst);
    assert_int_equal(w, 10 * SIM_US);
    assert_int_equal(t, 3 * SIM_NS);
    mach_costs_free(c);
    fix_free(f);
}

/* Every missing cost and kind of the table in one error, each located;
 * the first line is the old single-cost message. */
static void test_missing_listed_at_once(void **state)
{
    (void)state;
    Fix *f = fix_new(NULL);
    static const char *const cpu[] = {"work", "teleport", "warp", NULL};
    static const char *const gpu[] = {"work", NULL};
    static const MachNeed needs[] = {{"cpu", cpu, NULL}, {"gpu", gpu, NULL},
                                     {NULL, NULL, NULL}};
    GError *err = NULL;
    assert_null(mach_costs_new(f->m, needs, &err));
    assert_non_null(err);
    const char *msg = err->message;
    assert_true(g_str_has_prefix(msg, TINY ":"));
    assert_non_null(strstr(msg, "found no cost for 'teleport' on 'cpu', "
                                "expected costs: {teleport:"));
    assert_non_null(strstr(msg, "3 missing in all:"));
    assert_non_null(strstr(msg, "\n  " TINY ":"));
    assert_non_null(strstr(msg, ": nodes.cpu.costs.teleport"));
    assert_non_null(strstr(msg, ": nodes.cpu.costs.warp"));
    assert_non_null(strstr(msg, ": nodes.gpu.costs.work"));
    assert_null(strstr(msg, "nodes.cpu.costs.work"));
    g_clear_error(&err);
    assert_false(mach_costs_check(f->m, needs, &err));
    g_clear_error(&err);
    assert_true(mach_costs_check(f->m, tiny_needs, &err));
    assert_null(err);
    /* mach_require_costs lists them all too */
    assert_false(mach_require_costs(f->m, "cpu", cpu, &err));
    assert_non_null(strstr(err->message, "2 missing in all:"));
    g_clear_error(&err);
    fix_free(f);
}

/* Each cost says where it comes from: the model's file, place, key and
 * text; an override names the override. */
static void test_provenance(void **state)
{
    (void)state;
    static const char *const sets[] = {"nodes.cpu.costs.tiny_op=5 ns", NULL};
    Fix *f = fix_new(sets);
    MachCosts *c = mach_costs_new(f->m, tiny_needs, NULL);
    assert_non_null(c);
    const MachCost *w = mach_costs_find(c, "cpu", "work");
    assert_non_null(w);
    assert_int_equal(w->from, MACH_COST_MODEL);
    assert_int_equal(w->prov, MACH_PROV_ASSUMPTION);
    assert_string_equal(w->text, "test fixture");
    assert_string_equal(w->file, TINY);
    assert_int_equal(w->line, 9);
    assert_string_equal(w->kind, "cpu");
    assert_string_equal(w->op, "work");
    const MachCost *t = mach_costs_find(c, "cpu", "tiny_op");
    assert_int_equal(t->value, 5 * SIM_NS);
    assert_int_equal(t->prov, MACH_PROV_OVERRIDE);
    assert_null(t->text);
    assert_string_not_equal(t->file, TINY);
    char *d = mach_cost_describe(w);
    assert_string_equal(d, "nodes.cpu.costs.work = 10 us (model, "
                           "assumption, " TINY ":9:21)");
    g_free(d);
    assert_string_equal(mach_cost_from_name(MACH_COST_DERIVED), "derived");
    mach_costs_free(c);
    fix_free(f);
}

/* A set holds what was declared, once each, in declaration order; the
 * machine's own table answers for the rest. */
static void test_declared_only(void **state)
{
    (void)state;
    Fix *f = fix_new(NULL);
    static const char *const a[] = {"tiny_op", NULL};
    static const char *const b[] = {"tiny_op", "work", NULL};
    static const MachNeed needs[] = {
        {"cpu", a, NULL}, {"cpu", b, NULL}, {NULL, NULL, NULL}};
    static const MachNeed one[] = {{"cpu", a, NULL}, {NULL, NULL, NULL}};
    MachCosts *c = mach_costs_new(f->m, needs, NULL);
    assert_int_equal(mach_costs_len(c), 2);
    assert_string_equal(mach_costs_nth(c, 0)->op, "tiny_op");
    assert_string_equal(mach_costs_nth(c, 1)->op, "work");
    mach_costs_free(c);
    c = mach_costs_new(f->m, one, NULL);
    assert_null(mach_costs_find(c, "cpu", "work"));
    assert_non_null(mach_cost_info(f->m, "cpu", "work"));
    assert_null(mach_cost_info(f->m, "gpu", "work"));
    mach_costs_free(c);
    mach_costs_free(NULL);
    fix_free(f);
}

/* Portable work (work.h): a cost the model lacks is derived from the
 * op's work on the kind's processor description (cycles / clock, bytes
 * / memory bandwidth, a graphics class through its software definition
 * unless priced itself); an explicit cost wins; an unpriced class is
 * named in the list of missing costs; the run's note lists derived ones. */
static void test_derived(void **state)
{
    (void)state;
    static const char *const ops[] = {"work", "blit", "tri", NULL};
    static const MachWork work[] = {
        {"work", {[MACH_W_FLOP] = 1000}}, /* explicit 10 us wins */
        {"blit", {[MACH_W_INSTR] = 4, [MACH_W_MEMBYTE] = 1000}},
        {"tri", {[MACH_W_VERTEX] = 3, [MACH_W_PIXEL] = 10}},
        {NULL, {0}}};
    static const MachNeed needs[] = {{"cpu", ops, work}, {NULL, NULL, NULL}};
    /* no description: both listed, each with a class that would do */
    Fix *f = fix_new(NULL);
    GError *err = NULL;
    assert_null(mach_costs_new(f->m, needs, &err));
    assert_non_null(strstr(err->message, "2 missing in all:"));
    assert_non_null(strstr(err->message, "nodes.cpu.costs.blit (or "
                                         "nodes.cpu.cycles.instr to derive"));
    g_clear_error(&err);
    fix_free(f);
    /* 1 GHz: instr 2 cycles = 2 ns, flop 1 ns, 1 GB/s = 1 ns a byte */
    static const char *const sets[] = {
        "nodes.cpu.cycles.instr=2", "nodes.cpu.cycles.flop=1",
        "nodes.cpu.memory_bandwidth=1 GB/s", NULL};
    f = fix_new(sets);
    MachCosts *c = mach_costs_new(f->m, needs, &err);
    assert_non_null(c);
    assert_int_equal(mach_costs_get(c, "cpu", "work"), 10 * SIM_US);
    assert_int_equal(mach_costs_find(c, "cpu", "work")->from,
                     MACH_COST_MODEL);
    const MachCost *b = mach_costs_find(c, "cpu", "blit");
    assert_int_equal(b->value, 1008 * SIM_NS);
    assert_int_equal(b->from, MACH_COST_DERIVED);
    assert_int_equal(b->prov, MACH_PROV_ASSUMPTION);
    assert_non_null(strstr(b->text, "4 instr + 1000 membyte"));
    /* vertex 80 flop + 30 instr = 140 ns, pixel 4 + 8 x 2 = 20 ns */
    assert_int_equal(mach_costs_get(c, "cpu", "tri"),
                     (3 * 140 + 10 * 20) * SIM_NS);
    /* the processors price named counts with the derived cost */
    MachOps o = {.op = {{"blit", 2}}, .n = 1};
    assert_int_equal(mach_proc_ops_cost(mach_proc(f->m, "cpu", 0), &o),
                     2016 * SIM_NS);
    SimResult *r = sim_result_new("t", "tiny");
    mach_costs_note_derived(mach_kind(f->m, "cpu"), r);
    assert_int_equal(r->notes->len, 1);
    const char *note = g_ptr_array_index(r->notes, 0);
    assert_non_null(strstr(note, "blit 1.008 us (4 instr + 1000 membyte); "
                                 "tri 620 ns (3 vertex + 10 pixel)"));
    sim_result_free(r);
    mach_costs_free(c);
    fix_free(f);
    /* a pixel rate of its own replaces the software definition; the
     * clock moves every cycle price */
    static const char *const gpu[] = {
        "nodes.cpu.cycles.instr=2", "nodes.cpu.cycles.flop=1",
        "nodes.cpu.cycles.pixel=0.5", "nodes.cpu.clock=2 GHz",
        "nodes.cpu.memory_bandwidth=1 GB/s", NULL};
    f = fix_new(gpu);
    c = mach_costs_new(f->m, needs, NULL);
    assert_int_equal(mach_costs_get(c, "cpu", "tri"),
                     3 * 70 * SIM_NS + 10 * 250 * SIM_PS);
    mach_costs_free(c);
    fix_free(f);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mul_sat_boundary),
        cmocka_unit_test(test_prices),
        cmocka_unit_test(test_missing_listed_at_once),
        cmocka_unit_test(test_provenance),
        cmocka_unit_test(test_declared_only),
        cmocka_unit_test(test_derived),
    };
    return cmocka_run_group_tests_name("costs", tests, NULL, NULL);
}
