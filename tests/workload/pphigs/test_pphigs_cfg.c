/* test_pphigs_cfg.c — the pphigs workload through its YAML: the generated
 * databases' statistics match the published "db" rows of
 * configs/papers/ellsworth90/published.yaml (both files read through cfg); bad
 * inputs fail with a located error; the reproduction's event-driven
 * frames give the analytic traversal's metrics exactly; the `pphigs`
 * workload runs configs/pphigs-flock.yaml deterministically and honours
 * overrides of the workload and of the machine section; a structure
 * database file dumped and read back runs as the generated one.  Run
 * from the repository root (make test does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/run/run.h"
#include "tests/workload/pphigs/pphigs_rig.h"
#include "sim/workload/workload.h"
#include "tests/support.h"
#include <glib/gstdio.h>
#include <math.h>
#include <string.h>

static const char *const names[] = {"space_station", "building_lobby",
                                    "flock_old_well", "two_human_figures"};

/* Published value of a "db" cell, or FALSE when the paper has none. */
static gboolean published(const CfgNode *paper, const char *row,
                          const char *col, double *v)
{
    char *path = g_strdup_printf("tables.db.rows.%s", row);
    const CfgNode *r = cfg_path(paper, path);
    g_free(path);
    assert_non_null(r);
    if (!cfg_get(r, col))
        return FALSE;
    assert_true(cfg_get_double(r, col, TRUE, 0, 1e9, v, NULL));
    return TRUE;
}

/* Within the table's printed precision (3 significant digits). */
static void near(double sim, double pub, double tol)
{
    assert_true(fabs(sim - pub) <= tol * fabs(pub) + 1e-9);
}

static void test_db_stats_match_paper(void **st)
{
    (void)st;
    CfgNode *paper = cfg_load_file("configs/papers/ellsworth90/published.yaml", NULL);
    assert_non_null(paper);
    for (guint i = 0; i < G_N_ELEMENTS(names); i++) {
        ScenePphigsSpec s;
        ScenePphigsDb db;
        assert_true(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                        names[i], NULL, &s, NULL));
        assert_true(scene_pphigs_generate(&s, &db, NULL));
        SceneDbStats x;
        scene_db_stats(db.db, &x);
        double v;
        assert_true(published(paper, names[i], "depth", &v));
        assert_int_equal(x.depth, (guint)v);
        assert_true(published(paper, names[i], "structures", &v));
        assert_int_equal(x.instances, (guint)v); /* per instance */
        assert_true(published(paper, names[i], "polys_per_structure", &v));
        near((double)x.primitives / x.instances, v, 0.005);
        assert_true(published(paper, names[i], "poly_attr_ratio", &v));
        near((double)x.primitives / x.attributes, v, 0.005);
        double off = 100 * scene_pphigs_offscreen_share(
                               db.db, scene_camera_view_proj(&db.camera));
        if (published(paper, names[i], "offscreen_pct", &v))
            assert_true(fabs(off - v) < 2.0);
        else
            assert_true(off < 1.0);
        scene_pphigs_db_clear(&db);
    }
    cfg_free(paper);
}

static void expect_error(const char *yaml, const char *what)
{
    GError *err = NULL;
    CfgNode *n = cfg_load_string(yaml, "bad.yaml", NULL);
    assert_non_null(n);
    ScenePphigsSpec s;
    assert_false(wl_pphigs_spec_from_cfg(n, &s, &err));
    assert_non_null(err);
    assert_non_null(strstr(err->message, "bad.yaml:"));
    assert_non_null(strstr(err->message, what));
    g_clear_error(&err);
    cfg_free(n);
}

