/* dp_test_model.h — the dpscan costs of a shipped machine model, for
 * tests: found on the model search path and checked by the machine layer
 * (mach_load_model), then read as dpscan reads them from a built machine
 * (dp_model.h).  procs is left 0: a test sets its partition. */
#ifndef PGSIM_TESTS_DP_TEST_MODEL_H
#define PGSIM_TESTS_DP_TEST_MODEL_H

#include "sim/machine/model.h"
#include "sim/workload/dpscan/dp_model.h"

static inline gboolean dp_test_model(const char *name, WlDpMachine *m,
                                     GError **err)
{
    CfgNode *model = mach_load_model(name, err);
    gboolean ok = model && wl_dp_machine_from_model(model, NULL, m, err);
    cfg_free(model);
    return ok;
}

#endif
