/* fuzz_trace.c — libFuzzer harness: a replay trace (docs/traces.md),
 * pgsim's own format or a SimGrid one, read and replayed on the iPSC/2
 * at the analytic fidelity (rpl_replay: the check pass, then the
 * streaming replay).  The reader works on files, so each input is
 * written to one scratch file first.  See fuzz.h. */
#include "sim/app/replay/rpl_replay.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    const char *path = fuzz_scratch("pgsim-fuzz-trace-XXXXXX", "input.pgt");
    if (!g_file_set_contents(path, (const char *)data, (gssize)size, NULL))
        return 0;
    RplReplayOpts o = {.trace = path, .machine = "ipsc2",
                       .fidelity = "analytic"};
    GError *err = NULL;
    sim_result_free(rpl_replay(&o, &err));
    g_clear_error(&err);
    g_remove(path);
    return 0;
}
