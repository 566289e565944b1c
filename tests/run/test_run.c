/* test_run.c — the runner's promises for every workload (issue 31):
 *
 * - run.until stops every shipped workload config early: the run ends at
 *   exactly the stop time, counts fewer frames than without it, the frames
 *   it counts are the same as the uncut run's first frames (a cut leaves
 *   the past alone), and no processor is busy longer than the stop time;
 * - a config section a workload does not read is refused where it
 *   stands, as is an unknown top-level section;
 * - the runner builds the machine and scene once and hands the same
 *   objects to the workload.
 * Each shipped config runs at 3 frames, shrunk where it is slow.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/run/run.h"
#include "tests/support.h"

typedef struct {
    const char *config;       /* under configs/ */
    const char *const *shrink; /* --set to keep it fast, NULL-terminated */
} Shipped;

static const char *const none[] = {NULL};
static const char *const dp_small[] = {"workload.width=256",
                                       "workload.height=200", NULL};
static const char *const pm_small[] = {"workload.resolution=200", NULL};

static const Shipped shipped[] = {
    {"tokenring.yaml", none},       {"quickstart.yaml", pm_small},
    {"pixelmerge-2pot.yaml", none}, {"pphigs-flock.yaml", none},
    {"dpscan-cm200.yaml", dp_small}, {"sortfirst-vehicle.yaml", none},
    {"argus-march.yaml", none},     {"argus-nurbs.yaml", none},
    {"performer-town.yaml", none},
    {"pn-onyx.yaml", none},
};

/* Runs configs/<s->config> with the shrink overrides, run.frames=3 and
 * `extra` (NULL: none). */
static SimResult *run_shipped(const Shipped *s, const char *extra,
                              GError **err)
{
    GPtrArray *ov = g_ptr_array_new();
    for (guint i = 0; s->shrink[i]; i++)
        g_ptr_array_add(ov, (char *)s->shrink[i]);
    g_ptr_array_add(ov, "run.frames=3");
    if (extra)
        g_ptr_array_add(ov, (char *)extra);
    g_ptr_array_add(ov, NULL);
    char *path = g_build_filename("configs", s->config, NULL);
    CfgRun *r = cfg_run_load(path, (const char *const *)ov->pdata, err);
    g_free(path);
    g_ptr_array_free(ov, TRUE);
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = r ? cfg_run_exec(r, &o, err) : NULL;
    cfg_run_free(r);
    return res;
}

static SimResult *run_ok(const Shipped *s, const char *extra)
{
    GError *e = NULL;
    SimResult *r = run_shipped(s, extra, &e);
    if (!r)
        fail_msg("%s %s: %s", s->config, extra ? extra : "", e->message);
    return r;
}

static SimTime frame_at(const SimResult *r, guint i)
{
    return g_array_index(r->frame_times, SimTime, i);
}

/* The cut run against the whole one (see the file comment): NULL, or
 * what is wrong (g_free). */
static char *cut_fault(const SimResult *whole, const SimResult *cut,
                       SimTime until)
{
    if (cut->elapsed != until)
        return g_strdup_printf("the cut run ends at %" G_GUINT64_FORMAT
                               " ps, expected run.until %" G_GUINT64_FORMAT
                               " ps",
                               cut->elapsed, until);
    if (cut->frame_times->len >= whole->frame_times->len)
        return g_strdup_printf("%u frames cut, expected fewer than the "
                               "whole run's %u",
                               cut->frame_times->len,
                               whole->frame_times->len);
    for (guint i = 0; i < cut->frame_times->len; i++)
        if (frame_at(cut, i) != frame_at(whole, i))
            return g_strdup_printf("frame %u is %" G_GUINT64_FORMAT
                                   " ps cut and %" G_GUINT64_FORMAT
                                   " ps whole",
                                   i, frame_at(cut, i), frame_at(whole, i));
    for (guint i = 0; i < cut->nodes->len; i++) {
        const SimNodeResult *n = cut->nodes->pdata[i];
        if (n->busy.total > until)
            return g_strdup_printf("%s busy %" G_GUINT64_FORMAT
                                   " ps past run.until",
                                   n->name, n->busy.total);
    }
    return NULL;
}

/* run.until halfway through each shipped config's run stops it there. */
static void test_until_stops_every_workload(void **state)
{
    (void)state;
    for (guint k = 0; k < G_N_ELEMENTS(shipped); k++) {
        const Shipped *s = &shipped[k];
        SimResult *whole = run_ok(s, NULL);
        assert_true(whole->frame_times->len == 3);
        SimTime until = whole->elapsed / 2;
        char *set = g_strdup_printf("run.until=%" G_GUINT64_FORMAT " ps",
                                    until);
        SimResult *cut = run_ok(s, set);
        char *fault = cut_fault(whole, cut, until);
        if (fault)
            fail_msg("%s cut at %s: %s", s->config, set, fault);
        g_free(set);
        sim_result_free(cut);
        sim_result_free(whole);
    }
}

