/* cmd_sweep.c — `pgsim sweep SWEEP.yaml [-j N] [--out DIR] [--resume]
 * [--quiet] [--strict]`.
 *
 * Expands the sweep (sweep_spec.c), runs the points not yet done locally
 * in up to N worker processes (default: the number of cores) or, under
 * mpirun, over the MPI ranks (sweep_mpi.c), then writes the ordered
 * results.csv / results.jsonl and the charts of the `plots:` section into
 * DIR (default out/<sweep name>), holding DIR's lock (sweep_lock.h) from
 * start to end.  Exit status: 0 when every point
 * succeeded, 1 when some point failed (its row holds the error) or a chart
 * could not be drawn, 2 on bad input.
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/sweep/sweep_lock.h"
#include "sim/app/sweep/sweep_mpi.h"
#include "sim/run/run.h"
#include <stdio.h>
#include <string.h>
#include <unistd.h>

typedef struct {
    int jobs;
    char *out_dir;
    gboolean resume;
    gboolean quiet;
    gboolean strict;
} SweepOpts;

/* --strict: a point that does not fit the machine is that point's error.
 * A process-wide flag because a SweepRunFn takes no context; forked and
 * MPI workers parse the same options. */
static gboolean strict_memory;

/* Runs one point's config through the run-config loader (the same
 * checks as `pgsim run`, so a bad value is that point's located error). */
static gboolean run_config(const CfgNode *cfg, uint64_t seed, SimResult **out,
                           GError **err)
{
    CfgRun *run = cfg_run_from_tree(cfg_copy(cfg), NULL, err);
    if (!run)
        return FALSE;
    g_assert(run->seed == seed);
    CfgRunOpts opts = {.out_dir = NULL, .quiet = TRUE, .progress = FALSE};
    *out = cfg_run_exec(run, &opts, err);
    cfg_run_free(run);
    char *note = *out && strict_memory ? sim_result_mem_note(*out) : NULL;
    if (note) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "%s (--strict)", note);
        g_clear_pointer(out, sim_result_free);
        g_free(note);
    }
    return *out != NULL;
}

