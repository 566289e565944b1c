/* test_pphigs_parse.c — the pphigs section parser at the ends of every
 * range (the lowest and highest value accepted, one step past refused at
 * its file:line:column), the refusals that combine keys, and the
 * own-memory estimate (mem_bytes) worked out from the database spec or
 * counted in a database file.
 * Run from the repository root (make test does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/workload/pphigs/pphigs_cfg.h"
#include "sim/workload/workload.h"
#include "sim/scene/scene_limits.h"

extern const WlOps wl_pphigs_ops;

#define HEAD                                                                   \
    "workload: {type: pphigs, database: flock_old_well,"                       \
    " databases: configs/pphigs/databases.yaml,"                               \
    " frame: configs/pphigs/frame.yaml"

static void *parse(const char *extra, GError **err)
{
    char *text = g_strdup_printf(HEAD "%s}\n", extra);
    CfgNode *root = cfg_load_string(text, "pp.yaml", err);
    assert_non_null(root);
    void *p = wl_pphigs_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    g_free(text);
    return p;
}

static void expect_ok(const char *extra)
{
    GError *e = NULL;
    void *p = parse(extra, &e);
    if (!p)
        fail_msg("%s: %s", extra, e->message);
    wl_pphigs_ops.free_params(p);
}

/* Refused with the message naming column `col` of line 1 and `what`. */
static void expect_refused_at(const char *extra, int col, const char *what)
{
    GError *e = NULL;
    void *p = parse(extra, &e);
    if (p)
        fail_msg("%s: accepted", extra);
    assert_non_null(e);
    char *at = g_strdup_printf("pp.yaml:1:%d:", col);
    if (!strstr(e->message, at) || !strstr(e->message, what))
        fail_msg("%s: '%s' lacks '%s' or '%s'", extra, e->message, at, what);
    g_free(at);
    g_clear_error(&e);
}

/* "<pre><v>" accepted for each `ok`, refused at v's column for `bad`. */
static void expect_range(const char *pre, const char *const *ok, guint n_ok,
                         const char *const *bad, guint n_bad)
{
    for (guint i = 0; i < n_ok; i++) {
        char *x = g_strdup_printf("%s%s%s", pre, ok[i],
                                  strchr(pre, '{') ? "}" : "");
        expect_ok(x);
        g_free(x);
    }
    for (guint i = 0; i < n_bad; i++) {
        char *x = g_strdup_printf("%s%s%s", pre, bad[i],
                                  strchr(pre, '{') ? "}" : "");
        expect_refused_at(x, (int)(strlen(HEAD) + strlen(pre)) + 1, "");
        g_free(x);
    }
}

#define RANGE(pre, ok, bad)                                                    \
    expect_range(pre, ok, G_N_ELEMENTS(ok), bad, G_N_ELEMENTS(bad))

static void test_ranges(void **st)
{
    (void)st;
    static const char *const gps_ok[] = {"1", "64"}, *gps_bad[] = {"0", "65"};
    RANGE(", gps: ", gps_ok, gps_bad);
    static const char *const ang_ok[] = {"-360", "360"},
                             *ang_bad[] = {"-361", "361"};
    RANGE(", edit_angle_deg: ", ang_ok, ang_bad);
    static const char *const cnt_ok[] = {"0", "1000000"},
                             *cnt_bad[] = {"-1", "1000001"};
    RANGE(", attr_cache_every: ", cnt_ok, cnt_bad);
    RANGE(", edits_per_frame: ", cnt_ok, cnt_bad);
    RANGE(", edits: {append: ", cnt_ok, cnt_bad);
    RANGE(", edits: {post: ", cnt_ok, cnt_bad);
    static const char *const frac_ok[] = {"0.000001", "1"},
                             *frac_bad[] = {"0.0000009", "1.0000001"};
    RANGE(", rebalance: {threshold: ", frac_ok, frac_bad);
    RANGE(", rebalance: {fraction: ", frac_ok, frac_bad);
    static const char *const n_ok[] = {"1", "1000000"},
                             *n_bad[] = {"0", "1000001"};
    RANGE(", rebalance: {frames: ", n_ok, n_bad);
    RANGE(", rebalance: {max_moves: ", n_ok, n_bad);
}