static void test_bad_specs(void **st)
{
    (void)st;
    expect_error("{kind: teapot, seed: 1}", "teapot");
    expect_error("{kind: space_station, polygns: 10}", "polygns");
    expect_error("{kind: space_station, polygons: -3}", "-3");
    GError *err = NULL;
    ScenePphigsSpec s;
    assert_false(wl_pphigs_spec_load("configs/pphigs/databases.yaml", "teapots",
                                     NULL, &s, &err));
    assert_non_null(strstr(err->message, "teapots"));
    assert_non_null(strstr(err->message, "flock_old_well"));
    g_clear_error(&err);
    /* frame.yaml: a missing provenance and an unknown key */
    WlPphigsSetup su;
    CfgNode *n = cfg_load_string("{width: 1, height: 1, region: 1, "
                                 "cmd_bytes: 1, end_bytes: 1, batch: 1, "
                                 "pixel_bytes: 1, element_bytes: 1, "
                                 "cluster_scale: {value: 8}}",
                                 "fr.yaml", NULL);
    assert_false(wl_pphigs_setup_from_cfg(n, &su, &err));
    assert_non_null(strstr(err->message, "fr.yaml:1:"));
    assert_non_null(strstr(err->message, "provenance"));
    g_clear_error(&err);
    cfg_free(n);
    n = cfg_load_string(
        "{width: 1, height: 1, region: 1, cmd_bytes: 1, "
        "end_bytes: 1, batch: 1, pixel_bytes: 1, element_bytes: 1, "
        "cluster_scale: {value: 8, assumption: x}, "
        "widht: 3}",
        "fr.yaml", NULL);
    assert_false(wl_pphigs_setup_from_cfg(n, &su, &err));
    assert_non_null(strstr(err->message, "widht"));
    g_clear_error(&err);
    cfg_free(n);
}

static void test_frames_equal_analytic(void **st)
{
    (void)st;
    PphigsRig rig = {"pixel-planes-5", "packet", {{0}, 0, 0}};
    assert_true(
        wl_pphigs_setup_load("configs/pphigs/frame.yaml", &rig.setup, NULL));
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m =
        pphigs_rig_machine_new(eng, "pixel-planes-5", 4, "packet", NULL);
    assert_non_null(m);
    WlPphigsCosts c;
    SimTime send;
    assert_true(wl_pphigs_costs_from_machine(m, &c, &send, NULL));
    assert_true(c.poly > 0 && c.vertex > 0 && send > 0);
    mach_free(m);
    sim_engine_free(eng);
    ScenePphigsSpec s;
    assert_true(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                    "flock_old_well", NULL, &s, NULL));
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    WlPphigsMetrics a[2], b[2];
    assert_true(pphigs_rig_run_db(&db, 4, &rig, &a[0], &a[1], NULL));
    pphigs_rig_analytic(&db, 4, &c, rig.setup.cluster_scale, &b[0],
                              &b[1]);
    for (int k = 0; k < 2; k++) {
        assert_true(a[k].t1 == b[k].t1); /* integer picoseconds */
        assert_true(a[k].sum == b[k].sum && a[k].max == b[k].max);
        near(a[k].efficiency, b[k].efficiency, 1e-12);
        near(a[k].utilisation, b[k].utilisation, 1e-12);
    }
    assert_true(a[1].efficiency > a[0].efficiency); /* complex wins */
    /* a bad model or fidelity is an error, not a crash */
    GError *err = NULL;
    rig.model = "no-such-machine";
    assert_false(pphigs_rig_run_db(&db, 4, &rig, &a[0], &a[1], &err));
    assert_non_null(strstr(err->message, "no-such-machine"));
    g_clear_error(&err);
    rig.model = "pixel-planes-5";
    rig.fidelity = "exact";
    assert_false(pphigs_rig_run_db(&db, 4, &rig, &a[0], &a[1], &err));
    assert_non_null(strstr(err->message, "exact"));
    g_clear_error(&err);
    scene_pphigs_db_clear(&db);
}

typedef struct {
    GArray *frames;
    double m[15];
    uint64_t bytes;
    guint gps;
} Out;

