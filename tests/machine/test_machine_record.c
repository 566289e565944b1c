/* test_machine_record.c — what `pgsim run --record` hears from the machine
 * layer (a logging recorder, tests/core/rec_log.h): each piece of work with
 * its node, phase, priced cost, end and named counts, then its completion
 * around the handler; shared-memory transfers likewise.  Also the exact
 * pricing of named counts: sums, accumulation by name, saturation at the
 * end of the clock and exactly below it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "sim/machine/shmem.h"
#include "tests/machine/tiny_rec.h"
#include "tests/support.h"

typedef TinyRec Fix;

static void noted(SimEngine *eng, void *ctx, void *arg)
{
    rec_log_note(ctx, "done %s @%" G_GUINT64_FORMAT, (const char *)arg,
                 sim_now(eng));
}

static void run(Fix *f)
{
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
}

/* tiny.yaml: work 10 us, tiny_op 3 ns on every cpu. */
static void test_compute_recorded(void **state)
{
    Fix *f = *state;
    unsigned ph = sim_engine_phase(f->eng, "draw");
    MachProc *p = mach_proc(f->m, "cpu", 1);
    const MachOp ops[] = {{"work", 2}, {"tiny_op", 5}};
    assert_true(mach_proc_compute_ops(p, ops, 2, ph, noted, &f->log, "a"));
    /* queued behind a on the same processor; no handler */
    assert_true(mach_proc_compute(p, 7, 0, NULL, NULL, NULL));
    run(f);
    char *want = g_strdup_printf(
        "compute @0 n1 p%u cost=20015000 end=20015000 work*2 tiny_op*5 "
        "h=1 -> 1\n"
        "compute @0 n1 p0 cost=7 end=20015007 h=0 -> 2\n"
        "begin 1 @20015000\n"
        "done a @20015000\n"
        "end 1\n"
        "begin 2 @20015007\n"
        "end 2\n",
        ph);
    assert_string_equal(f->log.text->str, want);
    g_free(want);
    assert_int_equal(mach_proc_busy(p), 20015007);
    assert_int_equal(mach_proc_busy_phase(p, ph), 20015000);
    assert_int_equal(mach_proc_requests(p), 2);
}

static void test_terms_and_priced_recorded(void **state)
{
    Fix *f = *state;
    MachProc *p = mach_proc(f->m, "cpu", 3);
    const MachOp ops[] = {{"tiny_op", 4}};
    const SimOpTerm terms[] = {
        {.node = 2, .bus = TRUE, .bytes = 64, .ops = ops, .n_ops = 1}};
    const SimWork w = {ops, 1, terms, 1};
    assert_true(mach_proc_compute_terms(p, 500, &w, 0, noted, &f->log, "t"));
    assert_true(
        mach_proc_compute_priced(p, 40, ops, 1, 0, noted, &f->log, "q"));
    run(f);
    assert_string_equal(f->log.text->str,
                        "compute @0 n3 p0 cost=500 end=500 tiny_op*4 "
                        "[n2 bus 64 B 1 ops] h=1 -> 1\n"
                        "compute @0 n3 p0 cost=40 end=540 tiny_op*4 h=1 -> 2\n"
                        "begin 1 @500\ndone t @500\nend 1\n"
                        "begin 2 @540\ndone q @540\nend 2\n");
}

