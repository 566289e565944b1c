/* test_engine.c — event order, ties, overflow, run bounds, stop, pool. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim/core/engine.h"
#include "tests/support.h"

typedef struct {
    GArray *log; /* int tags in execution order */
    GArray *times;
} Log;

static void log_tag(SimEngine *e, void *ctx, void *arg)
{
    Log *l = ctx;
    int tag = GPOINTER_TO_INT(arg);
    SimTime t = sim_now(e);
    g_array_append_val(l->log, tag);
    g_array_append_val(l->times, t);
}

static Log *log_new(void)
{
    Log *l = g_new0(Log, 1);
    l->log = g_array_new(FALSE, FALSE, sizeof(int));
    l->times = g_array_new(FALSE, FALSE, sizeof(SimTime));
    return l;
}

static void log_free(Log *l)
{
    g_array_free(l->log, TRUE);
    g_array_free(l->times, TRUE);
    g_free(l);
}

static void test_time_order_then_schedule_order(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    Log *l = log_new();
    sim_schedule_at(e, 30, log_tag, l, GINT_TO_POINTER(3));
    sim_schedule_at(e, 10, log_tag, l, GINT_TO_POINTER(1));
    sim_schedule_at(e, 20, log_tag, l, GINT_TO_POINTER(20));
    sim_schedule_at(e, 20, log_tag, l, GINT_TO_POINTER(21));
    sim_schedule_at(e, 20, log_tag, l, GINT_TO_POINTER(22));
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    int want[] = {1, 20, 21, 22, 3};
    assert_int_equal(l->log->len, 5);
    for (int i = 0; i < 5; i++)
        assert_int_equal(g_array_index(l->log, int, i), want[i]);
    assert_int_equal(sim_now(e), 30);
    assert_int_equal(sim_engine_events(e), 5);
    log_free(l);
    sim_engine_free(e);
}

/* An event scheduled at the current time from a handler runs after the
 * events already pending at that time (its seq is larger). */
static void spawn_same_time(SimEngine *e, void *ctx, void *arg)
{
    log_tag(e, ctx, arg);
    if (GPOINTER_TO_INT(arg) == 1)
        sim_schedule_in(e, 0, log_tag, ctx, GINT_TO_POINTER(9));
}

static void test_zero_delay_runs_after_pending_ties(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    Log *l = log_new();
    sim_schedule_at(e, 5, spawn_same_time, l, GINT_TO_POINTER(1));
    sim_schedule_at(e, 5, spawn_same_time, l, GINT_TO_POINTER(2));
    sim_schedule_at(e, 6, spawn_same_time, l, GINT_TO_POINTER(3));
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    int want[] = {1, 2, 9, 3};
    assert_int_equal(l->log->len, 4);
    for (int i = 0; i < 4; i++)
        assert_int_equal(g_array_index(l->log, int, i), want[i]);
    log_free(l);
    sim_engine_free(e);
}

static void schedule_huge(SimEngine *e, void *ctx, void *arg)
{
    (void)ctx;
    (void)arg;
    assert_false(sim_schedule_in(e, SIM_TIME_MAX, log_tag, NULL, NULL));
}

static void test_overflow_is_an_error_not_a_wrap(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    sim_schedule_at(e, 100, schedule_huge, NULL, NULL);
    GError *err = NULL;
    assert_false(sim_engine_run(e, SIM_TIME_MAX, &err));
    assert_non_null(err);
    assert_true(g_error_matches(err, SIM_ERROR, SIM_ERROR_OVERFLOW));
    assert_int_equal(sim_error_exit_status(err), 2);
    assert_int_equal(sim_engine_pending(e), 0); /* nothing wrapped in */
    g_error_free(err);
    sim_engine_free(e);
}

static void test_time_helpers(void **state)
{
    (void)state;
    SimTime t = 7;
    assert_false(sim_time_add(SIM_TIME_MAX - 1, 2, &t));
    assert_int_equal(t, 7);
    assert_true(sim_time_add(SIM_TIME_MAX - 2, 2, &t));
    assert_true(t == SIM_TIME_MAX);
    assert_true(sim_time_add_sat(SIM_TIME_MAX, 5) == SIM_TIME_MAX);
    assert_true(sim_time_from_s(350e-6, &t));
    assert_int_equal(t, 350 * SIM_US);
    assert_false(sim_time_from_s(-1.0, &t));
    assert_false(sim_time_from_s(1e300, &t));
    assert_false(sim_time_from_s(NAN, &t));
    assert_int_equal(sim_time_for_bytes(2.8e6, 2.8e6), SIM_S);
    assert_int_equal(sim_time_for_bytes(1, 3e12), 1); /* never zero */
}

