/* fuzz_model.c — libFuzzer harness: a machine model (an inline `machine`
 * section), checked (mach_check_section) and then built the way a
 * workload builds it (mach_new_from_cfg at the analytic fidelity, which
 * builds the network).  See fuzz.h. */
#include "sim/core/cfg.h"
#include "sim/core/engine.h"
#include "sim/machine/machine.h"
#include "tests/fuzz/fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_setup();
    char *text = fuzz_text(data, size);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "fuzz.yaml", &err);
    if (root && mach_check_section(root, &err)) {
        SimEngine *eng = sim_engine_new(1);
        mach_free(mach_new_from_cfg(eng, root, "analytic", &err));
        sim_engine_free(eng);
    }
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    return 0;
}