static void test_ops_pricing(void **state)
{
    Fix *f = *state;
    MachProc *p = mach_proc(f->m, "cpu", 0);
    MachOps o = {0};
    assert_int_equal(mach_proc_ops_cost(p, &o), 0);
    mach_ops_add(&o, "work", 2);
    mach_ops_add(&o, "tiny_op", 1);
    mach_ops_add(&o, "work", 3); /* adds to the first entry */
    char same[] = "tiny_op"; /* equal text at another address */
    mach_ops_add(&o, same, 0);
    assert_int_equal(o.n, 2);
    assert_string_equal(o.op[0].name, "work");
    assert_int_equal(o.op[0].count, 5);
    assert_int_equal(o.op[1].count, 1);
    assert_int_equal(mach_proc_ops_cost(p, &o), 50 * SIM_US + 3 * SIM_NS);
    /* a count whose price is exactly representable, then one more */
    uint64_t most = SIM_TIME_MAX / (10 * SIM_US);
    MachOp big[] = {{"work", most}};
    MachOps ob = {.n = 1, .op = {big[0]}};
    assert_int_equal(mach_proc_ops_cost(p, &ob), most * 10 * SIM_US);
    ob.op[0].count = most + 1;
    assert_int_equal(mach_proc_ops_cost(p, &ob), SIM_TIME_MAX);
    /* the sum saturates too */
    ob.op[0].count = most;
    ob.op[1] = (MachOp){"tiny_op", most};
    ob.n = 2;
    assert_int_equal(mach_proc_ops_cost(p, &ob), SIM_TIME_MAX);
    /* an empty list is a plain time of 0 */
    MachOps none = {0};
    assert_true(mach_proc_compute_list(p, &none, 0, noted, &f->log, "z"));
    run(f);
    assert_string_equal(f->log.text->str,
                        "compute @0 n0 p0 cost=0 end=0 h=1 -> 1\n"
                        "begin 1 @0\ndone z @0\nend 1\n");
}

static void test_shmem_send_recorded(void **state)
{
    Fix *f = *state;
    MachShmem sh;
    mach_shmem_init_with(&sh, 1e9, 100 * SIM_NS); /* 1 B per ns */
    SimTime end = 0;
    assert_true(mach_shmem_send(&sh, f->eng, 2, 3, 1000, noted, &f->log, "s"));
    end = sh.last_end;
    assert_int_equal(end, 1100 * SIM_NS);
    assert_true(mach_shmem_send(&sh, f->eng, 0, 1, 500, NULL, NULL, NULL));
    run(f);
    assert_string_equal(f->log.text->str,
                        "transfer @0 2->3 1000 B end=1100000 -> 1\n"
                        "transfer @0 0->1 500 B end=1600000 -> 2\n"
                        "begin 1 @1100000\ndone s @1100000\nend 1\n"
                        "begin 2 @1600000\nend 2\n");
    assert_int_equal(sh.bytes, 1500);
    assert_int_equal(sh.transfers, 2);
    assert_int_equal(sh.busy, 1500 * SIM_NS);
    assert_int_equal(sh.free_at, 1500 * SIM_NS);
    assert_int_equal(mach_shmem_time(&sh, 2000), 2100 * SIM_NS);
    assert_true(mach_shmem_utilisation(&sh, 3000 * SIM_NS) == 0.5);
    assert_true(mach_shmem_utilisation(&sh, 0) == 0.0);
}

/* Without a recorder: the handler runs at the transfer's end, and a
 * transfer without one schedules nothing. */
static void test_shmem_send_plain(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    RecLog log;
    rec_log_init(&log);
    MachShmem sh;
    mach_shmem_init_with(&sh, 2e9, 5 * SIM_NS);
    assert_true(mach_shmem_send(&sh, eng, 0, 1, 4000, noted, &log, "p"));
    assert_true(mach_shmem_send(&sh, eng, 0, 1, 4000, NULL, NULL, NULL));
    assert_int_equal(sim_engine_pending(eng), 1);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_string_equal(log.text->str, "done p @2005000\n");
    assert_int_equal(sh.free_at, 4000 * SIM_NS);
    rec_log_clear(&log);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(
            test_compute_recorded, tiny_rec_setup, tiny_rec_teardown),
        cmocka_unit_test_setup_teardown(
            test_terms_and_priced_recorded, tiny_rec_setup, tiny_rec_teardown),
        cmocka_unit_test_setup_teardown(
            test_ops_pricing, tiny_rec_setup, tiny_rec_teardown),
        cmocka_unit_test_setup_teardown(
            test_shmem_send_recorded, tiny_rec_setup, tiny_rec_teardown),
        cmocka_unit_test(test_shmem_send_plain),
    };
    return cmocka_run_group_tests_name("machine_record", tests, NULL, NULL);
}
