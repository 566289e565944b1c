/* sweep_run.c — running sweep points: one line per point, the master's
 * bookkeeping, and the local pool of forked workers.
 *
 * Pool invariant: at most `jobs` children exist; the parent holds only the
 * read end of each child's pipe, so EOF on it means the child is gone.  A
 * child writes its whole line and exits; the parent reaps it, and turns a
 * non-zero exit, a signal or a missing line into the point's error line.
 * Output order is the log's business (sweep_log_finish sorts).  O(points).
 */
#include "sim/app/sweep/sweep_run.h"
#include "sim/output/json.h"
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- lines ----------------------------------------------------------- */

/* A parameter value: a JSON number when its text is one, else a string. */
static void add_value(JsonBuilder *b, const char *text)
{
    JsonNode *v = js_parse(text, -1, NULL, NULL);
    if (js_is_num(v))
        json_builder_add_value(b, json_node_copy(v));
    else
        js_add_str(b, text);
    if (v)
        json_node_unref(v);
}

/* Opens the point's object: point, repetition, seed, parameter values. */
static JsonBuilder *line_head(const SweepSpec *s, guint i)
{
    SweepPoint pt = sweep_spec_point(s, i);
    JsonBuilder *b = json_builder_new();
    json_builder_begin_object(b);
    js_set_int(b, "point", pt.index);
    js_set_int(b, "repetition", pt.rep);
    js_set_int(b, "seed", (gint64)pt.seed);
    for (guint p = 0; p < s->params->len; p++) {
        const SweepParam *sp = g_ptr_array_index(s->params, p);
        json_builder_set_member_name(b, sp->key);
        add_value(b, sweep_spec_value(s, &pt, p));
    }
    return b;
}

/* Closes the object and returns it as one line ending in '\n'. */
static char *line_finish(JsonBuilder *b)
{
    json_builder_end_object(b);
    char *one = js_finish(b, FALSE);
    char *line = g_strconcat(one, "\n", NULL);
    g_free(one);
    return line;
}

char *sweep_point_error_line(const SweepSpec *s, guint i, const char *msg)
{
    JsonBuilder *b = line_head(s, i);
    js_set_str(b, "status", "error");
    js_set_str(b, "error", msg);
    return line_finish(b);
}

static void put_result(JsonBuilder *b, const SimResult *r)
{
    double umean = 0.0, umax = 0.0; /* idle processors count as 0 */
    double all = (double)r->nodes->len + (double)sim_result_n_idle(r);
    for (guint n = 0; n < r->nodes->len; n++) {
        double u = sim_result_node_util(r, g_ptr_array_index(r->nodes, n));
        umean += u / all;
        umax = MAX(umax, u);
    }
    js_set_num(b, "frames", r->frame_times->len);
    js_set_num(b, "mean_frame_s", sim_result_mean_frame_s(r));
    js_set_num(b, "elapsed_s", sim_time_to_s(r->elapsed));
    js_set_num(b, "events", (double)r->events);
    js_set_num(b, "comm_bytes", (double)r->comm_bytes);
    js_set_num(b, "comm_messages", (double)r->comm_messages);
    js_set_num(b, "util_mean", umean);
    js_set_num(b, "util_max", umax);
    for (guint m = 0; m < r->metrics->len; m++) {
        const SimMetric *sm = g_ptr_array_index(r->metrics, m);
        js_set_num(b, sm->name, sm->value);
    }
}

char *sweep_point_line(const SweepSpec *s, guint i, SweepRunFn fn)
{
    SweepPoint pt = sweep_spec_point(s, i);
    GError *err = NULL;
    SimResult *r = NULL;
    CfgNode *cfg = sweep_spec_config(s, &pt, &err);
    gboolean ok = cfg && fn(cfg, pt.seed, &r, &err);
    cfg_free(cfg);
    if (!ok) {
        char *line =
            sweep_point_error_line(s, i, err ? err->message : "run failed");
        g_clear_error(&err);
        sim_result_free(r);
        return line;
    }
    JsonBuilder *b = line_head(s, i);
    js_set_str(b, "status", "ok");
    js_set_str(b, "error", NULL);
    put_result(b, r);
    sim_result_free(r);
    return line_finish(b);
}