/* FALSE when the caller should return *status (help, or a bad option). */
static gboolean parse_opts(SweepOpts *o, int *argc, char ***argv, int *status)
{
    GOptionEntry entries[] = {
        {"jobs", 'j', 0, G_OPTION_ARG_INT, &o->jobs,
         "worker processes (default: the number of cores)", "N"},
        {"out", 0, 0, G_OPTION_ARG_FILENAME, &o->out_dir,
         "output directory (default out/<sweep name>)", "DIR"},
        {"resume", 0, 0, G_OPTION_ARG_NONE, &o->resume,
         "continue an interrupted sweep in DIR", NULL},
        {"quiet", 'q', 0, G_OPTION_ARG_NONE, &o->quiet, "no progress bar",
         NULL},
        {"strict", 0, 0, G_OPTION_ARG_NONE, &o->strict,
         "a point that does not fit the machine (per-node memory above the "
         "model's) fails, instead of memory_fits 0 in its row",
         NULL},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    if (!cli_parse("sweep", "SWEEP.yaml",
                   "Runs a parameter sweep (docs/sweeps.md): locally with "
                   "-j worker processes, or over the ranks of mpirun.",
                   entries, argc, argv, status))
        return FALSE;
    *status = 2;
    if (!cli_want_args("sweep", "SWEEP.yaml", *argc, *argv, 1))
        return FALSE;
    if (o->jobs < 0) {
        fprintf(stderr,
                "pgsim sweep: -j: found %d, expected 0 (one job per "
                "core) or a positive count\n",
                o->jobs);
        return FALSE;
    }
    if (o->jobs == 0)
        o->jobs = (int)g_get_num_processors();
    strict_memory = o->strict;
    return TRUE;
}

static char *out_dir_for(const SweepOpts *o, const SweepSpec *s)
{
    return o->out_dir ? g_strdup(o->out_dir)
                      : g_build_filename("out", s->name, NULL);
}

/* The rows of t a chart's where ("K=V, K=V"; NULL: t itself) keeps: a
 * new table, or NULL with *err. */
static DataTable *where_rows(DataTable *t, const char *where, GError **err)
{
    if (!where)
        return t;
    DataTable *k = dt_new_like(t);
    for (guint r = 0; r < t->rows->len; r++)
        dt_copy_row(k, t, r);
    char **items = g_strsplit(where, ", ", -1);
    for (guint i = 0; k && items[i]; i++)
        if (!cli_keep_where(&k, items[i], err)) {
            if (k)
                dt_free(k);
            k = NULL;
        }
    g_strfreev(items);
    return k;
}

/* Writes the ordered outputs and the charts; counts failed rows. */
static gboolean finish(const SweepSpec *s, const char *dir, guint *failed,
                       guint *charts_failed, GError **err)
{
    DataTable *t = NULL;
    if (!sweep_log_finish(dir, s, &t, err))
        return FALSE;
    int sc = dt_col(t, "status");
    *failed = 0;
    for (guint r = 0; r < t->rows->len; r++)
        *failed += strcmp(dt_cell(t, r, sc), "ok") != 0;
    /* a chart that cannot be drawn (every point failed ...) is reported
     * but does not hide the results */
    for (guint p = 0; p < s->plots->len; p++) {
        const PlotSpec *ps = g_ptr_array_index(s->plots, p);
        GError *e = NULL;
        DataTable *kept = where_rows(t, ps->where, &e);
        if (!kept || !plot_render(ps, kept, dir, &e)) {
            fprintf(stderr, "pgsim sweep: chart %s not drawn: %s\n", ps->name,
                    e->message);
            g_error_free(e);
            *charts_failed += 1;
        }
        if (kept != t)
            dt_free(kept);
    }
    dt_free(t);
    return TRUE;
}

static int report(const SweepSpec *s, const char *dir, guint ran, GError *err)
{
    guint failed = 0, charts_failed = 0;
    if (!err)
        finish(s, dir, &failed, &charts_failed, &err);
    if (err)
        return cli_fail(err);
    printf("sweep %s: %u points (%u run now), %u failed; %s/results.csv\n",
           s->name, sweep_spec_points(s), ran, failed, dir);
    return failed || charts_failed ? 1 : 0;
}

/* Rank 0 (or the only process): runs the points not yet done, locally or
 * on the MPI workers, then writes the outputs. */
static int run_master(const SweepSpec *s, const SweepOpts *o, int size)
{
    GError *err = NULL;
    char *dir = out_dir_for(o, s);
    /* another sweep may not write to dir until this one has finished */
    char *fp = sweep_spec_fingerprint(s);
    SweepLock *lock = sweep_lock_take(dir, fp, &err);
    g_free(fp);
    SweepLog *log = lock ? sweep_log_open(dir, s, o->resume, &err) : NULL;
    guint ran = 0;
    if (!log && size > 1)
        sweep_mpi_master(NULL, size, NULL); /* stop the workers */
    if (log) {
        SweepJob j;
        sweep_job_init(&j, s, log, run_config,
                       !o->quiet && isatty(STDERR_FILENO));
        if (size > 1)
            sweep_mpi_master(&j, size, &err);
        else
            sweep_run_local(&j, o->jobs, &err);
        ran = j.finished;
        sweep_job_clear(&j);
        sweep_log_close(log);
    }
    int st = report(s, dir, ran, err);
    sweep_lock_release(lock);
    g_free(dir);
    return st;
}

static int with_spec(const char *path, const SweepOpts *o, int rank, int size)
{
    GError *err = NULL;
    SweepSpec *s = sweep_spec_load(path, &err);
    if (!s && rank > 0) {
        int st = sim_error_exit_status(err);
        g_error_free(err);
        return st;
    }
    if (!s)
        return cli_fail(err);
    int st = 0;
    if (rank > 0)
        sweep_mpi_worker(s, run_config);
    else
        st = run_master(s, o, size);
    sweep_spec_free(s);
    return st;
}

int cmd_sweep(int argc, char **argv)
{
    SweepOpts o = {0};
    int rank = 0, size = 1, st = 0;
    gboolean mpi = sweep_mpi_launched();
    if (mpi)
        sweep_mpi_init(&argc, &argv, &rank, &size);
    if (rank > 0)
        o.quiet = TRUE;
    if (parse_opts(&o, &argc, &argv, &st))
        st = with_spec(argv[1], &o, rank, size);
    if (mpi)
        sweep_mpi_finalize();
    g_free(o.out_dir);
    return st;
}
