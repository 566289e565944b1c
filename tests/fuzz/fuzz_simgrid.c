/* fuzz_simgrid.c — libFuzzer harness: a SimGrid time-independent trace
 * (rpl_sgparse.h) read and replayed on a 4-node iPSC/2 at the analytic
 * fidelity with a flop cost, so computes, point-to-point messages and
 * collectives all run (rpl_replay_simgrid: the scan, then the replay).
 * Inputs go straight to the SimGrid reader, whatever their first line.
 * The reader works on files, so each input is written to one scratch
 * file first.  See fuzz.h. */
#include "sim/app/replay/rpl_simgrid.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *sets[] = {"machine.nodes.node.costs.flop=1 ns", NULL};
    fuzz_setup();
    const char *path = fuzz_scratch("pgsim-fuzz-simgrid-XXXXXX", "input.txt");
    if (!g_file_set_contents(path, (const char *)data, (gssize)size, NULL))
        return 0;
    RplReplayOpts o = {.trace = path, .machine = "ipsc2", .nodes = 4,
                       .fidelity = "analytic", .sets = sets};
    GError *err = NULL;
    sim_result_free(rpl_replay_simgrid(&o, &err));
    g_clear_error(&err);
    g_remove(path);
    return 0;
}
