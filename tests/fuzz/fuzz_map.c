/* fuzz_map.c — libFuzzer harness: a `--map FILE` of `pgsim replay`
 * (lines "TRACE_PROC TARGET_PROC", docs/traces.md) applied to a fixed
 * 6-processor trace replayed on the iPSC/2 at the analytic fidelity
 * (rpl_target.c's map reader, then the replay on the mapped machine).
 * The input is written to a scratch map file beside the trace.  See
 * fuzz.h. */
#include "sim/app/replay/rpl_replay.h"
#include "tests/fuzz/fuzz.h"
#include <glib/gstdio.h>
#include <stdlib.h>

static const char trace[] = "pgsim-trace 3\nmachine ipsc2\nprocs 6\n"
                            "kind node 0 6 16000000\nphase compute\n"
                            "at 0\nw 0 0 1000 +\ns 1 5 4096 +\nw 2 0 10\n"
                            "on 0\nw 3 0 2000 frame\non 1\nw 5 0 500\n"
                            "s 5 4 64\nw 4 0 7 frame\n";

static char *scratch_dir, *trace_path, *map_path;

static void remove_scratch(void)
{
    g_remove(trace_path);
    g_rmdir(scratch_dir);
    g_free(trace_path);
    g_free(map_path);
    g_free(scratch_dir);
}

static void scratch(void)
{
    if (scratch_dir)
        return;
    scratch_dir = g_dir_make_tmp("pgsim-fuzz-map-XXXXXX", NULL);
    trace_path = g_build_filename(scratch_dir, "t.pgt", NULL);
    map_path = g_build_filename(scratch_dir, "input.map", NULL);
    g_file_set_contents(trace_path, trace, -1, NULL);
    atexit(remove_scratch);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    scratch();
    if (!g_file_set_contents(map_path, (const char *)data, (gssize)size, NULL))
        return 0;
    RplReplayOpts o = {.trace = trace_path, .machine = "ipsc2",
                       .fidelity = "analytic", .map = map_path};
    GError *err = NULL;
    sim_result_free(rpl_replay(&o, &err));
    g_clear_error(&err);
    g_remove(map_path);
    return 0;
}
