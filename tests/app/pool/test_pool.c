/* test_pool.c — the process pool (sim/app/pool/pool.h): a task that
 * crashes or exits non-zero fails alone with the reason, results come
 * back by task whatever order the tasks start and end in (one larger
 * than a pipe buffer included), no more than `jobs` workers are alive at
 * once, and a failing done() stops the pool. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <signal.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "sim/app/pool/pool.h"
#include "sim/core/error.h"

/* Task 1 crashes, task 2 exits with status 5, the others answer. */
static char *crashy(void *ctx, guint task, gsize *len)
{
    (void)ctx;
    if (task == 1)
        raise(SIGSEGV);
    if (task == 2)
        _exit(5);
    char *s = g_strdup_printf("task %u", task);
    *len = strlen(s);
    return s;
}

static void test_crash_fails_alone(void **state)
{
    (void)state;
    GError *err = NULL;
    PoolResult *r = pool_map(4, NULL, crashy, NULL, 2, &err);
    g_assert_no_error(err);
    assert_non_null(r);
    assert_null(r[0].fail);
    assert_string_equal(r[0].out->str, "task 0");
    assert_non_null(r[1].fail);
    assert_true(g_str_has_prefix(r[1].fail, "worker killed by signal 11 ("));
    assert_string_equal(r[1].out->str, "");
    assert_string_equal(r[2].fail, "worker exited with status 5");
    assert_null(r[3].fail);
    assert_string_equal(r[3].out->str, "task 3");
    pool_results_free(r, 4);
}

#define BIG (200 * 1000) /* bytes: more than a pipe buffer (64 KiB) */

/* Task t answers "<t>:" then, for task 0, BIG bytes of 'x'. */
static char *labelled(void *ctx, guint task, gsize *len)
{
    (void)ctx;
    GString *s = g_string_new(NULL);
    g_string_printf(s, "%u:", task);
    if (task == 0)
        for (int i = 0; i < BIG; i++)
            g_string_append_c(s, 'x');
    *len = s->len;
    return g_string_free(s, FALSE);
}

static void test_results_by_task(void **state)
{
    (void)state;
    const guint order[] = {5, 3, 1, 0, 2, 4};
    GError *err = NULL;
    PoolResult *r = pool_map(6, order, labelled, NULL, 3, &err);
    g_assert_no_error(err);
    for (guint t = 0; t < 6; t++) {
        char *want = g_strdup_printf("%u:", t);
        assert_null(r[t].fail);
        assert_true(g_str_has_prefix(r[t].out->str, want));
        g_free(want);
    }
    assert_int_equal(r[0].out->len, 2 + BIG);
    assert_int_equal(r[5].out->len, 2);
    pool_results_free(r, 6);
    /* no task at all: an empty result set, not an error */
    r = pool_map(0, NULL, labelled, NULL, 1, &err);
    g_assert_no_error(err);
    assert_non_null(r);
    pool_results_free(r, 0);
}

/* Shared between the test and its workers (MAP_SHARED). */
typedef struct {
    int started, live, peak;
    int jobs;
} Gauge;

/* Counts itself alive; the first wave waits (up to 0.5 s) for one worker
 * more than the bound to start, which a pool keeping the bound never
 * starts, so a pool one over the bound is seen whatever the timing. */
static char *gauged(void *ctx, guint task, gsize *len)
{
    Gauge *g = ctx;
    __atomic_add_fetch(&g->started, 1, __ATOMIC_SEQ_CST);
    int live = __atomic_add_fetch(&g->live, 1, __ATOMIC_SEQ_CST);
    int peak = __atomic_load_n(&g->peak, __ATOMIC_SEQ_CST);
    while (live > peak &&
           !__atomic_compare_exchange_n(&g->peak, &peak, live, FALSE,
                                        __ATOMIC_SEQ_CST, __ATOMIC_SEQ_CST))
        ;
    gint64 until = g_get_monotonic_time() + 500 * 1000;
    while ((int)task < g->jobs &&
           __atomic_load_n(&g->started, __ATOMIC_SEQ_CST) <= g->jobs &&
           g_get_monotonic_time() < until)
        g_usleep(1000);
    __atomic_sub_fetch(&g->live, 1, __ATOMIC_SEQ_CST);
    *len = 0;
    return g_strdup("");
}

static void test_jobs_bound(void **state)
{
    (void)state;
    for (int jobs = 1; jobs <= 3; jobs += 2) {
        Gauge *g = mmap(NULL, sizeof *g, PROT_READ | PROT_WRITE,
                        MAP_SHARED | MAP_ANONYMOUS, -1, 0);
        assert_true(g != MAP_FAILED);
        *g = (Gauge){0, 0, 0, jobs};
        GError *err = NULL;
        PoolResult *r = pool_map(7, NULL, gauged, g, jobs, &err);
        g_assert_no_error(err);
        assert_int_equal(g->started, 7);
        assert_int_equal(g->peak, jobs); /* the bound, and reached */
        for (guint t = 0; t < 7; t++)
            assert_null(r[t].fail);
        pool_results_free(r, 7);
        munmap(g, sizeof *g);
    }
}

/* ---- pool_run: done() can stop the pool ------------------------------- */

typedef struct {
    guint next, handed, done;
} Count;

static gboolean count_next(void *ctx, guint *task)
{
    Count *c = ctx;
    if (c->next >= 10)
        return FALSE;
    *task = c->next++;
    c->handed++;
    return TRUE;
}

static gboolean fail_first(void *ctx, guint task, const GString *out,
                           const char *fail, GError **err)
{
    (void)out;
    (void)fail;
    Count *c = ctx;
    c->done++;
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "task %u: log full", task);
    return FALSE;
}

static char *quick(void *ctx, guint task, gsize *len)
{
    (void)ctx;
    (void)task;
    *len = 2;
    return g_strdup("ok");
}

static void test_done_error_stops(void **state)
{
    (void)state;
    static const PoolOps ops = {count_next, quick, fail_first};
    Count c = {0, 0, 0};
    GError *err = NULL;
    assert_false(pool_run(&ops, &c, 2, &err));
    assert_non_null(err);
    assert_true(g_str_has_suffix(err->message, ": log full"));
    g_error_free(err);
    assert_int_equal(c.done, 1);   /* no done() after the failure */
    assert_int_equal(c.handed, 2); /* and no task handed out after it */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crash_fails_alone),
        cmocka_unit_test(test_results_by_task),
        cmocka_unit_test(test_jobs_bound),
        cmocka_unit_test(test_done_error_stops),
    };
    return cmocka_run_group_tests_name("pool", tests, NULL, NULL);
}
