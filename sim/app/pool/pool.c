/* pool.c — forked worker processes, one per task (pool.h).
 *
 * Invariant: at most `jobs` children exist; the parent holds only the
 * read end of each child's pipe (it closes the write end right after the
 * fork, so later children never inherit it), hence end of file on a pipe
 * means its child has exited or closed it.  A child writes its whole
 * result and exits; the parent reaps it at end of file and turns a
 * non-zero exit or a signal into the task's `fail`.  The parent keeps
 * reading every pipe while children run, so a result larger than a pipe
 * buffer never blocks its child.  O(tasks) forks, O(jobs) per poll.
 */
#include "sim/app/pool/pool.h"
#include "sim/core/error.h"
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct {
    pid_t pid;
    int fd;
    guint task;
    GString *buf;
} PoolChild;

/* ---- the child --------------------------------------------------------- */

static void default_signals(void)
{
    static const int sigs[] = {SIGINT, SIGSEGV, SIGBUS,
                               SIGFPE, SIGILL,  SIGABRT};
    for (guint k = 0; k < G_N_ELEMENTS(sigs); k++)
        signal(sigs[k], SIG_DFL);
}

static G_NORETURN void child_main(const PoolOps *ops, void *ctx, guint task,
                                  int wfd)
{
    default_signals();
    gsize len = 0, off = 0;
    char *out = ops->work(ctx, task, &len);
    while (off < len) {
        ssize_t w = write(wfd, out + off, len - off);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            _exit(3);
        off += (gsize)w;
    }
    _exit(0);
}

/* Forks the child of `task`; its pid, or -1 (errno set). */
static pid_t spawn(const PoolOps *ops, void *ctx, guint task, int *rfd)
{
    int fds[2];
    if (pipe(fds) != 0)
        return -1;
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        child_main(ops, ctx, task, fds[1]);
    }
    int saved = errno;
    close(fds[1]);
    if (pid < 0)
        close(fds[0]);
    *rfd = fds[0];
    errno = saved;
    return pid;
}

/* ---- the parent -------------------------------------------------------- */

/* Why a child with this wait status failed (g_free), or NULL. */
static char *failure(int status)
{
    if (WIFSIGNALED(status))
        return g_strdup_printf("worker killed by signal %d (%s)",
                               WTERMSIG(status), g_strsignal(WTERMSIG(status)));
    if (WEXITSTATUS(status) != 0)
        return g_strdup_printf("worker exited with status %d",
                               WEXITSTATUS(status));
    return NULL;
}

static gboolean fill(const PoolOps *ops, void *ctx, GArray *kids, int jobs,
                     GError **err)
{
    guint task;
    while ((int)kids->len < jobs && ops->next(ctx, &task)) {
        PoolChild c = {0, -1, task, NULL};
        c.pid = spawn(ops, ctx, task, &c.fd);
        if (c.pid < 0) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                        "cannot start a worker process: %s", g_strerror(errno));
            return FALSE;
        }
        c.buf = g_string_new(NULL);
        g_array_append_val(kids, c);
    }
    return TRUE;
}

/* Reads what child k sent; at end of file reaps it and reports it. */
static gboolean drain(const PoolOps *ops, void *ctx, GArray *kids, guint k,
                      GError **err)
{
    PoolChild *c = &g_array_index(kids, PoolChild, k);
    char chunk[4096];
    ssize_t n = read(c->fd, chunk, sizeof chunk);
    if (n > 0 || (n < 0 && errno == EINTR)) {
        if (n > 0)
            g_string_append_len(c->buf, chunk, n);
        return TRUE;
    }
    close(c->fd);
    int status = 0;
    while (waitpid(c->pid, &status, 0) < 0 && errno == EINTR)
        ;
    PoolChild done = *c;
    g_array_remove_index_fast(kids, k);
    char *why = failure(status);
    gboolean ok = ops->done(ctx, done.task, done.buf, why, err);
    g_free(why);
    g_string_free(done.buf, TRUE);
    return ok;
}

static gboolean poll_kids(const PoolOps *ops, void *ctx, GArray *kids,
                          GError **err)
{
    struct pollfd *pf = g_new0(struct pollfd, kids->len);
    for (guint k = 0; k < kids->len; k++)
        pf[k] =
            (struct pollfd){g_array_index(kids, PoolChild, k).fd, POLLIN, 0};
    int r = poll(pf, kids->len, -1);
    gboolean ok = TRUE;
    /* from the end, so that removing child k moves only a polled one */
    for (guint k = kids->len; ok && r > 0 && k-- > 0;)
        if (pf[k].revents)
            ok = drain(ops, ctx, kids, k, err);
    g_free(pf);
    return ok;
}

static void kill_kids(GArray *kids)
{
    for (guint k = 0; k < kids->len; k++) {
        PoolChild *c = &g_array_index(kids, PoolChild, k);
        kill(c->pid, SIGTERM);
        while (waitpid(c->pid, NULL, 0) < 0 && errno == EINTR)
            ;
        close(c->fd);
        g_string_free(c->buf, TRUE);
    }
}

gboolean pool_run(const PoolOps *ops, void *ctx, int jobs, GError **err)
{
    g_assert(jobs >= 1);
    GArray *kids = g_array_new(FALSE, FALSE, sizeof(PoolChild));
    gboolean ok = TRUE;
    while (ok) {
        ok = fill(ops, ctx, kids, jobs, err);
        if (ok && kids->len == 0)
            break;
        if (ok)
            ok = poll_kids(ops, ctx, kids, err);
    }
    kill_kids(kids);
    g_array_free(kids, TRUE);
    return ok;
}

/* ---- every result, by task --------------------------------------------- */

typedef struct {
    guint n, next;
    const guint *order;
    PoolWorkFn work;
    void *ctx;
    PoolResult *res;
} PoolMap;

static gboolean map_next(void *ctx, guint *task)
{
    PoolMap *m = ctx;
    if (m->next >= m->n)
        return FALSE;
    *task = m->order ? m->order[m->next] : m->next;
    m->next++;
    g_assert(*task < m->n);
    return TRUE;
}

static char *map_work(void *ctx, guint task, gsize *len)
{
    PoolMap *m = ctx;
    return m->work(m->ctx, task, len);
}

static gboolean map_done(void *ctx, guint task, const GString *out,
                         const char *fail, GError **err)
{
    (void)err;
    PoolMap *m = ctx;
    g_assert(!m->res[task].out); /* each task once */
    m->res[task].out = g_string_new_len(out->str, (gssize)out->len);
    m->res[task].fail = g_strdup(fail);
    return TRUE;
}

PoolResult *pool_map(guint n, const guint *order, PoolWorkFn work, void *ctx,
                     int jobs, GError **err)
{
    static const PoolOps ops = {map_next, map_work, map_done};
    PoolMap m = {n, 0, order, work, ctx, g_new0(PoolResult, MAX(n, 1))};
    if (!pool_run(&ops, &m, jobs, err)) {
        pool_results_free(m.res, n);
        return NULL;
    }
    return m.res;
}

void pool_results_free(PoolResult *r, guint n)
{
    if (!r)
        return;
    for (guint i = 0; i < n; i++) {
        if (r[i].out)
            g_string_free(r[i].out, TRUE);
        g_free(r[i].fail);
    }
    g_free(r);
}