/* ---- children -------------------------------------------------------- */

static G_NORETURN void child_main(const SweepSpec *s, guint i, SweepRunFn fn,
                                  int wfd)
{
    char *line = sweep_point_line(s, i, fn);
    size_t len = strlen(line), off = 0;
    while (off < len) {
        ssize_t w = write(wfd, line + off, len - off);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            _exit(3);
        off += (size_t)w;
    }
    _exit(0);
}

/* Forks a child for point i; returns its pid and the pipe's read end. */
static pid_t spawn_point(const SweepSpec *s, guint i, SweepRunFn fn, int *rfd)
{
    int fds[2];
    if (pipe(fds) != 0)
        return -1;
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        signal(SIGINT, SIG_DFL);
        child_main(s, i, fn, fds[1]);
    }
    close(fds[1]);
    if (pid < 0)
        close(fds[0]);
    *rfd = fds[0];
    return pid;
}

/* Reaps the child and returns the point's line (error line on failure). */
static char *reap(const SweepSpec *s, guint i, pid_t pid, GString *buf)
{
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    char msg[96] = "";
    if (WIFSIGNALED(status))
        g_snprintf(msg, sizeof msg, "worker killed by signal %d (%s)",
                   WTERMSIG(status), g_strsignal(WTERMSIG(status)));
    else if (WEXITSTATUS(status) != 0)
        g_snprintf(msg, sizeof msg, "worker exited with status %d",
                   WEXITSTATUS(status));
    else if (buf->len == 0 || buf->str[buf->len - 1] != '\n' ||
             memchr(buf->str, '\n', buf->len - 1))
        g_strlcpy(msg, "worker wrote no complete line", sizeof msg);
    if (*msg)
        return sweep_point_error_line(s, i, msg);
    return g_strdup(buf->str);
}