static void test_run_until_and_stop(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    Log *l = log_new();
    for (int i = 1; i <= 10; i++)
        sim_schedule_at(e, (SimTime)i * 10, log_tag, l, GINT_TO_POINTER(i));
    assert_true(sim_engine_run(e, 55, NULL));
    assert_int_equal(l->log->len, 5);
    assert_int_equal(sim_now(e), 55);
    assert_int_equal(sim_engine_pending(e), 5);
    assert_true(sim_engine_run(e, 60, NULL)); /* boundary is inclusive */
    assert_int_equal(l->log->len, 6);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(l->log->len, 10);
    log_free(l);
    sim_engine_free(e);
}

static void stop_now(SimEngine *e, void *ctx, void *arg)
{
    log_tag(e, ctx, arg);
    sim_engine_stop(e);
}

static void test_stop_leaves_rest_pending(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    Log *l = log_new();
    sim_schedule_at(e, 1, log_tag, l, GINT_TO_POINTER(1));
    sim_schedule_at(e, 2, stop_now, l, GINT_TO_POINTER(2));
    sim_schedule_at(e, 3, log_tag, l, GINT_TO_POINTER(3));
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(l->log->len, 2);
    assert_int_equal(sim_engine_pending(e), 1);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(l->log->len, 3);
    log_free(l);
    sim_engine_free(e);
}

/* A chain in which every event schedules two: the pool grows far past its
 * first block without losing or reordering anything. */
typedef struct {
    uint64_t ran;
    SimTime last;
} Fan;

static void fan_out(SimEngine *e, void *ctx, void *arg)
{
    Fan *f = ctx;
    uintptr_t depth = (uintptr_t)arg;
    assert_true(sim_now(e) >= f->last);
    f->last = sim_now(e);
    f->ran++;
    if (depth < 16) {
        sim_schedule_in(e, 3, fan_out, f, (void *)(depth + 1));
        sim_schedule_in(e, 5, fan_out, f, (void *)(depth + 1));
    }
}

static void test_pool_grows(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    Fan f = {0, 0};
    sim_schedule_at(e, 0, fan_out, &f, (void *)0);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(f.ran, (1u << 17) - 1);
    sim_engine_free(e);
}

static void test_entities_phases_and_rng_streams(void **state)
{
    (void)state;
    SimEngine *a = sim_engine_new(99), *b = sim_engine_new(99);
    uint32_t a0 = sim_entity_add(a, "n0"), a1 = sim_entity_add(a, "n1");
    uint32_t b0 = sim_entity_add(b, "n0");
    assert_int_equal(a0, 0);
    assert_int_equal(a1, 1);
    assert_string_equal(sim_entity_name(a, a1), "n1");
    /* same (seed, id) -> same stream, whatever else was drawn */
    sim_rng_u64(sim_entity_rng(a, a1));
    assert_true(sim_rng_u64(sim_entity_rng(a, a0)) ==
                sim_rng_u64(sim_entity_rng(b, b0)));
    assert_true(sim_rng_u64(sim_entity_rng(a, a0)) !=
                sim_rng_u64(sim_entity_rng(a, a1)));
    unsigned p = sim_engine_phase(a, "merge");
    assert_int_equal(sim_engine_phase(a, "merge"), p);
    assert_int_not_equal(sim_engine_phase(a, "zbuf"), p);
    assert_string_equal(sim_engine_phase_name(a, p), "merge");
    assert_true(sim_engine_seed(a) == 99);
    sim_engine_free(a);
    sim_engine_free(b);
    sim_engine_free(NULL);
}

typedef struct {
    int calls;
} Prog;

static void on_progress(SimEngine *e, void *ctx)
{
    (void)e;
    ((Prog *)ctx)->calls++;
}

static void test_progress_every_n_events(void **state)
{
    (void)state;
    SimEngine *e = sim_engine_new(1);
    Prog p = {0};
    sim_engine_set_progress(e, 100, on_progress, &p);
    Log *l = log_new();
    for (int i = 0; i < 1000; i++)
        sim_schedule_at(e, (SimTime)i, log_tag, l, NULL);
    assert_true(sim_engine_run(e, SIM_TIME_MAX, NULL));
    assert_int_equal(p.calls, 10);
    log_free(l);
    sim_engine_free(e);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_time_order_then_schedule_order),
        cmocka_unit_test(test_zero_delay_runs_after_pending_ties),
        cmocka_unit_test(test_overflow_is_an_error_not_a_wrap),
        cmocka_unit_test(test_time_helpers),
        cmocka_unit_test(test_run_until_and_stop),
        cmocka_unit_test(test_stop_leaves_rest_pending),
        cmocka_unit_test(test_pool_grows),
        cmocka_unit_test(test_entities_phases_and_rng_streams),
        cmocka_unit_test(test_progress_every_n_events),
    };
    return cmocka_run_group_tests_name("engine", tests, NULL, NULL);
}
