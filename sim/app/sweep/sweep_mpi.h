/* sweep_mpi.h — sweeps across machines with Open MPI.
 *
 * Under `mpirun -np N pgsim sweep ...` rank 0 is the master: it owns the
 * results log and hands point indices, one at a time, to ranks 1..N-1
 * (dynamic master-worker: a rank gets its next point when it returns a
 * line).  Workers run each point in a forked child, like the local pool,
 * and send back its JSON line.  Rows therefore equal a local run's.
 *
 * Compiled in when PGSIM_HAVE_MPI is defined; otherwise
 * sweep_mpi_launched() is FALSE and nothing else may be called.
 */
#ifndef PGSIM_APP_SWEEP_SWEEP_MPI_H
#define PGSIM_APP_SWEEP_SWEEP_MPI_H

#include "sim/app/sweep/sweep_run.h"

/* TRUE when MPI support is built in and this process was started by
 * mpirun (OMPI_COMM_WORLD_SIZE or PMIX_RANK in the environment). */
gboolean sweep_mpi_launched(void);
/* MPI_Init; *rank and *size of MPI_COMM_WORLD. */
void sweep_mpi_init(int *argc, char ***argv, int *rank, int *size);
void sweep_mpi_finalize(void);
/* Rank 0.  With j == NULL (setup failed) only tells the workers to stop.
 * Otherwise runs every point of j on the workers; FALSE on a log error
 * (the workers are stopped all the same). */
gboolean sweep_mpi_master(SweepJob *j, int size, GError **err);
/* Ranks > 0: run points until the master says stop. */
void sweep_mpi_worker(const SweepSpec *s, SweepRunFn fn);

#endif