static gboolean read_all(int fd, GString *buf)
{
    char chunk[4096];
    for (;;) {
        ssize_t n = read(fd, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return n == 0;
        g_string_append_len(buf, chunk, n);
    }
}

char *sweep_point_isolated(const SweepSpec *s, guint i, SweepRunFn fn)
{
    int fd;
    pid_t pid = spawn_point(s, i, fn, &fd);
    if (pid < 0)
        return sweep_point_error_line(s, i, "cannot fork a worker");
    GString *buf = g_string_new(NULL);
    read_all(fd, buf);
    close(fd);
    char *line = reap(s, i, pid, buf);
    g_string_free(buf, TRUE);
    return line;
}

/* ---- the master's bookkeeping ---------------------------------------- */

void sweep_job_init(SweepJob *j, const SweepSpec *s, SweepLog *log,
                    SweepRunFn fn, gboolean progress)
{
    *j = (SweepJob){.spec = s, .log = log, .fn = fn};
    j->todo = g_array_new(FALSE, FALSE, sizeof(guint));
    for (guint i = 0; i < sweep_spec_points(s); i++)
        if (!log || !sweep_log_done(log, i))
            g_array_append_val(j->todo, i);
    if (progress && j->todo->len) {
        char *label = g_strdup_printf("sweep %s: points", s->name);
        j->bar = rpt_progress_new(j->todo->len, label);
        g_free(label);
        rpt_progress_note(j->bar, "0 failed");
    }
}

void sweep_job_clear(SweepJob *j)
{
    g_array_free(j->todo, TRUE);
    j->todo = NULL;
}

gboolean sweep_job_next(SweepJob *j, guint *i)
{
    if (j->next >= j->todo->len)
        return FALSE;
    *i = g_array_index(j->todo, guint, j->next++);
    return TRUE;
}

static gboolean line_failed(const char *line)
{
    JsonNode *v = js_parse(line, -1, NULL, NULL);
    const char *status = js_str(js_get(v, "status"));
    gboolean failed = status && strcmp(status, "error") == 0;
    if (v)
        json_node_unref(v);
    return failed;
}

gboolean sweep_job_finish(SweepJob *j, const char *line, GError **err)
{
    j->finished++;
    if (line_failed(line)) {
        j->failed++;
        char note[32];
        g_snprintf(note, sizeof note, "%u failed", j->failed);
        rpt_progress_note(j->bar, note);
    }
    rpt_progress_update(j->bar, j->finished);
    return !j->log || sweep_log_append(j->log, line, err);
}

void sweep_job_done(SweepJob *j)
{
    rpt_progress_finish(j->bar);
    j->bar = NULL;
}

/* ---- the local pool -------------------------------------------------- */

typedef struct {
    pid_t pid;
    int fd;
    guint point;
    GString *buf;
} SweepChild;

static gboolean fill_pool(SweepJob *j, GArray *kids, int jobs)
{
    guint i;
    while ((int)kids->len < jobs && sweep_job_next(j, &i)) {
        SweepChild c = {0, -1, i, NULL};
        c.pid = spawn_point(j->spec, i, j->fn, &c.fd);
        if (c.pid < 0)
            return FALSE;
        c.buf = g_string_new(NULL);
        g_array_append_val(kids, c);
    }
    return TRUE;
}

/* Reads what a child sent; on EOF reaps it and records its line. */
static gboolean drain(SweepJob *j, GArray *kids, guint k, gboolean *gone,
                      GError **err)
{
    SweepChild *c = &g_array_index(kids, SweepChild, k);
    char chunk[4096];
    ssize_t n = read(c->fd, chunk, sizeof chunk);
    *gone = FALSE;
    if (n > 0 || (n < 0 && errno == EINTR)) {
        if (n > 0)
            g_string_append_len(c->buf, chunk, n);
        return TRUE;
    }
    close(c->fd);
    char *line = reap(j->spec, c->point, c->pid, c->buf);
    g_string_free(c->buf, TRUE);
    g_array_remove_index_fast(kids, k);
    *gone = TRUE;
    gboolean ok = sweep_job_finish(j, line, err);
    g_free(line);
    return ok;
}

static gboolean poll_kids(SweepJob *j, GArray *kids, GError **err)
{
    struct pollfd *pf = g_new0(struct pollfd, kids->len);
    for (guint k = 0; k < kids->len; k++)
        pf[k] =
            (struct pollfd){g_array_index(kids, SweepChild, k).fd, POLLIN, 0};
    int r = poll(pf, kids->len, -1);
    gboolean ok = TRUE;
    for (guint k = kids->len; ok && r > 0 && k-- > 0;) {
        gboolean gone;
        if (pf[k].revents)
            ok = drain(j, kids, k, &gone, err);
    }
    g_free(pf);
    return ok;
}

static void kill_kids(GArray *kids)
{
    for (guint k = 0; k < kids->len; k++) {
        SweepChild *c = &g_array_index(kids, SweepChild, k);
        kill(c->pid, SIGTERM);
        waitpid(c->pid, NULL, 0);
        close(c->fd);
        g_string_free(c->buf, TRUE);
    }
}

gboolean sweep_run_local(SweepJob *j, int jobs, GError **err)
{
    g_assert(jobs >= 1);
    GArray *kids = g_array_new(FALSE, FALSE, sizeof(SweepChild));
    gboolean ok = TRUE;
    while (ok) {
        if (!fill_pool(j, kids, jobs)) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                        "cannot start a worker process: %s", g_strerror(errno));
            ok = FALSE;
        } else if (kids->len == 0) {
            break;
        } else {
            ok = poll_kids(j, kids, err);
        }
    }
    kill_kids(kids);
    g_array_free(kids, TRUE);
    sweep_job_done(j);
    return ok;
}