static void run_flock(const char *const *sets, Out *o)
{
    CfgNode *root = cfg_load_file("configs/pphigs-flock.yaml", NULL);
    assert_non_null(root);
    assert_true(cfg_set_override(root, "workload.gps=4", NULL));
    o->gps = 4;
    for (; sets && *sets; sets++)
        assert_true(cfg_set_override(root, *sets, NULL));
    GError *err = NULL;
    assert_non_null(cfg_get(cfg_get(root, "workload"), "type")); /* app's */
    /* the runner refuses any key nobody read (cfg_check_unused) */
    SupportRun opt = {.fidelity = "packet", .frames = 3, .seed = 3};
    SimResult *r = support_run_tree(root, &opt, &err);
    if (!r)
        fail_msg("%s", err->message);
    o->frames = g_array_new(FALSE, FALSE, sizeof(SimTime));
    g_array_append_vals(o->frames, r->frame_times->data, r->frame_times->len);
    /* 16 + the database's 5 + the renderers' range 2 + idle GPs and
     * the two polygon rates + the distribution's traffic 3 + the sort's
     * bytes and overlap 2 (docs/sorts.md) */
    assert_int_equal(r->metrics->len, 31);
    assert_true(((SimMetric *)g_ptr_array_index(r->metrics, 14))->value == 1);
    for (guint i = 0; i < 15; i++)
        o->m[i] = ((SimMetric *)g_ptr_array_index(r->metrics, i))->value;
    o->bytes = r->comm_bytes;
    assert_int_equal(r->nodes->len + sim_result_n_idle(r), 1 + o->gps + 16 + 1);
    sim_result_free(r);
}

static void test_workload_runs(void **st)
{
    (void)st;
    Out a, b, c;
    run_flock(NULL, &a);
    run_flock(NULL, &b);
    assert_int_equal(a.frames->len, 3);
    assert_memory_equal(a.frames->data, b.frames->data, 3 * sizeof(SimTime));
    assert_memory_equal(a.m, b.m, sizeof a.m);
    assert_int_equal(a.bytes, b.bytes);
    assert_true(a.m[7] == 12); /* 4 edits x 3 frames */
    assert_true(a.m[8] >= 4);  /* each edit sends >= 1 element per frame */
    const char *sets[] = {"workload.database=building_lobby",
                          "workload.algorithm=simple",
                          "workload.edits_per_frame=0", NULL};
    run_flock(sets, &c);
    assert_true(c.m[7] == 0);
    assert_true(c.m[8] == 0);      /* no edits, and no moves on a fresh list */
    assert_true(c.m[4] != a.m[4]); /* other database: other commands */
    g_array_unref(a.frames);
    g_array_unref(b.frames);
    g_array_unref(c.frames);
}

/* Runs configs/pphigs-flock.yaml through the app with overrides; returns
 * the result (NULL with *err). */
static SimResult *app_run(const char *const *sets, GError **err)
{
    CfgRun *r = cfg_run_load("configs/pphigs-flock.yaml", sets, err);
    if (!r)
        return NULL;
    SimResult *res = cfg_run_exec(r, NULL, err);
    cfg_run_free(r);
    return res;
}

static double metric(const SimResult *r, const char *name)
{
    double v = -1;
    assert_true(sim_result_get_metric(r, name, &v));
    return v;
}

/* The machine section reaches the frame: GP count, ring parameters. */
static void test_machine_overrides(void **st)
{
    (void)st;
    const char *base[] = {"run.frames=1", "workload.edits_per_frame=0", NULL};
    SimResult *a = app_run(base, NULL);
    assert_non_null(a);
    assert_true(metric(a, "gps") == 16); /* the model's count */
    const char *four[] = {"run.frames=1", "workload.edits_per_frame=0",
                          "machine.nodes.gp.count=4", NULL};
    SimResult *b = app_run(four, NULL);
    assert_non_null(b);
    assert_true(metric(b, "gps") == 4);
    const char *slow[] = {"run.frames=1", "workload.edits_per_frame=0",
                          "machine.network.startup=1 ms", NULL};
    SimResult *c = app_run(slow, NULL);
    assert_non_null(c);
    assert_true(metric(c, "frame_ms") > metric(a, "frame_ms") + 1);
    const char *gpcost[] = {"run.frames=1", "workload.edits_per_frame=0",
                            "machine.nodes.gp.costs.vertex=20 us", NULL};
    SimResult *d = app_run(gpcost, NULL);
    assert_non_null(d);
    assert_true(metric(d, "gp_util_pct") > metric(a, "gp_util_pct"));
    sim_result_free(a);
    sim_result_free(b);
    sim_result_free(c);
    sim_result_free(d);
    /* both counts given and different: a located error at workload.gps */
    const char *clash[] = {"workload.gps=8", "machine.nodes.gp.count=4", NULL};
    GError *err = NULL;
    assert_null(app_run(clash, &err));
    assert_non_null(strstr(err->message, "--set workload.gps=8:1:1: "
                                         "found gps 8 while"));
    g_clear_error(&err);
    const char *nodb[] = {"workload.database=teapot", NULL};
    assert_null(app_run(nodb, &err));
    assert_non_null(strstr(err->message, "--set workload.database=teapot"
                                         ":1:1: found database 'teapot'"));
    g_clear_error(&err);
}

