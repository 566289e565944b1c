/* sweep_mpi.c — dynamic master-worker distribution of sweep points over
 * Open MPI ranks.
 *
 * Protocol on MPI_COMM_WORLD: master -> worker TAG_WORK (one unsigned:
 * the point index) or TAG_STOP (empty); worker -> master TAG_LINE (the
 * point's JSON line as chars, without NUL).  Invariant: each worker has
 * at most one point outstanding, and every worker receives exactly one
 * TAG_STOP, so MPI_Finalize never waits on a message in flight.
 * Messages: 2 per point plus 1 per worker.
 */
#include "sim/app/sweep/sweep_mpi.h"
#include <stdlib.h>
#include <string.h>

#ifdef PGSIM_HAVE_MPI
#include <mpi.h>

enum { TAG_WORK = 1, TAG_STOP = 2, TAG_LINE = 3 };

gboolean sweep_mpi_launched(void)
{
    return g_getenv("OMPI_COMM_WORLD_SIZE") || g_getenv("PMIX_RANK");
}

void sweep_mpi_init(int *argc, char ***argv, int *rank, int *size)
{
    MPI_Init(argc, argv);
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
}

void sweep_mpi_finalize(void)
{
    MPI_Finalize();
}

/* Sends the worker its next point, or stop; returns TRUE if work went. */
static gboolean feed(SweepJob *j, int worker)
{
    unsigned idx;
    if (j && sweep_job_next(j, &idx)) {
        MPI_Send(&idx, 1, MPI_UNSIGNED, worker, TAG_WORK, MPI_COMM_WORLD);
        return TRUE;
    }
    MPI_Send(NULL, 0, MPI_CHAR, worker, TAG_STOP, MPI_COMM_WORLD);
    return FALSE;
}

static char *recv_line(int *from)
{
    MPI_Status st;
    int n = 0;
    MPI_Probe(MPI_ANY_SOURCE, TAG_LINE, MPI_COMM_WORLD, &st);
    MPI_Get_count(&st, MPI_CHAR, &n);
    char *line = g_malloc((size_t)n + 1);
    MPI_Recv(line, n, MPI_CHAR, st.MPI_SOURCE, TAG_LINE, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    line[n] = '\0';
    *from = st.MPI_SOURCE;
    return line;
}

gboolean sweep_mpi_master(SweepJob *j, int size, GError **err)
{
    int busy = 0;
    gboolean ok = TRUE;
    for (int w = 1; w < size; w++)
        busy += feed(j, w);
    while (busy > 0) {
        int from;
        char *line = recv_line(&from);
        busy--;
        if (ok && !sweep_job_finish(j, line, err))
            ok = FALSE; /* keep draining, but hand out no more work */
        g_free(line);
        busy += feed(ok ? j : NULL, from);
    }
    if (j)
        sweep_job_done(j);
    return ok;
}

void sweep_mpi_worker(const SweepSpec *s, SweepRunFn fn)
{
    for (;;) {
        MPI_Status st;
        unsigned idx = 0;
        MPI_Recv(&idx, 1, MPI_UNSIGNED, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
        if (st.MPI_TAG == TAG_STOP)
            return;
        char *line = sweep_point_isolated(s, idx, fn);
        MPI_Send(line, (int)strlen(line), MPI_CHAR, 0, TAG_LINE,
                 MPI_COMM_WORLD);
        g_free(line);
    }
}

#else /* !PGSIM_HAVE_MPI */

gboolean sweep_mpi_launched(void)
{
    return FALSE;
}

void sweep_mpi_init(int *argc, char ***argv, int *rank, int *size)
{
    (void)argc;
    (void)argv;
    *rank = 0;
    *size = 1;
    g_assert_not_reached();
}

void sweep_mpi_finalize(void)
{
    g_assert_not_reached();
}

gboolean sweep_mpi_master(SweepJob *j, int size, GError **err)
{
    (void)j;
    (void)size;
    (void)err;
    g_assert_not_reached();
}

void sweep_mpi_worker(const SweepSpec *s, SweepRunFn fn)
{
    (void)s;
    (void)fn;
    g_assert_not_reached();
}

#endif
