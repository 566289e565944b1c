/* test_overlap.c — work held for the longest of overlapping terms
 * (sim/machine/overlap.c): reset empties a used record, the cost is the
 * maximum of the worker's own counts and every term (counts priced on
 * the term's processor, bytes as an idle bus transfer), and the work a
 * recording hears carries each term's node, bus flag, bytes and counts. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/machine/machine.h"
#include "sim/machine/overlap.h"
#include "sim/machine/shmem.h"
#include "tests/machine/tiny_rec.h"
#include "tests/support.h"

typedef TinyRec Fix;

static void noted(SimEngine *eng, void *ctx, void *arg)
{
    rec_log_note(ctx, "done %s @%" G_GUINT64_FORMAT, (const char *)arg,
                 sim_now(eng));
}

/* tiny.yaml: work 10 us, tiny_op 3 ns on every cpu.  The bus: 1 MB/s
 * (1 us a byte) after 5 us of latency. */
static void test_overlap_cost_is_longest_term(void **state)
{
    Fix *f = *state;
    MachProc *w = mach_proc(f->m, "cpu", 0), *pipe = mach_proc(f->m, "cpu", 2);
    MachShmem bus;
    mach_shmem_init_with(&bus, 1e6, 5 * SIM_US);
    MachOverlap o;
    o.own.n = 4; /* a used record */
    o.n = 2;
    mach_overlap_reset(&o);
    assert_int_equal(o.own.n, 0);
    assert_int_equal(o.n, 0);
    assert_int_equal(mach_overlap_cost(w, &o), 0);
    mach_ops_add(&o.own, "work", 2);
    assert_int_equal(mach_overlap_cost(w, &o), 20 * SIM_US);
    MachOps pipe_ops = {0};
    mach_ops_add(&pipe_ops, "work", 3);
    mach_overlap_ops(&o, pipe, &pipe_ops);
    assert_int_equal(o.n, 1);
    assert_ptr_equal(o.term[0].on, pipe);
    assert_null(o.term[0].bus);
    assert_int_equal(mach_overlap_cost(w, &o), 30 * SIM_US);
    mach_overlap_bus(&o, &bus, pipe, 20);
    assert_int_equal(o.n, 2);
    assert_int_equal(o.term[1].bytes, 20);
    assert_int_equal(o.term[1].ops.n, 0);
    assert_int_equal(mach_overlap_cost(w, &o), 30 * SIM_US);
    mach_overlap_bus(&o, &bus, pipe, 40); /* 5 + 40 us: the longest */
    assert_int_equal(mach_overlap_cost(w, &o), 45 * SIM_US);
    /* the worker's own counts longest: 5 x work */
    mach_ops_add(&o.own, "work", 3);
    assert_int_equal(mach_overlap_cost(w, &o), 50 * SIM_US);
    mach_overlap_reset(&o);
    mach_ops_add(&o.own, "tiny_op", 1);
    assert_int_equal(mach_overlap_cost(w, &o), 3 * SIM_NS);
}

static void test_overlap_submitted(void **state)
{
    Fix *f = *state;
    MachProc *w = mach_proc(f->m, "cpu", 1), *pipe = mach_proc(f->m, "cpu", 3);
    MachShmem bus;
    mach_shmem_init_with(&bus, 1e6, 5 * SIM_US);
    MachOverlap o;
    mach_overlap_reset(&o);
    mach_ops_add(&o.own, "tiny_op", 7);
    MachOps pipe_ops = {0};
    mach_ops_add(&pipe_ops, "work", 1);
    mach_ops_add(&pipe_ops, "tiny_op", 2);
    mach_overlap_ops(&o, pipe, &pipe_ops);
    mach_overlap_bus(&o, &bus, pipe, 64);
    assert_true(mach_proc_compute_overlap(w, &o, 0, noted, &f->log, "x"));
    /* no terms: the own counts alone */
    mach_overlap_reset(&o);
    mach_ops_add(&o.own, "work", 1);
    assert_true(mach_proc_compute_overlap(w, &o, 0, NULL, NULL, NULL));
    assert_true(sim_engine_run(f->eng, SIM_TIME_MAX, NULL));
    assert_string_equal(f->log.text->str,
                        "compute @0 n1 p0 cost=69000000 end=69000000 "
                        "tiny_op*7 [n3 0 B 2 ops] [n3 bus 64 B 0 ops] h=1 -> 1\n"
                        "compute @0 n1 p0 cost=10000000 end=79000000 "
                        "work*1 h=0 -> 2\n"
                        "begin 1 @69000000\ndone x @69000000\nend 1\n"
                        "begin 2 @79000000\nend 2\n");
    assert_int_equal(mach_proc_busy(w), 79 * SIM_US);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(
            test_overlap_cost_is_longest_term, tiny_rec_setup, tiny_rec_teardown),
        cmocka_unit_test_setup_teardown(
            test_overlap_submitted, tiny_rec_setup, tiny_rec_teardown),
    };
    return cmocka_run_group_tests_name("overlap", tests, NULL, NULL);
}
