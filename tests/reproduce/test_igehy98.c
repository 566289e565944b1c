/* test_igehy98.c — the Argus reproduction's runner: one run of a config
 * with `--set` overrides gives a frame rate, overrides reach the run
 * (one context issuing with no application work is faster than with
 * it; a dearer patch vertex, as the leave-one-out rows set, slower),
 * and a bad override or file is an error, not a number. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <unistd.h>

#include "sim/reproduce/igehy98.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rate_and_overrides),
    };
    return cmocka_run_group_tests_name("igehy98", tests, NULL, NULL);
}
