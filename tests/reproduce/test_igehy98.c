/* test_igehy98.c — the Argus reproduction's runner: one run of a config
 * with `--set` overrides gives a frame rate, overrides reach the run
 * (one context issuing with no application work is faster than with
 * it; a dearer patch vertex, as the leave-one-out rows set, slower),
 * and a bad override or file is an error, not a number; the claim
 * "scalable on 24 processors" (igehy98_claims.c) comes out 1 or 0 with
 * its threshold, and its reason names the binding side. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <unistd.h>

#include "sim/reproduce/igehy98.h"
#include <string.h>

static const char *small =
    "schema_version: 1\n"
    "machine: {model: origin2000}\n"
    "workload: {type: argus, processors: 8, contexts: 1,\n"
    "  application: nurbs, tile: 32, width: 160, height: 120,\n"
    "  check_image: false}\n"
    "scene: {generator: nurbs, patches_u: 2, patches_v: 3, tess: 6}\n";

static char *write_tmp(void)
{
    GError *e = NULL;
    char *path = NULL;
    int fd = g_file_open_tmp("igehy98-XXXXXX.yaml", &path, &e);
    assert_true(fd >= 0);
    close(fd);
    assert_true(g_file_set_contents(path, small, -1, &e));
    return path;
}

static void test_rate_and_overrides(void **state)
{
    (void)state;
    GString *used = g_string_new(NULL);
    RpContext ctx_ = {.fidelity = "faithful", .quiet = TRUE,
                      .fidelity_used = used};
    const RpContext *ctx = &ctx_;
    char *path = write_tmp();
    GError *e = NULL;
    double with_app = 0, issue_only = 0;
    assert_true(rp_igehy98_rate(ctx, path, NULL, &with_app, &e));
    const char *none[] = {"workload.application=none", NULL};
    assert_true(rp_igehy98_rate(ctx, path, none, &issue_only, &e));
    assert_true(with_app > 0 && isfinite(with_app));
    assert_true(issue_only > with_app);
    /* the leave-one-out rows' override: a cost of the model, per cell */
    const char *slow[] = {"machine.nodes.cpu.costs.nurbs_vertex=5us", NULL};
    double slower = 0;
    assert_true(rp_igehy98_rate(ctx, path, slow, &slower, &e));
    assert_true(slower < 0.8 * with_app);
    const char *bad[] = {"workload.contexts=zero", NULL};
    double hz = -1;
    assert_false(rp_igehy98_rate(ctx, path, bad, &hz, &e));
    assert_non_null(e);
    g_clear_error(&e);
    assert_false(rp_igehy98_rate(ctx, "/nonexistent/argus.yaml", NULL, &hz, &e));
    g_clear_error(&e);
    /* the pass's fidelity reaches the run and the table's header */
    assert_non_null(strstr(used->str, "origin2000"));
    g_string_free(used, TRUE);
    g_unlink(path);
    g_free(path);
}

/* The claim's holds row for efficiency `eff` on the small config;
 * *speedup gets the nurbs speed-up, *note the reason (g_free). */
static double claim(const RpContext *ctx, const char *path, double eff,
                    double *speedup, char **note)
{
    char *dir = g_path_get_dirname(path), *base = g_path_get_basename(path);
    char *text = g_strdup_printf(
        "claims: {scales_24: {set: [workload.check_image=false],\n"
        "  processors: [4, 8], contexts_per: 2, efficiency: %g,\n"
        "  contexts: [1, 2, 6], shared: [workload.geometry=4,\n"
        "  workload.rasterisers=4]}}\napps: {nurbs: %s}\n",
        eff, base);
    GError *e = NULL;
    CfgNode *root = cfg_load_string(text, "c.yaml", &e);
    assert_non_null(root);
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    if (!rp_igehy98_claims(ctx, dir, cfg_get(root, "claims"),
                           cfg_get(root, "apps"), rows, &e))
        fail_msg("%s", e->message);
    double holds = -1;
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        assert_string_equal(r->table, "claims");
        if (strcmp(r->column, "nurbs_speedup") == 0)
            *speedup = r->sim;
        if (strcmp(r->column, "holds") == 0) {
            holds = r->sim;
            *note = g_strdup(r->note);
        }
    }
    g_ptr_array_free(rows, TRUE);
    cfg_free(root);
    g_free(text);
    g_free(dir);
    g_free(base);
    return holds;
}

/* Twice the processors must give efficiency x 2 the rate: with 0.5 the
 * small Nurbs holds, with 1 it cannot (its speed-up is below 2), and
 * each verdict says so with the figures it was decided on. */
static void test_claim_can_fail(void **state)
{
    (void)state;
    GString *used = g_string_new(NULL);
    RpContext ctx_ = {.fidelity = "faithful", .quiet = TRUE,
                      .fidelity_used = used};
    char *path = write_tmp(), *yes = NULL, *no = NULL;
    double s = 0, s2 = 0;
    assert_true(claim(&ctx_, path, 0.5, &s, &yes) == 1);
    assert_true(s >= 1.0 && s < 2.0);
    assert_true(claim(&ctx_, path, 1.0, &s2, &no) == 0);
    assert_true(s2 == s);
    assert_non_null(strstr(yes, "holds, because"));
    assert_non_null(strstr(no, "does not hold, because"));
    assert_non_null(strstr(yes, "binds"));
    g_free(yes);
    g_free(no);
    g_string_free(used, TRUE);
    g_unlink(path);
    g_free(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rate_and_overrides),
        cmocka_unit_test(test_claim_can_fail),
    };
    return cmocka_run_group_tests_name("igehy98", tests, NULL, NULL);
}
