/* test_shmem.c — shared memory as a FIFO bandwidth server: transfers
 * queue behind each other, a lone one takes bytes / bandwidth + latency,
 * an idle gap is not charged, and a machine without a bus is refused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/machine/shmem.h"
#include "tests/support.h"

static void test_fifo(void **state)
{
    (void)state;
    MachShmem sh;
    mach_shmem_init_with(&sh, 1e9, 100 * SIM_NS); /* 1 GB/s */
    /* 1000 B = 1 us, then 100 ns latency */
    assert_int_equal(mach_shmem_transfer(&sh, 0, 1000), 1100 * SIM_NS);
    /* a second one at t = 0 waits for the first */
    assert_int_equal(mach_shmem_transfer(&sh, 0, 1000), 2100 * SIM_NS);
    /* after an idle gap it starts at once */
    assert_int_equal(mach_shmem_transfer(&sh, 10 * SIM_US, 500),
                     10 * SIM_US + 600 * SIM_NS);
    assert_int_equal(sh.bytes, 2500);
    assert_int_equal(sh.busy, 2500 * SIM_NS);
    assert_true(mach_shmem_utilisation(&sh, 25 * SIM_US) > 0.099 &&
                mach_shmem_utilisation(&sh, 25 * SIM_US) < 0.101);
    MachShmem inf;
    mach_shmem_init_with(&inf, 0, 0);
    assert_int_equal(mach_shmem_transfer(&inf, 5, 1u << 30), 5);
}

static void test_needs_a_bus(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    GError *e = NULL;
    MachMachine *m = mach_new_from_model(eng, "ipsc2", "analytic", &e);
    assert_non_null(m);
    MachShmem sh;
    assert_false(mach_shmem_init(&sh, m, &e));
    assert_non_null(e);
    g_clear_error(&e);
    mach_free(m);
    m = mach_new_from_model(eng, "origin2000", "analytic", &e);
    assert_non_null(m);
    assert_true(mach_shmem_init(&sh, m, &e));
    assert_true(sh.bandwidth > 9e9 && sh.latency == 315 * SIM_NS);
    mach_free(m);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fifo),
        cmocka_unit_test(test_needs_a_bus),
    };
    return cmocka_run_group_tests_name("shmem", tests, NULL, NULL);
}
