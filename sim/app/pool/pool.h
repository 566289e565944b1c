/* pool.h — a pool of forked worker processes, one process per task.
 *
 * The parent hands out tasks (`next`) and forks one child per task, at
 * most `jobs` alive at once.  A child runs `work`, writes the bytes it
 * returns to a pipe and exits; the parent reads every child's pipe as it
 * fills (poll), reaps the child at end of file and calls `done` with what
 * the child wrote and, when it did not exit with status 0, why ("worker
 * killed by signal 11 (Segmentation fault)", "worker exited with status
 * 3").  So a task that crashes or aborts fails alone, the others go on,
 * and tasks need not be thread-safe.  `done` runs in the order children
 * end; the task index says which one ended.  Sweeps (sim/app/sweep/) and
 * `pgsim reproduce -j` (sim/app/cli/cmd_reproduce.c) both run on it.
 *
 * A child restores the default action of SIGINT and of the crash signals
 * (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT), so that it dies of its own
 * crash whatever handlers the parent had.  Cost: one fork and one pipe
 * per task; O(jobs) per poll.
 */
#ifndef PGSIM_APP_POOL_POOL_H
#define PGSIM_APP_POOL_POOL_H

#include <glib.h>

/* Child side: the result of `task`, a new buffer of *len bytes (g_free;
 * the child exits right after writing it). */
typedef char *(*PoolWorkFn)(void *ctx, guint task, gsize *len);

typedef struct {
    /* Parent: the next task to start; FALSE when none is left. */
    gboolean (*next)(void *ctx, guint *task);
    PoolWorkFn work;
    /* Parent: `task` ended.  out (borrowed) holds the bytes it wrote;
     * fail is NULL when it exited with status 0, else why.  FALSE with
     * *err stops the pool. */
    gboolean (*done)(void *ctx, guint task, const GString *out,
                     const char *fail, GError **err);
} PoolOps;

/* Runs tasks until next() has none left and every child has ended.
 * FALSE with *err when a worker cannot be started or done() failed; the
 * children still running are then killed (SIGTERM) and reaped. */
gboolean pool_run(const PoolOps *ops, void *ctx, int jobs, GError **err);

/* One task's outcome: what it wrote, and why it failed (NULL if it
 * exited with status 0). */
typedef struct {
    GString *out;
    char *fail;
} PoolResult;

/* Runs tasks 0 .. n - 1 with `work`, starting them in the order `order`
 * (a permutation of 0 .. n - 1; NULL: ascending).  Returns n results
 * indexed by task, whatever order they ended in (pool_results_free), or
 * NULL with *err when a worker cannot be started. */
PoolResult *pool_map(guint n, const guint *order, PoolWorkFn work, void *ctx,
                     int jobs, GError **err);
void pool_results_free(PoolResult *r, guint n);

#endif
