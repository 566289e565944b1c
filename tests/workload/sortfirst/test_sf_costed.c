/* test_sf_costed.c — issue 37 point 4 on a small vehicle: the off-screen
 * master chunks of dynamic mastership spread evenly (sf_mastership.c),
 * the pull request's interrupt at the master (request_interrupt), and
 * the frame buffer's read-out and assembly (sf_fbuf.c), each costed on
 * the machine; each test fails without its mechanism. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "tests/workload/sortfirst/sf_testutil.h"

static const char *small =
    "machine: {model: cluster-ib}\n"
    "workload: {type: sortfirst, processors: 4, granularity: 5,\n"
    "           resolution: 64, bookkeeping: %s, regions: static,\n"
    "           mastership: %s, migration: %s, framebuffer: %s,\n"
    "           offscreen: %s}\n"
    "scene: {generator: vehicle, structures: 40, triangles: 3000,\n"
    "        instances: 3, circle_radius: 6, camera_radius: 15,\n"
    "        camera_height: 5, fov: 15, degrees_per_frame: 12}\n";

static SimResult *run(const char *bk, const char *ms, const char *mig,
                      const char *fb, const char *off, const char *const *sets)
{
    char *text = g_strdup_printf(small, bk, ms, mig, fb, off);
    GError *e = NULL;
    SimResult *r = sf_test_run(text, sets, 12, NULL, FALSE, &e);
    if (!r)
        fail_msg("%s", e->message);
    g_free(text);
    assert_true(sf_test_metric(r, "image_matches_serial") == 1);
    return r;
}

/* A narrow view: chunks leave the screen.  Kept, they pile up on a few
 * masters; spread, no master holds more than 10 % over the mean plus
 * one chunk (40 structures of 3000 triangles in chunks of 5: 5 polygons
 * at most), at the price of more bytes. */
static void test_offscreen_spread(void **state)
{
    (void)state;
    for (int bk = 0; bk < 2; bk++) {
        const char *b = bk ? "maxset" : "minset";
        SimResult *keep = run(b, "dynamic", "push", "none", "keep", NULL);
        SimResult *spr = run(b, "dynamic", "push", "none", "spread", NULL);
        double mean = sf_test_metric(spr, "offscreen_master_polygons") / 4;
        assert_true(sf_test_metric(keep, "offscreen_spread_per_frame") == 0);
        assert_true(sf_test_metric(spr, "offscreen_spread_per_frame") > 0);
        assert_true(sf_test_metric(keep, "offscreen_master_polygons_max") >
                    1.5 * mean);
        assert_true(sf_test_metric(spr, "offscreen_master_polygons_max") <=
                    1.1 * mean + 5);
        assert_true(sf_test_metric(spr, "offscreen_master_polygons") ==
                    sf_test_metric(keep, "offscreen_master_polygons"));
        assert_true(sf_test_metric(spr, "migrated_bytes_per_frame") >
                    sf_test_metric(keep, "migrated_bytes_per_frame"));
        sim_result_free(keep);
        sim_result_free(spr);
    }
}

/* Each request served costs its master request_interrupt (3 us on
 * cluster-ib): the interrupt time is the requests' messages (half the
 * pull messages) x 3 us, and the frame is longer than with a free
 * interrupt. */
static void test_pull_interrupt(void **state)
{
    (void)state;
    const char *free_irq[] = {
        "machine.nodes.node.costs.request_interrupt.value=0 ns", NULL};
    SimResult *a = run("minset", "fixed", "pull", "none", "keep", NULL);
    SimResult *z = run("minset", "fixed", "pull", "none", "keep", free_irq);
    double served = sf_test_metric(a, "messages_per_frame") / 2;
    assert_true(served > 0);
    assert_true(fabs(sf_test_metric(a, "interrupt_ms") - served * 0.003) <
                1e-9);
    assert_true(sf_test_metric(z, "interrupt_ms") == 0);
    assert_true(sf_test_metric(a, "frame_ms") > sf_test_metric(z, "frame_ms"));
    sim_result_free(a);
    sim_result_free(z);
}

/* The frame buffer: 64 x 64 pixels of 4 B arrive in P messages (64 B
 * each) at node 4, which assembles 4096 pixels at 1 ns; the frame ends
 * after that, later than without it by at least the last region's
 * read-out and assembly (32 x 32 pixels at 1 ns each) and its message
 * (1 us start-up on cluster-ib). */
static void test_framebuffer(void **state)
{
    (void)state;
    SimResult *fb = run("maxset", "fixed", "push", "node", "keep", NULL);
    SimResult *no = run("maxset", "fixed", "push", "none", "keep", NULL);
    assert_true(sf_test_metric(fb, "framebuffer_bytes_per_frame") ==
                4 * 64 + 64 * 64 * 4);
    assert_true(fabs(sf_test_metric(fb, "assembly_ms") - 4096e-6) < 1e-9);
    assert_true(sf_test_metric(fb, "frame_ms") >
                sf_test_metric(no, "frame_ms") + 2 * 1024e-6 + 1e-3);
    assert_true(sf_test_metric(fb, "polygons_rendered_per_frame") ==
                sf_test_metric(no, "polygons_rendered_per_frame"));
    assert_true(fb->comm_messages == no->comm_messages + 12 * 4);
    sim_result_free(fb);
    sim_result_free(no);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offscreen_spread),
        cmocka_unit_test(test_pull_interrupt),
        cmocka_unit_test(test_framebuffer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