/* The check itself fails on a run that went past its stop time. */
static void test_check_cut_can_fail(void **state)
{
    (void)state;
    SimResult *whole = run_ok(&shipped[0], NULL);
    char *set = g_strdup_printf("run.until=%" G_GUINT64_FORMAT " ps",
                                whole->elapsed / 2);
    SimResult *cut = run_ok(&shipped[0], set);
    g_free(set);
    char *fault = cut_fault(whole, cut, cut->elapsed);
    assert_null(fault);
    /* a stop time other than the run's end; a run no shorter than the
     * whole; a frame the cut changed; a processor busy past the end */
    fault = cut_fault(whole, cut, cut->elapsed - 1);
    assert_non_null(fault);
    g_free(fault);
    assert_non_null(fault = cut_fault(cut, cut, cut->elapsed));
    g_free(fault);
    g_array_index(cut->frame_times, SimTime, 0) += 1;
    assert_non_null(fault = cut_fault(whole, cut, cut->elapsed));
    g_free(fault);
    g_array_index(cut->frame_times, SimTime, 0) -= 1;
    ((SimNodeResult *)cut->nodes->pdata[0])->busy.total = cut->elapsed + 1;
    assert_non_null(fault = cut_fault(whole, cut, cut->elapsed));
    g_free(fault);
    sim_result_free(cut);
    sim_result_free(whole);
}

/* The workload's plan for a config: which sections it reads. */
static unsigned plan_reads(const char *config)
{
    char *path = g_build_filename("configs", config, NULL);
    CfgNode *root = cfg_load_file(path, NULL);
    g_free(path);
    assert_non_null(root);
    const CfgNode *wl = cfg_get(root, "workload");
    const WlOps *ops = wl_find(cfg_scalar(cfg_get(wl, "type")));
    assert_non_null(ops);
    void *p = ops->parse(wl, NULL);
    assert_non_null(p);
    WlPlan plan = {.machine_set = g_ptr_array_new_with_free_func(g_free)};
    if (ops->plan)
        ops->plan(p, &plan);
    g_ptr_array_free(plan.machine_set, TRUE);
    ops->free_params(p);
    cfg_free(root);
    return plan.reads;
}

static void expect_refused(const Shipped *s, const char *set,
                           const char *found)
{
    GError *e = NULL;
    SimResult *r = run_shipped(s, set, &e);
    if (r || !strstr(e->message, found))
        fail_msg("%s with %s: %s, expected a located '%s'", s->config, set,
                 r ? "ran" : e->message, found);
    assert_true(g_str_has_prefix(e->message, "--set "));
    g_error_free(e);
}

/* Each workload refuses a section it would not read: a machine or a
 * scene its plan leaves out, and an unknown top-level section. */
static void test_unread_sections_refused(void **state)
{
    (void)state;
    guint refused_plan = 0;
    for (guint k = 0; k < G_N_ELEMENTS(shipped); k++) {
        const Shipped *s = &shipped[k];
        unsigned reads = plan_reads(s->config);
        if (!(reads & WL_READS_MACHINE)) {
            expect_refused(s, "machine.model=ipsc2",
                           "found a machine: section, expected none");
            refused_plan++;
        }
        if (!(reads & WL_READS_SCENE)) {
            expect_refused(s, "scene.generator=teapots",
                           "found a scene: section, expected none");
            refused_plan++;
        }
        expect_refused(s, "extras.colour=blue",
                       "found unknown key 'extras'");
    }
    assert_true(refused_plan > 0); /* some workload reads less than all */
}

/* What the workload runs on is what the runner built. */
static const WlOps *real_pm;
static MachMachine *seen_machine;
static Scene *seen_scene;

static gboolean probe_run(const WlContext *ctx, void *params, SimResult *out,
                          GError **err)
{
    seen_machine = ctx->machine;
    seen_scene = ctx->scene;
    return real_pm->run(ctx, params, out, err);
}

static void test_built_once_and_handed_over(void **state)
{
    (void)state;
    GError *e = NULL;
    const char *const ov[] = {"workload.resolution=64", NULL};
    CfgRun *r = cfg_run_load("configs/quickstart.yaml", ov, &e);
    assert_non_null(r);
    assert_non_null(r->machine_built);
    assert_non_null(r->scene_built);
    real_pm = r->wl;
    WlOps probe = *r->wl;
    probe.run = probe_run;
    r->wl = &probe;
    CfgRunOpts o = {.quiet = TRUE};
    SimResult *res = cfg_run_exec(r, &o, &e);
    assert_non_null(res);
    assert_ptr_equal(seen_machine, r->machine_built);
    assert_ptr_equal(seen_scene, r->scene_built);
    assert_ptr_equal(mach_engine(seen_machine), r->eng);
    r->wl = real_pm;
    sim_result_free(res);
    cfg_run_free(r);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_until_stops_every_workload),
        cmocka_unit_test(test_check_cut_can_fail),
        cmocka_unit_test(test_unread_sections_refused),
        cmocka_unit_test(test_built_once_and_handed_over),
    };
    return cmocka_run_group_tests_name("run", tests, NULL, NULL);
}
