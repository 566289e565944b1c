/* sweep_fake.c — the fake point runner shared by the sweep tests. */
#include "tests/app/sweep/sweep_fake.h"
#include <glib/gstdio.h>
#include <stdlib.h>

static double num_at(const CfgNode *cfg, const char *key)
{
    const CfgNode *n = cfg_path(cfg, key);
    return n ? g_ascii_strtod(cfg_scalar(n), NULL) : 0.0;
}

gboolean sweep_fake_run(const CfgNode *cfg, uint64_t seed, SimResult **out,
                        GError **err)
{
    double a = num_at(cfg, "a"), b = num_at(cfg, "b");
    if (a == 4) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT, "a is 4");
        return FALSE;
    }
    if (a == 5)
        abort();
    SimResult *r = sim_result_new("fake", "none");
    sim_result_add_frame(r, (SimTime)(a * 1000 + b));
    sim_result_set_metric(r, "score", a * 10 + b, "");
    sim_result_set_metric(r, "seedbits", (double)(seed & 0xff), "");
    *out = r;
    return TRUE;
}

void sweep_test_rm_out(char *dir)
{
    const char *files[] = {"results.csv", "results.jsonl", "sweep.fingerprint",
                           "provenance.json"};
    for (int i = 0; i < 4; i++) {
        char *p = g_build_filename(dir, files[i], NULL);
        g_remove(p);
        g_free(p);
    }
    g_rmdir(dir);
    g_free(dir);
}