/* Every edit kind from the config (seed 001 §3): counted, its elements
 * and host time reported, and the frame still equals the serial render
 * of the edited list; an edit kind that cannot run (post with nothing
 * unposted) is not counted; both edits.modify and edits_per_frame is a
 * located error. */
static void test_edit_kinds(void **st)
{
    (void)st;
    const char *none[] = {"run.frames=3", "workload.edits_per_frame=0", NULL};
    SimResult *a = app_run(none, NULL);
    assert_non_null(a);
    const char *all[] = {"run.frames=3", "workload.edits_per_frame=0",
                         "workload.edits={append: 2, insert: 2, delete: 1, "
                         "unpost: 1, post: 2}",
                         "workload.database=space_station_panel", NULL};
    SimResult *b = app_run(all, NULL);
    assert_non_null(b);
    assert_true(metric(b, "edits_append") == 6);
    assert_true(metric(b, "edits_insert") == 6);
    assert_true(metric(b, "edits_delete") == 3);
    assert_true(metric(b, "edits_unpost") == 3);
    assert_true(metric(b, "edits_post") == 3); /* 1 of 2 each frame */
    assert_true(metric(b, "image_matches_serial") == 1);
    assert_true(metric(b, "host_edit_ms_per_frame") > 0);
    assert_true(metric(a, "host_edit_ms_per_frame") == 0);
    assert_true(metric(b, "host_elements_per_frame") >
                metric(a, "host_elements_per_frame"));
    sim_result_free(a);
    sim_result_free(b);
    const char *both[] = {"workload.edits={modify: 1}", NULL};
    GError *err = NULL;
    assert_null(app_run(both, &err));
    assert_non_null(strstr(err->message, "found both edits.modify"));
    g_clear_error(&err);
}

/* workload.attr_cache_every (§3.4): the same edits send the same
 * elements and draw the same frame; the backward scans examine fewer
 * elements, and the host's edit time falls by scan_element (2 us in
 * the model) for each element not examined, which shortens the frame;
 * a negative interval is a located error. */
static void test_attr_cache_knob(void **st)
{
    (void)st;
    const char *off[] = {"run.frames=2", "run.fidelity=analytic",
                         "workload.edits={insert: 4, delete: 4}", NULL};
    const char *on[] = {"run.frames=2", "run.fidelity=analytic",
                        "workload.edits={insert: 4, delete: 4}",
                        "workload.attr_cache_every=2", NULL};
    SimResult *a = app_run(off, NULL), *b = app_run(on, NULL);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(metric(b, "image_matches_serial") == 1);
    assert_true(metric(a, "host_elements_per_frame") ==
                metric(b, "host_elements_per_frame"));
    double fewer = metric(a, "step_back_elements_per_frame") -
                   metric(b, "step_back_elements_per_frame") -
                   metric(b, "attr_cache_walk_per_frame");
    assert_true(fewer > 10);
    assert_true(fabs(metric(a, "host_edit_ms_per_frame") -
                     metric(b, "host_edit_ms_per_frame") - fewer * 2e-3) <
                1e-9);
    assert_true(metric(b, "frame_ms") < metric(a, "frame_ms"));
    sim_result_free(a);
    sim_result_free(b);
    /* with only modify edits the step back is reported when a cache is
     * on (every 1: the smallest interval) and not otherwise; modifies
     * neither scan nor walk */
    const char *mod1[] = {"run.frames=1", "run.fidelity=analytic",
                          "workload.attr_cache_every=1", NULL};
    const char *mod0[] = {"run.frames=1", "run.fidelity=analytic", NULL};
    a = app_run(mod1, NULL), b = app_run(mod0, NULL);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(metric(a, "edits") > 0);
    assert_true(metric(a, "attr_cache_walk_per_frame") == 0);
    assert_true(metric(a, "step_back_elements_per_frame") == 0);
    double v;
    assert_false(sim_result_get_metric(b, "attr_cache_walk_per_frame", &v));
    assert_false(sim_result_get_metric(b, "step_back_max_elements", &v));
    sim_result_free(a);
    sim_result_free(b);
    const char *bad[] = {"workload.attr_cache_every=-1", NULL};
    GError *err = NULL;
    assert_null(app_run(bad, &err));
    assert_non_null(strstr(err->message, "--set workload.attr_cache_every=-1"
                                         ":1:1: "));
    g_clear_error(&err);
}

