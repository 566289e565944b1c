/* sweep_fake.h — a fake SweepRunFn for sweep tests: metrics computed from
 * the config's `a` and `b` and the seed; a == 4 fails, a == 5 aborts. */
#ifndef PGSIM_TESTS_SWEEP_FAKE_H
#define PGSIM_TESTS_SWEEP_FAKE_H

#include "sim/app/sweep/sweep_run.h"

gboolean sweep_fake_run(const CfgNode *cfg, uint64_t seed, SimResult **out,
                        GError **err);

/* Removes a sweep output directory and frees the path. */
void sweep_test_rm_out(char *dir);

#endif
