/* rpl_fixture.h — a recorded trace for replay tests: runs a config with
 * a recorder and writes its trace into a fresh temporary directory. */
#ifndef PGSIM_TESTS_RPL_FIXTURE_H
#define PGSIM_TESTS_RPL_FIXTURE_H

#include "sim/run/run.h"

typedef struct {
    char *dir, *path; /* the temporary directory and the trace in it */
    SimResult *res;   /* the recorded run's result */
    uint64_t actions; /* actions recorded */
    guint unplaced;   /* frames no action could mark */
} RplFixture;

/* Records config (with overrides sets, may be NULL) to dir/name; fails
 * the test on any error. */
void rpl_fixture_record(RplFixture *f, const char *config,
                        const char *const *sets, const char *name);
/* Removes the trace and its directory, frees the result. */
void rpl_fixture_clear(RplFixture *f);

#endif