/* With nothing changing between frames (no edits, no rebalancing) a
 * 2-frame run reports the 1-frame run's per-frame metrics; the last
 * frame's imbalance is 1 - processor utilisation, and the speed-up is
 * GPs x efficiency x utilisation (seed 001 §6). */
static void test_per_frame_metrics(void **st)
{
    (void)st;
    const char *sets[] = {"run.frames=1", "run.fidelity=analytic",
                          "workload.edits_per_frame=0",
                          "workload.rebalance={enabled: false}", NULL};
    SimResult *a = app_run(sets, NULL);
    sets[0] = "run.frames=2";
    SimResult *b = app_run(sets, NULL);
    assert_non_null(a);
    assert_non_null(b);
    static const char *const same[] = {
        "frame_ms", "ring_bytes_per_frame", "commands_per_frame",
        "expressions_per_frame", "host_elements_per_frame",
        "last_imbalance_pct", "distribution_efficiency_pct",
        "processor_utilisation_pct", "speedup", "gps", "edits",
        "rebalance_moves", "host_edit_ms_per_frame", "image_matches_serial"};
    for (guint i = 0; i < G_N_ELEMENTS(same); i++)
        if (fabs(metric(a, same[i]) - metric(b, same[i])) >
            1e-9 * fabs(metric(a, same[i])))
            fail_msg("%s: %g then %g", same[i], metric(a, same[i]),
                     metric(b, same[i]));
    assert_true(metric(a, "commands_per_frame") > 0);
    assert_true(metric(a, "ring_bytes_per_frame") > 0);
    assert_true(metric(a, "expressions_per_frame") >
                metric(a, "commands_per_frame"));
    assert_true(metric(a, "host_elements_per_frame") == 0);
    assert_true(metric(a, "rebalance_moves") == 0);
    assert_true(metric(a, "image_matches_serial") == 1);
    assert_true(fabs(metric(a, "last_imbalance_pct") - 100 +
                     metric(a, "processor_utilisation_pct")) < 1e-9);
    assert_true(fabs(metric(a, "speedup") -
                     metric(a, "gps") *
                         metric(a, "distribution_efficiency_pct") / 100 *
                         metric(a, "processor_utilisation_pct") / 100) <
                1e-9);
    assert_true(fabs(metric(b, "frame_ms") * 2e-3 - sim_time_to_s(b->elapsed)) <
                1e-12);
    double v;
    assert_false(sim_result_get_metric(a, "step_back_elements_per_frame", &v));
    sim_result_free(a);
    sim_result_free(b);
    /* each frame unposts one of the two posted structures and posts the
     * same one back before it is drawn: the frames draw what the
     * unedited run draws */
    const char *panel[] = {"run.frames=2", "run.fidelity=analytic",
                           "workload.database=space_station_panel",
                           "workload.edits_per_frame=0",
                           "workload.edits={unpost: 1, post: 1}", NULL};
    b = app_run(panel, NULL);
    panel[4] = NULL;
    a = app_run(panel, NULL);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(metric(b, "edits_unpost") == 2 && metric(b, "edits_post") == 2);
    assert_true(metric(b, "commands_per_frame") ==
                metric(a, "commands_per_frame"));
    assert_true(metric(b, "expressions_per_frame") ==
                metric(a, "expressions_per_frame"));
    sim_result_free(a);
    sim_result_free(b);
}

