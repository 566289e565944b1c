/* tiny_rec.h — the fixture machine-layer suites share: an engine, the
 * "tiny" model (tests/data/models/tiny.yaml) built analytic, and a
 * logging recorder (tests/core/rec_log.h) set on the engine. */
#ifndef PGSIM_TESTS_TINY_REC_H
#define PGSIM_TESTS_TINY_REC_H

#include "sim/machine/machine.h"
#include "tests/core/rec_log.h"

typedef struct {
    SimEngine *eng;
    MachMachine *m;
    RecLog log;
} TinyRec;

/* cmocka set-up and tear-down: *state is the TinyRec. */
int tiny_rec_setup(void **state);
int tiny_rec_teardown(void **state);

#endif
