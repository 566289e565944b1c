/* test_record.c — recorded completions and display-refresh waits
 * (sim/core/record.h): the next multiple of a period, exactly, saturating
 * at the end of the clock; a wait without a recorder is a plain event at
 * that multiple; with one, the recorder hears of the wait, then of the
 * completion around the handler, at the same instant. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/memlimit.h"
#include "sim/core/record.h"
#include "tests/core/rec_log.h"
#include "tests/support.h"

static void test_refresh_at(void **state)
{
    (void)state;
    assert_int_equal(sim_refresh_at(0, 10), 0);
    assert_int_equal(sim_refresh_at(1, 10), 10);
    assert_int_equal(sim_refresh_at(9, 10), 10);
    assert_int_equal(sim_refresh_at(10, 10), 10);
    assert_int_equal(sim_refresh_at(11, 10), 20);
    assert_int_equal(sim_refresh_at(29, 7), 35);
    assert_int_equal(sim_refresh_at(35, 7), 35);
    assert_int_equal(sim_refresh_at(5, 1), 5);
    assert_int_equal(sim_refresh_at(3, 1000), 1000);
    /* the last whole multiple below 2^64 is still exact; past it the
     * clock's end */
    SimTime top = SIM_TIME_MAX / 10 * 10;
    assert_int_equal(sim_refresh_at(top, 10), top);
    assert_int_equal(sim_refresh_at(top - 9, 10), top);
    assert_int_equal(sim_refresh_at(top + 1, 10), SIM_TIME_MAX);
    assert_int_equal(sim_refresh_at(SIM_TIME_MAX, 1), SIM_TIME_MAX);
    assert_int_equal(sim_refresh_at(SIM_TIME_MAX, SIM_TIME_MAX), SIM_TIME_MAX);
}

typedef struct {
    RecLog *log; /* NULL: no recorder */
    SimTime period;
    uint32_t node;
    gboolean with_done;
    SimTime done_at;
    int done_runs;
} Wait;

static void waited(SimEngine *eng, void *ctx, void *arg)
{
    Wait *w = ctx;
    assert_ptr_equal(arg, &w->period);
    w->done_at = sim_now(eng);
    w->done_runs++;
    if (w->log)
        rec_log_note(w->log, "done @%" G_GUINT64_FORMAT, sim_now(eng));
}

static void start_wait(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    Wait *w = ctx;
    assert_true(sim_wait_refresh(eng, w->node, w->period,
                                 w->with_done ? waited : NULL, w,
                                 &w->period));
}

/* Runs one wait that starts at `at`; returns the engine's end time. */
static SimTime run_wait(Wait *w, SimTime at)
{
    SimEngine *eng = sim_engine_new(1);
    if (w->log)
        sim_engine_set_recorder(eng, &w->log->rec);
    sim_schedule_at(eng, at, start_wait, w, NULL);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    SimTime end = sim_now(eng);
    sim_engine_free(eng);
    return end;
}

static void test_wait_without_recorder(void **state)
{
    (void)state;
    Wait w = {.period = 10, .with_done = TRUE};
    assert_int_equal(run_wait(&w, 11), 20);
    assert_int_equal(w.done_at, 20);
    assert_int_equal(w.done_runs, 1);
    w.done_runs = 0;
    assert_int_equal(run_wait(&w, 30), 30); /* on a refresh: no wait */
    assert_int_equal(w.done_at, 30);
    assert_int_equal(w.done_runs, 1);
    Wait none = {.period = 10, .with_done = FALSE};
    assert_int_equal(run_wait(&none, 11), 11); /* nothing scheduled */
}

static void test_wait_recorded(void **state)
{
    (void)state;
    RecLog log;
    rec_log_init(&log);
    Wait w = {.log = &log, .period = 16, .node = 3, .with_done = TRUE};
    assert_int_equal(run_wait(&w, 17), 32);
    assert_string_equal(log.text->str, "refresh @17 n3 every 16 -> 1\n"
                                       "begin 1 @32\n"
                                       "done @32\n"
                                       "end 1\n");
    g_string_truncate(log.text, 0);
    Wait quiet = {.log = &log, .period = 16, .node = 5, .with_done = FALSE};
    assert_int_equal(run_wait(&quiet, 0), 0);
    assert_string_equal(log.text->str, "refresh @0 n5 every 16 -> 2\n"
                                       "begin 2 @0\n"
                                       "end 2\n");
    assert_int_equal(quiet.done_runs, 0);
    rec_log_clear(&log);
}

static void never(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    (void)ctx;
    (void)arg;
    fail_msg("a refused completion ran");
}

/* A completion the engine cannot queue (its event memory over the limit)
 * is refused, and its record freed (the sanitizer build sees a leak). */
static void test_schedule_refused(void **state)
{
    (void)state;
    RecLog log;
    rec_log_init(&log);
    SimEngine *eng = sim_engine_new(1);
    sim_mem_set_limit(1000); /* below the first 1024-event block */
    assert_false(sim_record_schedule_done(eng, &log.rec, 7, 5, never, NULL,
                                          NULL));
    sim_mem_set_limit(0);
    assert_false(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_string_equal(log.text->str, "");
    sim_engine_free(eng);
    assert_true(sim_record_schedule_done(eng = sim_engine_new(1), &log.rec, 7,
                                         5, NULL, NULL, NULL));
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_string_equal(log.text->str, "begin 7 @5\nend 7\n");
    sim_engine_free(eng);
    rec_log_clear(&log);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refresh_at),
        cmocka_unit_test(test_wait_without_recorder),
        cmocka_unit_test(test_wait_recorded),
        cmocka_unit_test(test_schedule_refused),
    };
    return cmocka_run_group_tests_name("record", tests, NULL, NULL);
}