/* A PNG of the 1280 x 1024 frame at dir/name. */
static void assert_png(const char *dir, const char *name)
{
    char *png = g_build_filename(dir, name, NULL);
    char *data = NULL;
    gsize len = 0;
    assert_true(g_file_get_contents(png, &data, &len, NULL));
    assert_true(len > 100 && memcmp(data, "\x89PNG", 4) == 0);
    assert_int_equal(((guchar)data[18] << 8) | (guchar)data[19], 1280);
    assert_int_equal(((guchar)data[22] << 8) | (guchar)data[23], 1024);
    g_free(data);
    assert_int_equal(g_remove(png), 0);
    g_free(png);
}

/* --out DIR: the frames go through the generic hook, DIR/frame.png (the
 * last) or DIR/frame-NNNN.png (--frames all), as for other workloads. */
static void test_frame_out(void **st)
{
    (void)st;
    const char *sets[] = {"run.frames=2", "run.fidelity=analytic", NULL};
    for (int all = 0; all <= 1; all++) {
        /* a CfgRun runs once: one load per run */
        CfgRun *r = cfg_run_load("configs/pphigs-flock.yaml", sets, NULL);
        assert_non_null(r);
        char *dir = g_dir_make_tmp("pgsim-pphigs-XXXXXX", NULL);
        CfgRunOpts o = {.out_dir = dir, .quiet = TRUE, .all_frames = all};
        SimResult *res = cfg_run_exec(r, &o, NULL);
        assert_non_null(res);
        if (all) {
            assert_png(dir, "frame-0000.png");
            assert_png(dir, "frame-0001.png");
        } else {
            assert_png(dir, "frame.png");
        }
        assert_int_equal(g_rmdir(dir), 0); /* nothing else was written */
        sim_result_free(res);
        g_free(dir);
        cfg_run_free(r);
    }
}

/* Two results with the same frame times, elapsed time, traffic and
 * metrics (names and values, exactly). */
static void assert_same_result(const SimResult *a, const SimResult *b)
{
    assert_int_equal(a->frame_times->len, b->frame_times->len);
    for (guint i = 0; i < a->frame_times->len; i++)
        assert_true(g_array_index(a->frame_times, SimTime, i) ==
                    g_array_index(b->frame_times, SimTime, i));
    assert_true(a->elapsed == b->elapsed);
    assert_true(a->comm_bytes == b->comm_bytes);
    assert_int_equal(a->metrics->len, b->metrics->len);
    for (guint i = 0; i < a->metrics->len; i++) {
        const SimMetric *x = g_ptr_array_index(a->metrics, i);
        const SimMetric *y = g_ptr_array_index(b->metrics, i);
        assert_string_equal(x->name, y->name);
        assert_true(x->value == y->value ||
                    (isnan(x->value) && isnan(y->value)));
    }
}

/* A file of `text` in dir; returns its path (free it). */
static char *write_file(const char *dir, const char *name, const char *text)
{
    char *path = g_build_filename(dir, name, NULL);
    assert_true(g_file_set_contents(path, text, -1, NULL));
    return path;
}

/* workload.database=FILE (issue 15 point 6): the flock dumped with
 * dump_db and read back runs exactly as the generated flock (edits and
 * rebalancing included); a changed file gives a different run; bad
 * files fail with located errors. */