static void test_combined_refusals(void **st)
{
    (void)st;
    const int alg = (int)strlen(HEAD ", algorithm: ") + 1;
    expect_ok(", algorithm: simple, edits: {modify: 2}");
    expect_ok(", algorithm: by_structure, edits_per_frame: 0,"
              " rebalance: {enabled: false}");
    expect_refused_at(", algorithm: by_structure, edits: {delete: 1},"
                      " rebalance: {enabled: false}",
                      alg, "no editing procedure");
    expect_refused_at(", algorithm: by_structure, edits_per_frame: 1,"
                      " rebalance: {enabled: false}",
                      alg, "no editing procedure");
    /* rebalancing is on unless disabled */
    expect_refused_at(", algorithm: by_structure, rebalance: {frames: 2}", alg,
                      "no editing procedure");
    expect_ok(", algorithm: by_structure");
    expect_refused_at(", edits_per_frame: 1, edits: {modify: 1}",
                      (int)strlen(HEAD ", edits_per_frame: 1, edits: {"
                                       "modify: ") + 1,
                      "edits.modify and edits_per_frame");
    expect_ok(", edits_per_frame: 1, edits: {append: 1}");
    expect_refused_at(", edits: {modfy: 1}",
                      (int)strlen(HEAD ", edits: {") + 1, "modfy");
}

/* mem_bytes: (polygons + boids x boid_polygons + well_polygons +
 * overlays) x SCENE_POLY_BYTES x max(1, verts - 2). */
static void test_mem_bytes(void **st)
{
    (void)st;
    ScenePphigsSpec s;
    assert_true(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                    "flock_old_well", NULL, &s, NULL));
    void *p = parse("", NULL);
    assert_non_null(p);
    GString *what = g_string_new(NULL);
    double polys = (double)s.polygons + (double)s.boids * s.boid_polygons +
                   s.well_polygons + s.overlays;
    assert_true(polys > s.polygons && s.boids > 1);
    double want = polys * SCENE_POLY_BYTES * MAX(1.0, s.verts - 2.0);
    assert_true(wl_pphigs_ops.mem_bytes(p, what) == want);
    char *w = g_strdup_printf("a database of %.0f polygons of %u vertices",
                              polys, s.verts);
    assert_string_equal(what->str, w);
    g_free(w);
    g_string_free(what, TRUE);
    wl_pphigs_ops.free_params(p);
}

/* mem_bytes of a database file: its host and GP copies, 2 x primitive
 * instances (max-set) x SCENE_POLY_BYTES; the spec's formula is not used.
 * The file: a leaf of 2 triangles executed twice under a root holding
 * one more, so 1 + 2 x 2 = 5 instances. */
static void test_mem_bytes_file(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-pphigs-mem-XXXXXX", NULL);
    char *db = g_build_filename(dir, "db.yaml", NULL);
    assert_true(g_file_set_contents(
        db,
        "structure_database: 1\n"
        "structures:\n"
        "  - name: leaf\n"
        "    elements:\n"
        "      - triangle: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n"
        "      - triangle: [[0, 0, 1], [1, 0, 1], [0, 1, 1]]\n"
        "  - name: root\n"
        "    elements:\n"
        "      - triangle: [[0, 0, 2], [1, 0, 2], [0, 1, 2]]\n"
        "      - execute: leaf\n"
        "      - execute: leaf\n"
        "posted: [root]\n",
        -1, NULL));
    char *text = g_strdup_printf("workload: {type: pphigs, database: %s,"
                                 " frame: configs/pphigs/frame.yaml}\n",
                                 db);
    CfgNode *root = cfg_load_string(text, "pp.yaml", NULL);
    assert_non_null(root);
    GError *err = NULL;
    void *p = wl_pphigs_ops.parse(cfg_get(root, "workload"), &err);
    if (!p)
        fail_msg("%s", err->message);
    GString *what = g_string_new(NULL);
    assert_true(wl_pphigs_ops.mem_bytes(p, what) == 2.0 * 5 * SCENE_POLY_BYTES);
    assert_string_equal(what->str, "a database of 5 primitive instances");
    g_string_free(what, TRUE);
    wl_pphigs_ops.free_params(p);
    cfg_free(root);
    g_free(text);
    assert_int_equal(g_remove(db), 0);
    assert_int_equal(g_rmdir(dir), 0);
    g_free(db);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ranges),
        cmocka_unit_test(test_combined_refusals),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_mem_bytes_file),
    };
    return cmocka_run_group_tests_name("pphigs_parse", tests, NULL, NULL);
}
