/* test_run_inputs.c — a run records the files it read (issue 34, point
 * 5; sim/core/inputs.h): each resolved model file by path and the
 * SHA-256 of its bytes, marked shipped or not; a model in a folder given
 * to the runner (`--models DIR`) shadows the shipped one and changes
 * path, hash and the mark; a mesh a scene reads is noted; collectors
 * nest, so a reproduction holds what its runs read.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/output/provenance.h"
#include "sim/run/run.h"
#include "sim/scene/scene_cfg.h"
#include "tests/support.h"

static const char *const small[] = {"workload.resolution=100", NULL};

/* The entry of `kind` (the first); fails the test when there is none. */
static const SimInput *entry(const SimInputs *in, const char *kind)
{
    for (guint i = 0; i < sim_inputs_len(in); i++)
        if (strcmp(sim_inputs_at(in, i)->kind, kind) == 0)
            return sim_inputs_at(in, i);
    fail_msg("no %s among the inputs", kind);
    return NULL;
}

/* Runs configs/quickstart.yaml (small) with `models`; a new result. */
static SimResult *run(const char *const *models)
{
    GError *err = NULL;
    CfgRun *r = cfg_run_load_in("configs/quickstart.yaml", small, models, &err);
    if (!r)
        fail_msg("%s", err->message);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = cfg_run_exec(r, &o, &err);
    assert_non_null(res);
    cfg_run_free(r);
    return res;
}

static void test_shipped_model_recorded(void **state)
{
    (void)state;
    SimResult *res = run(NULL);
    const SimInput *m = entry(res->inputs, "model");
    assert_string_equal(m->path, "models/ipsc2.yaml");
    char *sha = prov_file_sha256("models/ipsc2.yaml");
    assert_string_equal(m->sha256, sha);
    assert_true(m->shipped);
    g_free(sha);
    sim_result_free(res);
}

static void test_models_dir_shadows(void **state)
{
    (void)state;
    char *dir = g_dir_make_tmp("inputs-XXXXXX", NULL);
    char *text = NULL, *path = g_build_filename(dir, "ipsc2.yaml", NULL);
    assert_true(g_file_get_contents("models/ipsc2.yaml", &text, NULL, NULL));
    char *shadow = g_strconcat(text, "# a user's copy\n", NULL);
    assert_true(g_file_set_contents(path, shadow, -1, NULL));
    const char *const models[] = {dir, NULL};
    SimResult *res = run(models);
    const SimInput *m = entry(res->inputs, "model");
    char *real = realpath(path, NULL);
    assert_string_equal(m->path, real);
    char *sha = prov_file_sha256(path), *shipped = prov_file_sha256(
                                            "models/ipsc2.yaml");
    assert_string_equal(m->sha256, sha);
    assert_string_not_equal(m->sha256, shipped);
    assert_false(m->shipped);
    GString *notes = g_string_new(NULL);
    SimProvenance p = {.inputs = res->inputs};
    prov_text_notes(notes, &p);
    assert_non_null(strstr(notes->str, real));
    g_string_free(notes, TRUE);
    free(real);
    g_free(sha);
    g_free(shipped);
    sim_result_free(res);
    support_rm_tree(dir);
    g_free(path);
    g_free(shadow);
    g_free(text);
    g_free(dir);
}

/* A mesh read inside nested collectors lands in both, once each. */
static void test_mesh_nested(void **state)
{
    (void)state;
    SimInputs *outer = sim_inputs_new(), *inner = sim_inputs_new();
    sim_inputs_push(outer);
    sim_inputs_push(inner);
    GError *err = NULL;
    Scene *s = scene_load("tests/data/scene/square.obj", &err);
    assert_non_null(s);
    scene_free(s);
    s = scene_load("tests/data/scene/square.obj", &err);
    scene_free(s);
    sim_inputs_pop(inner);
    sim_inputs_pop(outer);
    assert_int_equal(sim_inputs_len(inner), 1);
    assert_int_equal(sim_inputs_len(outer), 1);
    char *sha = prov_file_sha256("tests/data/scene/square.obj");
    assert_string_equal(entry(outer, "mesh")->sha256, sha);
    assert_string_equal(entry(inner, "mesh")->path,
                        "tests/data/scene/square.obj");
    g_free(sha);
    sim_inputs_free(inner);
    sim_inputs_free(outer);
}

int main(void)
{
    /* The checkout is the data root, as it is for build/pgsim (this binary
     * sits deeper, under build/tests/run). */
    g_setenv("PGSIM_DATA", ".", TRUE);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_model_recorded),
        cmocka_unit_test(test_models_dir_shadows),
        cmocka_unit_test(test_mesh_nested),
    };
    return cmocka_run_group_tests_name("run_inputs", tests, NULL, NULL);
}