static void test_database_file(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-pphigs-db-XXXXXX", NULL);
    char *db = g_build_filename(dir, "flock.yaml", NULL);
    char *dump = g_strdup_printf("workload.dump_db=%s", db);
    char *use = g_strdup_printf("workload.database=%s", db);
    const char *gen[] = {"run.frames=3", "run.fidelity=analytic", dump, NULL};
    const char *file[] = {"run.frames=3", "run.fidelity=analytic", use, NULL};
    SimResult *a = app_run(gen, NULL);
    assert_non_null(a);
    GError *err = NULL;
    SimResult *b = app_run(file, &err);
    if (!b)
        fail_msg("%s", err->message);
    assert_same_result(a, b);
    assert_true(metric(b, "image_matches_serial") == 1);
    sim_result_free(b);
    /* The run reads the file: one boid polygon moved changes it. */
    char *text = NULL;
    assert_true(g_file_get_contents(db, &text, NULL, NULL));
    char *at = strstr(text, "polygon: [[");
    assert_non_null(at);
    at[strlen("polygon: [[")] = at[strlen("polygon: [[")] == '9' ? '8' : '9';
    assert_true(g_file_set_contents(db, text, -1, NULL));
    g_free(text);
    SimResult *c = app_run(file, NULL);
    assert_non_null(c);
    assert_true(metric(c, "commands_per_frame") !=
                    metric(a, "commands_per_frame") ||
                c->elapsed != a->elapsed);
    sim_result_free(c);
    sim_result_free(a);
    assert_int_equal(g_remove(db), 0);
    /* a missing file: located at the key that named it */
    assert_null(app_run(file, &err));
    assert_non_null(strstr(err->message, ":1:1: found database file '"));
    assert_non_null(strstr(err->message, "that cannot be read"));
    g_clear_error(&err);
    /* an element of an unknown kind: located in the file */
    char *bad = write_file(dir, "flock.yaml",
                           "structure_database: 1\n"
                           "structures:\n"
                           "  - name: a\n"
                           "    elements:\n"
                           "      - teapot: 3\n"
                           "posted: [a]\n");
    assert_null(app_run(file, &err));
    char *where = g_strdup_printf("%s:5:", db);
    assert_non_null(strstr(err->message, where));
    g_free(where);
    g_clear_error(&err);
    /* nothing posted: nothing to draw */
    g_free(write_file(dir, "flock.yaml",
                      "structure_database: 1\n"
                      "structures:\n"
                      "  - name: a\n"
                      "    elements:\n"
                      "      - triangle: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n"));
    assert_null(app_run(file, &err));
    assert_non_null(strstr(err->message, "with nothing posted"));
    g_clear_error(&err);
    assert_int_equal(g_remove(bad), 0);
    assert_int_equal(g_rmdir(dir), 0);
    g_free(bad);
    g_free(use);
    g_free(dump);
    g_free(db);
    g_free(dir);
}

/* `pgsim run` of one fresh frame reports the reproduction's cells. */
static void test_run_matches_table(void **st)
{
    (void)st;
    const char *sets[] = {"run.frames=1",
                          "run.fidelity=analytic",
                          "workload.edits_per_frame=0",
                          "workload.gps=4",
                          "workload.rebalance.enabled=false",
                          NULL};
    SimResult *r = app_run(sets, NULL);
    assert_non_null(r);
    PphigsRig rig = {"pixel-planes-5", "analytic", {{0}, 0, 0}};
    assert_true(
        wl_pphigs_setup_load("configs/pphigs/frame.yaml", &rig.setup, NULL));
    ScenePphigsSpec s;
    assert_true(wl_pphigs_spec_load("configs/pphigs/databases.yaml",
                                    "flock_old_well", NULL, &s, NULL));
    ScenePphigsDb db;
    assert_true(scene_pphigs_generate(&s, &db, NULL));
    WlPphigsMetrics simple, complex;
    assert_true(pphigs_rig_run_db(&db, 4, &rig, &simple, &complex, NULL));
    near(metric(r, "distribution_efficiency_pct"), 100 * complex.efficiency,
         1e-12);
    near(metric(r, "processor_utilisation_pct"), 100 * complex.utilisation,
         1e-12);
    near(metric(r, "speedup"), complex.speedup, 1e-12);
    scene_pphigs_db_clear(&db);
    sim_result_free(r);
}

int main(void)
{
    support_warnings_fatal(); /* an error set twice is a bug */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_db_stats_match_paper),
        cmocka_unit_test(test_bad_specs),
        cmocka_unit_test(test_frames_equal_analytic),
        cmocka_unit_test(test_workload_runs),
        cmocka_unit_test(test_machine_overrides),
        cmocka_unit_test(test_edit_kinds),
        cmocka_unit_test(test_attr_cache_knob),
        cmocka_unit_test(test_per_frame_metrics),
        cmocka_unit_test(test_frame_out),
        cmocka_unit_test(test_run_matches_table),
        cmocka_unit_test(test_database_file),
    };
    return cmocka_run_group_tests_name("pphigs_cfg", tests, NULL, NULL);
}
