/* test_scene_cfg_files.c — the file side of sim/scene/scene_cfg.c:
 * scene_load() by extension (.yaml, .yml, in any case; anything else a
 * model file), a scene file's top level (a map with `scene:`; a run
 * config's other sections skipped only when it has schema_version), the
 * `file:` key resolved against the YAML file's directory, and the
 * generator errors of a PPHIGS section located at `generator`.  Each
 * case with its whole message.  Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include <glib/gstdio.h>

#include "sim/scene/scene_cfg.h"
#include "tests/support.h"

typedef struct {
    char *dir;
} Tmp;

static char *put(Tmp *t, const char *name, const char *text)
{
    char *p = g_build_filename(t->dir, name, NULL);
    assert_true(g_file_set_contents(p, text, -1, NULL));
    return p;
}

static const char *square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                            "f 1 2 3\nf 1 3 4\n";

static void check_fail(const char *path, const char *tail)
{
    GError *err = NULL;
    Scene *s = scene_load(path, &err);
    if (s)
        print_error("accepted %s\n", path);
    assert_null(s);
    char *want = g_strconcat(path, tail, NULL);
    if (strcmp(err->message, want))
        print_error("got  %s\nwant %s\n", err->message, want);
    assert_string_equal(err->message, want);
    assert_int_equal(err->code, SIM_ERROR_INPUT);
    g_free(want);
    g_error_free(err);
}

static Scene *load_ok(const char *path)
{
    GError *err = NULL;
    Scene *s = scene_load(path, &err);
    if (!s)
        print_error("%s\n", err->message);
    assert_non_null(s);
    return s;
}

static void test_load_by_extension(void **st)
{
    (void)st;
    Tmp t = {g_dir_make_tmp("pgsim-scf-XXXXXX", NULL)};
    char *obj = put(&t, "sq.obj", square);
    const char *names[] = {"a.yaml", "b.yml", "C.YAML", "D.YmL"};
    for (guint i = 0; i < 4; i++) {
        /* file: relative to the YAML file's directory */
        char *y = put(&t, names[i], "scene: {file: sq.obj, two_sided: true}\n");
        Scene *s = load_ok(y);
        assert_int_equal(scene_n_polys(s), 2);
        assert_true(s->two_sided);
        scene_free(s);
        g_unlink(y);
        g_free(y);
    }
    /* a model file by its own extension: one white instance */
    Scene *s = load_ok(obj);
    assert_int_equal(scene_n_instances(s), 1);
    assert_int_equal(scene_n_polys(s), 2);
    scene_free(s);
    /* an absolute file: path is used as it is */
    char *y = g_build_filename(t.dir, "abs.yaml", NULL);
    char *text = g_strdup_printf("scene: {file: '%s'}\n", obj);
    g_free(put(&t, "abs.yaml", text));
    s = load_ok(y);
    assert_int_equal(scene_n_polys(s), 2);
    scene_free(s);
    /* a .yaml.obj is a model file, so its YAML text is a bad OBJ: no faces */
    char *yo = put(&t, "scene.yaml.obj", "scene: {file: sq.obj}\n");
    check_fail(yo, ":0:0: found a model without faces, expected at least one "
                   "polygon (an OBJ 'f' line or a PLY face)");
    g_unlink(yo);
    g_free(yo);
    g_unlink(y);
    g_free(y);
    g_free(text);
    g_unlink(obj);
    g_free(obj);
    g_rmdir(t.dir);
    g_free(t.dir);
}

/* A run config (schema_version) may hold machine, workload, run and
 * sweep beside scene; a plain scene file may not. */
static void test_run_config_sections(void **st)
{
    (void)st;
    Tmp t = {g_dir_make_tmp("pgsim-scf-XXXXXX", NULL)};
    char *obj = put(&t, "sq.obj", square);
    char *run = put(&t, "run.yaml",
                    "schema_version: 1\nmachine: {p: 4}\nworkload: {x: 1}\n"
                    "run: {frames: 2}\nsweep: {y: 2}\n"
                    "scene: {file: sq.obj}\n");
    Scene *s = load_ok(run);
    assert_int_equal(scene_n_polys(s), 2);
    scene_free(s);
    char *plain = put(&t, "plain.yaml", "scene: {file: sq.obj}\n"
                                        "machine: {p: 4}\n");
    check_fail(plain, ":2:1: found unknown key 'machine', expected one of: "
                      "scene, schema_version");
    char *extra = put(&t, "extra.yaml", "schema_version: 1\n"
                                        "scene: {file: sq.obj}\n"
                                        "colour: 3\n");
    check_fail(extra, ":3:1: found unknown key 'colour', expected one of: "
                      "scene, schema_version, machine, workload, run, sweep");
    /* a YAML file that does not parse, or is not there */
    char *broken = put(&t, "broken.yaml", "scene: {file: [\n");
    GError *err = NULL;
    assert_null(scene_load(broken, &err));
    assert_true(g_str_has_prefix(err->message, broken));
    g_clear_error(&err);
    char *missing = g_build_filename(t.dir, "missing.yaml", NULL);
    assert_null(scene_load(missing, &err));
    assert_int_equal(err->code, SIM_ERROR_IO);
    g_clear_error(&err);
    g_free(missing);
    g_unlink(broken);
    g_free(broken);
    char *noscene = put(&t, "noscene.yaml", "machine: {p: 4}\n");
    check_fail(noscene, ":1:1: found no key 'scene', expected a scene: "
                        "section (docs/scenes.md)");
    char *seq = put(&t, "seq.yaml", "[1, 2]\n");
    check_fail(seq, ":1:1: found a non-map, expected a map with a scene: "
                    "section");
    /* the scene section's own unknown keys are refused too */
    char *inner = put(&t, "inner.yaml", "scene: {file: sq.obj, colour: 1}\n");
    check_fail(inner, ":1:23: found unknown key 'colour', expected one of: "
                      "file, generator, pn_triangles, view, camera, path, "
                      "background, two_sided");
    const char *all[] = {obj, run, plain, extra, noscene, seq, inner};
    for (guint i = 0; i < G_N_ELEMENTS(all); i++) {
        g_unlink(all[i]);
        g_free((char *)all[i]);
    }
    g_rmdir(t.dir);
    g_free(t.dir);
}

/* A spec the PPHIGS generator refuses: its message located at the
 * section's `generator` key. */
static void test_pphigs_error_located(void **st)
{
    (void)st;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("scene:\n  size: 10\n"
                                    "  generator: space_station\n"
                                    "  polygons: 3\n  attributes: 9\n",
                                    "p.yaml", &err);
    assert_non_null(root);
    assert_null(scene_from_cfg(cfg_get(root, "scene"), &err));
    assert_string_equal(err->message,
                        "p.yaml:3:14: found an attribute count the polygons "
                        "cannot carry, expected 2 <= attributes <= polygons "
                        "+ 1");
    g_clear_error(&err);
    cfg_free(root);
}

int main(void)
{
    /* a reader that goes on after its error sets a GError over another,
     * and GLib warns: that is a failure here */
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_load_by_extension),
        cmocka_unit_test(test_run_config_sections),
        cmocka_unit_test(test_pphigs_error_located),
    };
    return cmocka_run_group_tests_name("scene_cfg_files", tests, NULL, NULL);
}
