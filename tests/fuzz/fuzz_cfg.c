/* fuzz_cfg.c — libFuzzer harness: a whole run config, loaded and checked
 * as `pgsim validate` loads it (cfg_load_string + cfg_run_from_tree:
 * overrides, schema, run, workload parser, machine section, scene,
 * unknown keys).  See fuzz.h. */
#include "sim/run/run.h"
#include "sim/core/cfg.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    char *text = fuzz_text(data, size);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "fuzz.yaml", &err);
    if (root)
        cfg_run_free(cfg_run_from_tree(root, NULL, &err));
    g_clear_error(&err);
    g_free(text);
    return 0;
}
