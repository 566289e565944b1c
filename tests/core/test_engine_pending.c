/* test_engine_pending.c — sim_engine_pending() counts the events still to
 * run: inside a handler the event being run is not among them (whether or
 * not the handler schedules), and after a run bounded by a time limit the
 * later events are. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/core/engine.h"
#include "tests/support.h"

static void note(SimEngine *e, void *ctx, void *arg)
{
    GArray *seen = ctx;
    size_t n = sim_engine_pending(e);
    g_array_append_val(seen, n);
    if (arg) /* schedules one more, 10 ps later */
        sim_schedule_in(e, 10, note, ctx, NULL);
}

static void test_pending(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    GArray *seen = g_array_new(FALSE, FALSE, sizeof(size_t));
    assert_int_equal(sim_engine_pending(e), 0);
    sim_schedule_at(e, 5, note, seen, GINT_TO_POINTER(1));
    sim_schedule_at(e, 7, note, seen, NULL);
    sim_schedule_at(e, 100, note, seen, NULL);
    assert_int_equal(sim_engine_pending(e), 3);
    assert_true(sim_engine_run(e, 50, NULL));
    /* at 5: 7 and 100 wait; at 7: 15 and 100; at 15: 100 */
    assert_int_equal(seen->len, 3);
    assert_int_equal(g_array_index(seen, size_t, 0), 2);
    assert_int_equal(g_array_index(seen, size_t, 1), 2);
    assert_int_equal(g_array_index(seen, size_t, 2), 1);
    assert_int_equal(sim_engine_pending(e), 1);
    assert_int_equal(sim_now(e), 50);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(g_array_index(seen, size_t, 3), 0);
    assert_int_equal(sim_engine_pending(e), 0);
    assert_int_equal(sim_engine_events(e), 4);
    g_array_free(seen, TRUE);
    sim_engine_free(e);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pending),
    };
    return cmocka_run_group_tests_name("engine_pending", tests, NULL, NULL);
}
