/* test_pf_checks.c — performer results checked against values the test
 * computes itself (issue 21): the PN-triangle measurement on
 * Pixel-Planes 5 (host -> GPs -> renderers: every triangle sent once,
 * split over the GPs and renderers with no remainder lost or doubled, the
 * slowest GP's time from the model's costs; no frame finished before
 * run.until: per-frame figures 0; an engine error fails the run), and
 * the per-frame log and its _stages.csv (a row per frame, the stage rows
 * adding up to the run). */
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/core/trace.h"
#include "sim/machine/machine.h"
#include "sim/machine/shmem.h"
#include "sim/scene/pn_triangles.h"
#include "sim/scene/scene_cfg.h"
#include "sim/workload/performer/pf_graph.h"
#include "sim/workload/performer/pf_pipeline.h"
#include "sim/workload/performer/pf_pn.h"
#include "sim/workload/performer/pf_stages.h"
#include "sim/workload/performer/pf_workload.h"
#include "tests/support.h"

static SimTrace *trace; /* given to run()'s engine when set */
static gboolean dry;     /* run()'s engine stops before the first event */

static SimResult *run(const char *yaml, int frames, GError **err)
{
    CfgNode *root = cfg_load_string(yaml, "pf.yaml", err);
    assert_non_null(root);
    SupportRun o = {.fidelity = "analytic",
                    .frames = frames,
                    .trace = trace,
                    .dry_run = dry};
    return support_run_tree(root, &o, err);
}

static double metric(const SimResult *r, const char *name)
{
    double v = NAN;
    if (!sim_result_get_metric(r, name, &v))
        fail_msg("no metric %s", name);
    return v;
}

static const char *pp5_scene =
    "scene: {generator: teapots, count: 1, polygons_per_teapot: 300}\n";

/* The scene's coarse triangles, and its PN-tessellated triangles and
 * points at `level`. */
static void pn_counts(guint level, uint64_t *coarse, uint64_t *fine,
                      uint64_t *pts)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(pp5_scene, "s.yaml", &err);
    Scene *s = scene_from_cfg(cfg_get(root, "scene"), &err);
    assert_non_null(s);
    ScenePnParams pn = {level, SCENE_PN_LINEAR, FALSE};
    *coarse = scene_n_triangles(s);
    *fine = *pts = 0;
    for (guint i = 0; i < scene_n_instances(s); i++) {
        SceneMesh *m = scene_pn_tessellate(scene_instance_mesh(s, i), &pn);
        *fine += scene_mesh_n_triangles(m);
        *pts += scene_mesh_n_vertices(m);
        scene_mesh_free(m);
    }
    scene_free(s);
    cfg_free(root);
}

static uint64_t ceil_div(uint64_t a, uint64_t b)
{
    return (a + b - 1) / b;
}

static void check_pp5(guint level, const char *send)
{
    char *yaml = g_strdup_printf(
        "machine: {model: pixel-planes-5}\n%s"
        "workload: {type: performer, pn: {level: %u, send: %s,\n"
        "  vertex_bytes: 40 B, command_bytes: 64 B}}\n",
        pp5_scene, level, send);
    GError *err = NULL;
    SimResult *r = run(yaml, 2, &err);
    if (!r)
        fail_msg("%s", err->message);
    uint64_t coarse, fine, pts;
    pn_counts(level, &coarse, &fine, &pts);
    gboolean fine_sent = !strcmp(send, "fine");
    assert_true(metric(r, "coarse_tris") == coarse);
    assert_true(metric(r, "fine_tris") == fine);
    assert_true(metric(r, "level") == level);
    /* every triangle sent once to some GP: 3 vertices of 40 B */
    assert_true(metric(r, "link_bytes_per_frame") ==
                3.0 * (fine_sent ? fine : coarse) * 40);
    /* every fine triangle becomes one 64 B renderer command */
    assert_true(metric(r, "command_bytes_per_frame") == fine * 64.0);
    /* GP 0 gets the rounded-up share of triangles and points */
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root =
        cfg_load_string("machine: {model: pixel-planes-5}\n", "m.yaml", &err);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    assert_non_null(m);
    uint64_t ng = mach_kind(m, "gp")->count;
    /* messages, two frames: the host's one to each GP, and each GP's
     * one to every renderer its share has a command for (GP g holds
     * fine / ng triangles, one more for g < fine mod ng) */
    uint64_t nr = mach_kind(m, "renderer")->count, msgs = 0;
    for (uint64_t g = 0; g < ng; g++)
        msgs += 1 + MIN(nr, fine / ng + (g < fine % ng));
    assert_int_equal(r->comm_messages, 2 * msgs);
    SimTime per = mach_cost(m, "gp", "polygon") +
                  3 * mach_cost(m, "gp", "vertex") +
                  mach_cost(m, "gp", "send_primitive");
    SimTime gp = per * ceil_div(fine, ng);
    if (!fine_sent && level > 0)
        gp += mach_cost(m, "gp", "pn_vertex") * ceil_div(pts, ng);
    assert_true(fabs(metric(r, "gp_ms") - gp * 1e-9) < 1e-9);
    assert_true(metric(r, "frame_ms") > gp * 1e-9);
    double v;
    assert_false(sim_result_get_metric(r, "bus_ms", &v));
    assert_false(sim_result_get_metric(r, "cpu_ms", &v));
    assert_true(fabs(metric(r, "fine_tris_per_s") -
                     fine / (metric(r, "frame_ms") * 1e-3)) <
                1e-6 * metric(r, "fine_tris_per_s"));
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
    sim_result_free(r);
    g_free(yaml);
}

/* The shared-memory machine (Onyx: CPU -> bus -> pipe): the CPU sends 3
 * vertices a sent triangle (draw_vertex each, vertex_bytes each over the
 * bus), the pipe draws every fine triangle and, when it tessellates
 * (coarse sent, level > 0), evaluates every PN point; the three run at
 * once and the frame is the slowest. */
static void check_smp(guint level, const char *send)
{
    char *yaml = g_strdup_printf(
        "machine:\n  model: sgi-onyx\n"
        "  nodes: {pipe: {costs: {pn_vertex: {value: 0.7 us, "
        "assumption: t}}}}\n%s"
        "workload: {type: performer, pn: {level: %u, send: %s,\n"
        "  vertex_bytes: 40 B}}\n",
        pp5_scene, level, send);
    GError *err = NULL;
    SimResult *r = run(yaml, 2, &err);
    if (!r)
        fail_msg("%s", err->message);
    uint64_t coarse, fine, pts;
    pn_counts(level, &coarse, &fine, &pts);
    gboolean fine_sent = !strcmp(send, "fine");
    uint64_t sent = fine_sent ? fine : coarse, bytes = 3 * sent * 40;
    assert_true(metric(r, "link_bytes_per_frame") == bytes);
    assert_true(metric(r, "command_bytes_per_frame") == 0);
    assert_int_equal(r->comm_bytes, 2 * bytes);
    /* one message per FIFO chunk (pf_gpipe.h: 8 KB) */
    uint64_t chunks = MAX((bytes + 8191) / 8192, 1);
    assert_int_equal(r->comm_messages, 2 * chunks);
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root = cfg_load_string(yaml, "m.yaml", &err);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "analytic", &err);
    assert_non_null(m);
    SimTime cpu = 3 * sent * mach_cost(m, "cpu", "draw_vertex");
    SimTime pipe = fine * mach_cost(m, "pipe", "triangle");
    if (!fine_sent && level > 0)
        pipe += pts * mach_cost(m, "pipe", "pn_vertex");
    MachShmem bus;
    assert_true(mach_shmem_init(&bus, m, &err));
    SimTime wire = sim_time_for_bytes((double)bytes, bus.bandwidth) +
                   bus.latency;
    assert_true(fabs(metric(r, "cpu_ms") - cpu * 1e-9) < 1e-12);
    assert_true(fabs(metric(r, "pipe_ms") - pipe * 1e-9) < 1e-12);
    assert_true(fabs(metric(r, "bus_ms") - wire * 1e-9) < 1e-12);
    /* through the pipe's FIFO: the slowest stream (the bus's latencies
     * overlap, its occupancy does not), plus filling and draining: a
     * chunk of each */
    SimTime slow = MAX(cpu, MAX(pipe, wire));
    SimTime fill = (cpu + pipe + wire) / chunks + 2 * bus.latency + 2;
    assert_int_equal(r->frame_times->len, 2);
    SimTime frame = g_array_index(r->frame_times, SimTime, 1);
    if (!(frame >= slow && frame <= slow + 2 * fill))
        fail_msg("frame %" PRIu64 " slow %" PRIu64 " fill %" PRIu64 " cpu %" PRIu64 " pipe %" PRIu64 " wire %" PRIu64 " n %" PRIu64, (uint64_t)frame, (uint64_t)slow, (uint64_t)fill, (uint64_t)cpu, (uint64_t)pipe, (uint64_t)wire, chunks);
    assert_true(fabs(metric(r, "frame_ms") - frame * 1e-9) < 1e-9);
    double gp;
    assert_false(sim_result_get_metric(r, "gp_ms", &gp));
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
    sim_result_free(r);
    g_free(yaml);
}

/* pn: with no keys: level 2, the coarse mesh sent, 32 B a vertex and,
 * on Pixel-Planes 5, 100 B a renderer command. */
static void test_pn_defaults(void **st)
{
    (void)st;
    uint64_t coarse, fine, pts;
    pn_counts(2, &coarse, &fine, &pts);
    GError *err = NULL;
    char *y = g_strdup_printf("machine:\n  model: sgi-onyx\n"
                              "  nodes: {pipe: {costs: {pn_vertex: {value: "
                              "0.7 us, assumption: t}}}}\n%s"
                              "workload: {type: performer, pn: {}}\n",
                              pp5_scene);
    SimResult *r = run(y, 1, &err);
    if (!r)
        fail_msg("%s", err->message);
    assert_true(metric(r, "level") == 2);
    assert_true(metric(r, "fine_tris") == fine);
    assert_true(metric(r, "link_bytes_per_frame") == 3.0 * coarse * 32);
    sim_result_free(r);
    g_free(y);
    y = g_strdup_printf("machine: {model: pixel-planes-5}\n%s"
                        "workload: {type: performer, pn: {}}\n",
                        pp5_scene);
    r = run(y, 1, &err);
    if (!r)
        fail_msg("%s", err->message);
    assert_true(metric(r, "command_bytes_per_frame") == fine * 100.0);
    sim_result_free(r);
    g_free(y);
}

/* The two machines a pn run is checked on: an Onyx pipe with a vertex
 * cost of its own, and Pixel-Planes 5. */
static const char *const pn_machines[] = {
    "machine:\n  model: sgi-onyx\n"
    "  nodes: {pipe: {costs: {pn_vertex: {value: 0.7 us, "
    "assumption: t}}}}\n",
    "machine: {model: pixel-planes-5}\n"};

/* pn: when run.until ends the run before a frame finishes (the bus
 * transfer alone takes longer than 1 us), every per-frame figure is 0,
 * not a division by no frames: frame time, triangle rate and the bytes
 * per frame on either machine; the mesh figures stand. */
static void test_pn_no_frame_finished(void **st)
{
    (void)st;
    uint64_t coarse, fine, pts;
    pn_counts(2, &coarse, &fine, &pts);
    for (guint i = 0; i < G_N_ELEMENTS(pn_machines); i++) {
        char *y = g_strconcat(pn_machines[i], pp5_scene,
                              "run: {until: 1 us}\n"
                              "workload: {type: performer, pn: {}}\n",
                              NULL);
        GError *err = NULL;
        SimResult *r = run(y, 3, &err);
        if (!r)
            fail_msg("%s", err->message);
        assert_int_equal(r->frame_times->len, 0);
        assert_true(metric(r, "frame_ms") == 0);
        assert_true(metric(r, "fine_tris_per_s") == 0);
        assert_true(metric(r, "link_bytes_per_frame") == 0);
        assert_true(metric(r, "command_bytes_per_frame") == 0);
        assert_true(metric(r, "fine_tris") == fine);
        assert_true(metric(r, "coarse_tris") == coarse);
        sim_result_free(r);
        g_free(y);
    }
}

/* pn: an engine error fails the run with the engine's message (a dry
 * run stops before the first event), on either machine. */
static void test_pn_engine_error(void **st)
{
    (void)st;
    dry = TRUE;
    for (guint i = 0; i < G_N_ELEMENTS(pn_machines); i++) {
        char *y = g_strconcat(pn_machines[i], pp5_scene,
                              "workload: {type: performer, pn: {}}\n", NULL);
        GError *err = NULL;
        assert_null(run(y, 1, &err));
        assert_non_null(err);
        assert_string_equal(err->message, "stopped before the first "
                                          "simulated event (dry run)");
        g_error_free(err);
        g_free(y);
    }
    dry = FALSE;
}

/* pn: refuses a machine of neither kind set (located at the machine
 * section) and a scene that is already tessellated, saying what it
 * expected. */
static void test_pn_refusals(void **st)
{
    (void)st;
    const struct {
        const char *machine, *scene, *want;
    } bad[] = {
        {"machine: {model: ipsc2}\n", pp5_scene,
         /* its nodes play cpu and pipe (roles): no shared memory */
         "found machine 'ipsc2' with a hypercube network and no shared "
         "memory, expected network {topology: bus, bandwidth, startup} (the "
         "memory's bandwidth and access latency): a shared-memory program "
         "runs on a shared-memory machine"},
        {"machine: {model: pixel-planes-5}\n",
         "scene: {generator: teapots, count: 1, polygons_per_teapot: 300,\n"
         "  pn_triangles: {level: 1}}\n",
         "found a pre-tessellated scene, expected the coarse scene "
         "(workload.pn tessellates it)"}};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        char *y = g_strconcat(bad[i].machine, bad[i].scene,
                              "workload: {type: performer, pn: {level: 1}}\n",
                              NULL);
        GError *err = NULL;
        assert_null(run(y, 1, &err));
        if (!g_str_has_suffix(err->message, bad[i].want))
            fail_msg("'%s', expected '%s'", err->message, bad[i].want);
        g_error_free(err);
        g_free(y);
    }
}

static void test_pn_on_the_onyx(void **st)
{
    (void)st;
    check_smp(2, "coarse");
    check_smp(1, "coarse");
    check_smp(2, "fine");
    check_smp(0, "coarse");
}

static void test_pn_on_pixel_planes_5(void **st)
{
    (void)st;
    check_pp5(2, "coarse");
    check_pp5(1, "coarse");
    check_pp5(1, "fine");
    check_pp5(0, "coarse");
}

/* ---- the per-frame log -------------------------------------------------- */

static gchar **read_lines(const char *path, guint *n)
{
    gchar *text = NULL;
    if (!g_file_get_contents(path, &text, NULL, NULL))
        fail_msg("no %s", path);
    gchar **lines = g_strsplit(g_strchomp(text), "\n", -1);
    g_free(text);
    *n = g_strv_length(lines);
    return lines;
}

static void test_frame_log(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pf-log-XXXXXX", NULL);
    assert_non_null(dir);
    char *log = g_build_filename(dir, "frames.csv", NULL);
    char *yaml = g_strdup_printf(
        "machine: {model: sgi-onyx}\n"
        "workload: {type: performer, frame_log: '%s',\n"
        "  town: {blocks: 1, houses: 2, trees: 2, cars: 1}}\n",
        log);
    GError *err = NULL;
    SimResult *r = run(yaml, 4, &err);
    if (!r)
        fail_msg("%s", err->message);
    guint n = 0;
    gchar **rows = read_lines(log, &n);
    assert_int_equal(n, 1 + 4);
    assert_true(g_str_has_prefix(rows[0], "frame,app_start_ms,app_ms,"));
    assert_true(g_str_has_suffix(rows[0], ",draw_pipe_ms"));
    char *stages = g_build_filename(dir, "frames_stages.csv", NULL);
    guint m = 0;
    gchar **srows = read_lines(stages, &m);
    assert_int_equal(m, 1 + 4 * 5);
    assert_string_equal(srows[0], "frame,stage,ms");
    double sum = 0;
    for (guint f = 0; f < 4; f++) {
        gchar **c = g_strsplit(rows[1 + f], ",", -1);
        assert_int_equal(g_strv_length(c), 20);
        assert_int_equal(atoi(c[0]), f);
        const char *names[] = {"app", "cull", "draw", "isect", "frame"};
        for (guint k = 0; k < 5; k++) {
            gchar **s = g_strsplit(srows[1 + 5 * f + k], ",", -1);
            assert_int_equal(atoi(s[0]), f);
            assert_string_equal(s[1], names[k]);
            /* the stage rows repeat the log's app, cull, draw, isect */
            if (k < 4)
                assert_string_equal(s[2], c[2 + k]);
            else if (f > 0) /* and the interval between swaps */
                assert_string_equal(s[2], c[8]);
            if (k == 4)
                sum += g_ascii_strtod(s[2], NULL);
            g_strfreev(s);
        }
        if (f == 0)
            assert_true(g_ascii_strtod(c[8], NULL) == 0);
        g_strfreev(c);
    }
    /* the frame stages add up to the last swap */
    assert_true(fabs(sum - r->elapsed * 1e-9) < 1e-5);
    assert_int_equal(r->frame_times->len, 4);
    g_strfreev(srows);
    g_strfreev(rows);
    g_remove(stages);
    g_remove(log);
    g_rmdir(dir);
    g_free(stages);
    g_free(log);
    g_free(yaml);
    g_free(dir);
    sim_result_free(r);
}

/* A geoset's sphere: centre of its vertices' box, radius to the
 * farthest vertex; the first vertex counts like the others. */
static void test_geoset_bound(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    guint geode = wl_pf_add_node(g, g->root, WL_PF_GEODE);
    guint gs = wl_pf_add_gstate(g, (WlPfGeoState){1, 2, 3});
    const Vec3 tris[6] = {vec3(-5, 0, 4), vec3(1, 0, 0), vec3(0, 1, 0),
                          vec3(0, 3, 0), vec3(1, 1, 1), vec3(0, 0, 1)};
    WlPfGeoSet *a = wl_pf_geoset(g, wl_pf_add_geoset(g, geode, tris, 1, gs));
    assert_true(a->center.x == -2 && a->center.y == 0.5 && a->center.z == 2);
    assert_true(fabs(a->radius - sqrt(9 + 0.25 + 4)) < 1e-12);
    WlPfGeoSet *b =
        wl_pf_geoset(g, wl_pf_add_geoset(g, geode, tris + 3, 1, gs));
    assert_true(b->center.x == 0.5 && b->center.y == 1.5 && b->center.z == 0.5);
    assert_true(fabs(b->radius - sqrt(0.25 + 2.25 + 0.25)) < 1e-12);
    assert_int_equal(wl_pf_geoset_tris(b), 1);
    /* all below zero: the box starts empty, not at the origin */
    const Vec3 neg[3] = {vec3(-5, -5, -5), vec3(-3, -4, -5), vec3(-4, -3, -7)};
    WlPfGeoSet *c = wl_pf_geoset(g, wl_pf_add_geoset(g, geode, neg, 1, gs));
    assert_true(c->center.x == -4 && c->center.y == -4 && c->center.z == -6);
    wl_pf_graph_free(g);
}

/* A geode holding one geoset whose sphere is centre (x, 0, 0), radius r
 * (a flat triangle spanning x - r .. x + r). */
static guint ball(WlPfGraph *g, guint parent, double x, double r, guint gs)
{
    guint geode = wl_pf_add_node(g, parent, WL_PF_GEODE);
    const Vec3 t[3] = {vec3(x - r, 0, 0), vec3(x + r, 0, 0), vec3(x, 0, 0)};
    wl_pf_add_geoset(g, geode, t, 1, gs);
    return geode;
}

static void sphere_is(const WlPfGraph *g, guint node, double cx, double r)
{
    const WlPfNode *n = wl_pf_node(g, node);
    if (fabs(n->center.x - cx) > 1e-12 || fabs(n->radius - r) > 1e-12 ||
        n->center.y != 0 || n->center.z != 0)
        fail_msg("node %u: centre %.6f radius %.6f, expected %.6f %.6f",
                 node, n->center.x, n->radius, cx, r);
}

/* Bounding spheres of groups: a sphere inside another adds nothing, one
 * containing the other replaces it, two overlapping ones give the
 * smallest sphere around both; an SCS scales and moves its sphere; a
 * group with nothing below has none (radius < 0). */
static void test_sphere_union(void **st)
{
    (void)st;
    WlPfGraph *g = wl_pf_graph_new();
    guint gs = wl_pf_add_gstate(g, (WlPfGeoState){0, 0, 0});
    guint inside = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    ball(g, inside, 0, 10, gs);
    ball(g, inside, 5, 1, gs);
    guint contains = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    ball(g, contains, 5, 1, gs);
    ball(g, contains, 0, 10, gs);
    guint overlap = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    ball(g, overlap, 0, 10, gs);
    ball(g, overlap, 9.5, 1, gs);
    guint scs = wl_pf_add_node(g, g->root, WL_PF_SCS);
    wl_pf_node(g, scs)->xf = mat4_mul(mat4_translate(3, 0, 0),
                                      mat4_scale(2, 2, 2));
    ball(g, scs, 1, 2, gs);
    guint tall = wl_pf_add_node(g, g->root, WL_PF_SCS);
    wl_pf_node(g, tall)->xf = mat4_scale(1, 3, 1); /* the largest axis */
    ball(g, tall, 0, 2, gs);
    guint wide = wl_pf_add_node(g, g->root, WL_PF_SCS);
    wl_pf_node(g, wide)->xf = mat4_scale(3, 1, 1); /* largest along x */
    ball(g, wide, 0, 2, gs);
    guint deep = wl_pf_add_node(g, g->root, WL_PF_SCS);
    wl_pf_node(g, deep)->xf = mat4_scale(1, 0.5, 3); /* along z */
    ball(g, deep, 0, 2, gs);
    guint point = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    ball(g, point, 0, 10, gs);
    ball(g, point, 20, 0, gs); /* a point still counts */
    guint first = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    ball(g, first, 20, 0, gs); /* a point first: merged, not replaced */
    ball(g, first, 0, 10, gs);
    guint empty = wl_pf_add_node(g, g->root, WL_PF_GROUP);
    wl_pf_update_bounds(g, g->root);
    sphere_is(g, point, 5, 15);
    sphere_is(g, first, 5, 15);
    sphere_is(g, tall, 0, 6);
    sphere_is(g, wide, 0, 6);
    sphere_is(g, deep, 0, 6);
    sphere_is(g, inside, 0, 10);
    sphere_is(g, contains, 0, 10);
    sphere_is(g, overlap, 0.25, 10.25);
    sphere_is(g, scs, 5, 4);
    assert_true(wl_pf_node(g, empty)->radius < 0);
    wl_pf_graph_free(g);
}

/* Mean interval between swaps over frames [skip, n): (last swap - swap
 * of frame skip) / (n - 1 - skip), 0 with fewer than two such frames;
 * mean latency: swap - APP start averaged over the same frames. */
static void test_run_summaries(void **st)
{
    (void)st;
    GArray *recs = g_array_new(FALSE, TRUE, sizeof(WlPfFrameRec));
    const SimTime swap[4] = {3, 7, 12, 19}, app[4] = {0, 2, 5, 10};
    for (int i = 0; i < 4; i++) {
        WlPfFrameRec r = {.app_start = app[i] * SIM_MS,
                          .swap = swap[i] * SIM_MS};
        g_array_append_val(recs, r);
    }
    assert_true(fabs(wl_pf_mean_interval_s(recs, 0) - 16e-3 / 3) < 1e-15);
    assert_true(fabs(wl_pf_mean_interval_s(recs, 1) - 12e-3 / 2) < 1e-15);
    assert_true(fabs(wl_pf_mean_interval_s(recs, 2) - 7e-3) < 1e-15);
    assert_true(wl_pf_mean_interval_s(recs, 3) == 0);
    assert_true(wl_pf_mean_interval_s(recs, 4) == 0);
    assert_true(fabs(wl_pf_mean_latency_s(recs, 0) - 24e-3 / 4) < 1e-15);
    assert_true(fabs(wl_pf_mean_latency_s(recs, 2) - 16e-3 / 2) < 1e-15);
    assert_true(fabs(wl_pf_mean_latency_s(recs, 3) - 9e-3) < 1e-15);
    assert_true(wl_pf_mean_latency_s(recs, 4) == 0);
    g_array_set_size(recs, 1);
    assert_true(wl_pf_mean_interval_s(recs, 0) == 0);
    g_array_unref(recs);
}

/* The run's metrics are the means of the frame log's columns over the
 * frames after the first min(4, frames / 4); the frame rate is the
 * inverse of the mean interval between those frames' swaps; the bytes
 * to the pipe are 3 vertices of vertex_bytes a drawn triangle; the
 * frame times are the intervals between swaps (the first from APP's
 * start). */
static void check_means(guint frames, guint skip)
{
    char *dir = g_dir_make_tmp("pf-means-XXXXXX", NULL);
    char *log = g_build_filename(dir, "f.csv", NULL);
    char *yaml = g_strdup_printf(
        "machine: {model: sgi-onyx}\n"
        "workload: {type: performer, frame_log: '%s', vertex_bytes: 24 B,\n"
        "  stress: {gain: 5, low: 0.001, high: 0.002, max: 3},\n"
        "  town: {blocks: 2, houses: 2, trees: 2, cars: 2}}\n",
        log);
    GError *err = NULL;
    SimResult *r = run(yaml, (int)frames, &err);
    if (!r)
        fail_msg("%s", err->message);
    guint n = 0;
    gchar **rows = read_lines(log, &n);
    assert_int_equal(n, 1 + frames);
    double col[20] = {0}, swap0 = 0, swap1 = 0, bytes = 0, prev = 0;
    for (guint f = 0; f < frames; f++) {
        gchar **c = g_strsplit(rows[1 + f], ",", -1);
        double v[20];
        for (int k = 0; k < 20; k++)
            v[k] = g_ascii_strtod(c[k], NULL);
        bytes += 3 * 24 * v[11];
        double ft = sim_time_to_ms(g_array_index(r->frame_times, SimTime, f));
        assert_true(fabs(ft - (v[6] - (f ? prev : v[1]))) < 2e-6);
        prev = v[6];
        if (f >= skip)
            for (int k = 0; k < 20; k++)
                col[k] += v[k];
        if (f == skip)
            swap0 = v[6];
        swap1 = v[6];
        g_strfreev(c);
    }
    double c = frames - skip;
    const struct {
        const char *name;
        int col;
        double tol;
    } m[] = {{"app_ms", 2, 1e-6},          {"cull_ms", 3, 1e-6},
             {"draw_ms", 4, 1e-6},         {"latency_ms", 7, 1e-6},
             {"stress_mean", 9, 1e-4},     {"lod_mean", 10, 1e-4},
             {"tris_per_frame", 11, 1e-9}, {"state_changes_per_frame", 13, 1e-9},
             {"state_changes_saved_per_frame", 14, 1e-9},
             {"matrix_ops_per_frame", 15, 1e-9},
             {"tris_culled_per_frame", 16, 1e-9},
             {"draw_cpu_ms", 17, 1e-6},    {"draw_bus_ms", 18, 1e-6},
             {"draw_pipe_ms", 19, 1e-6}};
    for (guint i = 0; i < G_N_ELEMENTS(m); i++)
        if (fabs(metric(r, m[i].name) - col[m[i].col] / c) > m[i].tol)
            fail_msg("%u frames: %s %.9f, expected %.9f", frames, m[i].name,
                     metric(r, m[i].name), col[m[i].col] / c);
    assert_true(metric(r, "stress_mean") > 1); /* the band is low */
    double iv = (swap1 - swap0) / (c - 1);
    assert_true(fabs(metric(r, "frame_rate_hz") - 1000 / iv) < 1e-6);
    assert_true(metric(r, "target_rate_hz") == 30);
    assert_true(metric(r, "scs_flattened") == 2 * 2 * 2);
    assert_true(metric(r, "matrix_ops_saved_per_frame") > 0);
    assert_true(r->comm_bytes == bytes);
    /* one message per FIFO chunk of at most 8 KB, at least one a frame */
    assert_true(r->comm_messages >= frames &&
                r->comm_messages >= bytes / (8 * 1024) &&
                r->comm_messages <= bytes / (8 * 1024) + frames);
    assert_true(fabs(r->elapsed * 1e-9 - swap1) < 1e-6);
    g_strfreev(rows);
    char *stages = g_build_filename(dir, "f_stages.csv", NULL);
    g_remove(stages);
    g_free(stages);
    g_remove(log);
    g_rmdir(dir);
    g_free(log);
    g_free(yaml);
    g_free(dir);
    sim_result_free(r);
}

/* The pipeline feeds the pipe over the shared bus: a machine whose
 * network is no bus is refused, located at the machine section. */
static void test_needs_a_bus(void **st)
{
    (void)st;
    GError *err = NULL;
    SimResult *r = run("machine: {model: sgi-onyx, network: "
                       "{topology: {value: ring, source: t}}}\n"
                       "workload: {type: performer, town: {blocks: 1}}\n",
                       2, &err);
    assert_null(r);
    assert_non_null(err);
    if (!strstr(err->message, "and no shared memory"))
        fail_msg("%s", err->message);
    g_error_free(err);
}

static void test_metrics_are_log_means(void **st)
{
    (void)st;
    check_means(12, 3); /* frames / 4 */
    check_means(21, 4); /* at most 4 */
    /* no houses: no LOD is visited, the mean LOD is 0, nothing flattens */
    GError *err = NULL;
    SimResult *r = run("machine: {model: sgi-onyx}\n"
                       "workload: {type: performer,\n"
                       "  town: {blocks: 1, houses: 0, trees: 1, cars: 1}}\n",
                       3, &err);
    if (!r)
        fail_msg("%s", err->message);
    assert_true(metric(r, "lod_mean") == 0);
    assert_true(metric(r, "scs_flattened") == 0);
    assert_true(metric(r, "matrix_ops_saved_per_frame") == 0);
    sim_result_free(r);
}

static void *parse(const char *w, GError **err)
{
    char *y = g_strdup_printf("workload: {type: performer, %s}\n", w);
    CfgNode *root = cfg_load_string(y, "p.yaml", err);
    g_free(y);
    assert_non_null(root);
    void *p = wl_pf_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    return p;
}

/* Each bound of the town, stress and rate keys, taken on both sides. */
static void test_parse_edges(void **st)
{
    (void)st;
    const char *ok[] = {
        "town: {blocks: 1, houses: 0, trees: 0, cars: 0, seed: 0}",
        "town: {blocks: 256, houses: 256, trees: 1024, cars: 4096}",
        "town: {block: 20, speed: 0, eye_height: 0, fov: 1}",
        "town: {block: 10000, speed: 1000, eye_height: 1000, fov: 170}",
        "town: {lod_ranges: [1, 2, 3]}",
        "stress: {gain: 0, low: 0.5, high: 0.5, max: 1}",
        "stress: {gain: 1000, low: 0, high: 10, max: 1000}",
        "video_rate: 60, frame_rate: 60", "video_rate: 1, frame_rate: 1",
        "video_rate: 1000, frame_rate: 0.1",
        "pn: {level: 0}", "pn: {level: 32, normals: quadratic}"};
    GError *err = NULL;
    for (guint i = 0; i < G_N_ELEMENTS(ok); i++) {
        void *p = parse(ok[i], &err);
        if (!p)
            fail_msg("%s: %s", ok[i], err->message);
        wl_pf_ops.free_params(p);
    }
    const char *bad[] = {
        "town: {blocks: 0}", "town: {blocks: 257}", "town: {houses: 257}",
        "town: {trees: 1025}", "town: {cars: 4097}", "town: {block: 19.9}",
        "town: {block: 10001}", "town: {fov: 0.9}", "town: {fov: 170.1}",
        "town: {speed: -1}", "town: {eye_height: 1001}",
        "town: {lod_ranges: [1, 2]}", "town: {lod_ranges: 5}",
        "town: {lod_ranges: [0, 2, 3]}", "town: {lod_ranges: [1, 1, 3]}",
        "town: {lod_ranges: [1, 2, x]}", "stress: 3",
        "stress: {max: 0.5}", "stress: {gain: 1001}",
        "stress: {low: 0.6, high: 0.5}", "video_rate: 0.5",
        "frame_rate: 0.05", "video_rate: 30, frame_rate: 60",
        "video_rate: 60, frame_rate: 25", "pn: {level: 33}",
        /* k = 0.99999999999983: within 1e-9 of a whole number, below 1 */
        "video_rate: 59.99999999999, frame_rate: 60"};
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        void *p = parse(bad[i], &err);
        if (p)
            fail_msg("%s: accepted", bad[i]);
        assert_true(g_str_has_prefix(err->message, "p.yaml:1:"));
        g_clear_error(&err);
    }
}

/* mem_bytes: the town's triangles (3 Vec3 each) and 512 B an object. */
static void test_mem_bytes(void **st)
{
    (void)st;
    GError *err = NULL;
    GString *what = g_string_new("");
    void *p = parse("flatten: false, town: {blocks: 2, houses: 3, trees: 4, "
                    "cars: 5}",
                    &err);
    double tri = 3 * sizeof(Vec3);
    double geo = 4 * (128 + 3 * 252.0 + 4 * 2.0) * tri + 5 * 12.0 * tri;
    assert_true(wl_pf_ops.mem_bytes(p, what) ==
                geo + (4 * (1.0 + 3 + 4) + 5) * 512.0);
    assert_string_equal(what->str, "a town of 2 x 2 blocks, 3 houses and 4 "
                                   "trees a block");
    wl_pf_ops.free_params(p);
    p = parse("town: {blocks: 2, houses: 3, trees: 4, cars: 5}", &err);
    g_string_truncate(what, 0);
    assert_true(wl_pf_ops.mem_bytes(p, what) ==
                2 * geo + (4 * (1.0 + 3 + 4) + 5) * 512.0);
    wl_pf_ops.free_params(p);
    p = parse("pn: {level: 1}", &err);
    g_string_truncate(what, 0);
    assert_true(wl_pf_ops.mem_bytes(p, what) == 0);
    assert_string_equal(what->str, "pn: no town");
    wl_pf_ops.free_params(p);
    g_string_free(what, TRUE);
}

/* Without frustum culling CULL visits every house of the town each
 * frame: a flattened house (an SCS turned group) saves its push and pop,
 * 2 matrix operations a frame each; unflattened, none are saved. */
static void test_matrix_ops_saved(void **st)
{
    (void)st;
    const char *flat[2] = {"true", "false"};
    for (int k = 0; k < 2; k++) {
        char *yaml = g_strdup_printf(
            "machine: {model: sgi-onyx}\n"
            "workload: {type: performer, cull: false, flatten: %s,\n"
            "  town: {blocks: 1, houses: 3, trees: 0, cars: 0}}\n",
            flat[k]);
        GError *err = NULL;
        SimResult *r = run(yaml, 5, &err);
        if (!r)
            fail_msg("%s", err->message);
        assert_true(metric(r, "scs_flattened") == (k ? 0 : 3));
        assert_true(metric(r, "matrix_ops_saved_per_frame") == (k ? 0 : 6));
        sim_result_free(r);
        g_free(yaml);
    }
}

/* A trace that keeps its marks' names and times. */
static void keep_mark(SimTrace *tr, const char *name, SimTime t)
{
    GString *s = tr->state;
    g_string_append_printf(s, "%s@%" G_GUINT64_FORMAT ";", name, (guint64)t);
}

/* Each frame's end is marked "frame n" in the trace, n from 0, at the
 * sum of the frame times so far: the pipeline's swaps and the PN
 * measurement's frame ends alike. */
static void test_frame_marks(void **st)
{
    (void)st;
    const char *yaml[2] = {
        "machine: {model: sgi-onyx}\n"
        "workload: {type: performer, town: {blocks: 1, houses: 1}}\n",
        "machine: {model: sgi-onyx}\n"
        "scene: {generator: teapots, count: 1, polygons_per_teapot: 300}\n"
        "workload: {type: performer, pn: {level: 1}}\n"};
    static const SimTraceOps ops = {.mark = keep_mark};
    for (int k = 0; k < 2; k++) {
        SimTrace tr = {&ops, g_string_new(NULL)};
        trace = &tr;
        GError *err = NULL;
        SimResult *r = run(yaml[k], 3, &err);
        trace = NULL;
        if (!r)
            fail_msg("%s", err->message);
        GString *want = g_string_new(NULL);
        SimTime end = 0;
        for (guint f = 0; f < 3; f++) {
            end += g_array_index(r->frame_times, SimTime, f);
            g_string_append_printf(want, "frame %u@%" G_GUINT64_FORMAT ";", f,
                                   (guint64)end);
        }
        assert_string_equal(((GString *)tr.state)->str, want->str);
        g_string_free(want, TRUE);
        g_string_free(tr.state, TRUE);
        sim_result_free(r);
    }
}

/* One frame has no interval between swaps: the frame rate is reported
 * as 0, not as the inverse of a zero interval. */
static void test_one_frame_rate(void **st)
{
    (void)st;
    GError *err = NULL;
    SimResult *r = run("machine: {model: sgi-onyx}\n"
                       "workload: {type: performer, town: {blocks: 1}}\n",
                       1, &err);
    if (!r)
        fail_msg("%s", err->message);
    assert_true(metric(r, "frame_rate_hz") == 0);
    assert_true(metric(r, "latency_ms") > 0);
    sim_result_free(r);
}

/* The free functions take NULL (GLib's convention), which the run's
 * clean-up after a failed build relies on. */
static void test_free_null(void **st)
{
    (void)st;
    wl_pf_graph_free(NULL);
    wl_pf_town_free(NULL);
    wl_pf_stages_free(NULL);
    wl_pf_pn_params_free(NULL);
    wl_pf_ops.free_params(NULL);
}

/* A shared-memory machine with a pipe that lacks one Performer cost
 * (sgi-onyx without isect_triangle and without the processor
 * description it would be derived from, written to a scratch model
 * folder) is refused before any frame runs: no result, the missing cost
 * named at the model's cpu costs. */
static void test_missing_cost_refused(void **st)
{
    (void)st;
    char *src = NULL;
    assert_true(g_file_get_contents("models/sgi-onyx.yaml", &src, NULL, NULL));
    GString *y = g_string_new(NULL);
    gchar **lines = g_strsplit(src, "\n", -1);
    gboolean skip = FALSE;
    const char *under = NULL; /* the skipped block's children's indent */
    for (gchar **l = lines; *l; l++) {
        if (g_str_has_prefix(*l, "      isect_triangle:"))
            skip = TRUE, under = "        ";
        else if (g_str_has_prefix(*l, "    cycles:") ||
                 g_str_has_prefix(*l, "    memory_bandwidth:"))
            skip = TRUE, under = "      ";
        else if (skip && !g_str_has_prefix(*l, under))
            skip = FALSE;
        if (!skip)
            g_string_append_printf(y, "%s\n", *l);
    }
    g_strfreev(lines);
    g_free(src);
    char *dir = g_dir_make_tmp("pgsim-pf-XXXXXX", NULL);
    char *path = g_build_filename(dir, "onyx-short.yaml", NULL);
    assert_true(g_file_set_contents(path, y->str, -1, NULL));
    g_string_free(y, TRUE);
    char *old = g_strdup(g_getenv("PGSIM_MODELS"));
    g_setenv("PGSIM_MODELS", dir, TRUE);
    GError *err = NULL;
    SimResult *r = run("machine: {model: onyx-short}\n"
                       "workload: {type: performer, town: {blocks: 1}}\n",
                       2, &err);
    if (old)
        g_setenv("PGSIM_MODELS", old, TRUE);
    else
        g_unsetenv("PGSIM_MODELS");
    assert_null(r);
    assert_non_null(err);
    if (!strstr(err->message, "found no cost for 'isect_triangle' on 'cpu'"))
        fail_msg("%s", err->message);
    g_error_free(err);
    g_unlink(path);
    g_rmdir(dir);
    g_free(path);
    g_free(dir);
    g_free(old);
}

/* A machine with fewer cpus than the mode needs (3 for APP, CULL and
 * DRAW, and one for ISECT, on by default) is refused at the workload
 * section, and the run stops there. */
static void test_machine_refused(void **st)
{
    (void)st;
    GError *err = NULL;
    SimResult *r = run("machine: {model: sgi-onyx, nodes: {cpu: {count: 2}}}\n"
                       "workload: {type: performer, mode: app_cull_draw,\n"
                       "  town: {blocks: 2, houses: 2, trees: 2, cars: 2}}\n",
                       2, &err);
    assert_null(r);
    assert_non_null(err);
    assert_string_equal(err->message,
                        "pf.yaml:2:11: found machine 'sgi-onyx' with 2 cpu "
                        "nodes, expected 4 cpus (mode app_cull_draw + isect) "
                        "and a pipe");
    g_error_free(err);
}

/* The workload's keys reach the run: the mode and isect decide how many
 * cpus are needed (the refusal names them), app_work replaces the
 * model's app_frame (APP is app_work + app_dcs a car), vertex_bytes
 * defaults to 32 B a vertex sent to the pipe, and phase: locked swaps on
 * frame boundaries (T = 1/30 s) where floating swaps on retraces. */
static void test_keys_reach_the_run(void **st)
{
    (void)st;
    const char *one = "machine: {model: sgi-onyx, nodes: {cpu: {count: 1}}}\n";
    const struct {
        const char *w, *need;
    } modes[] = {{"mode: appcull_draw, isect: false", "2 cpus (mode appcull_draw)"},
                 {"mode: appculldraw", "2 cpus (mode appculldraw + isect)"},
                 {"isect: false", "3 cpus (mode app_cull_draw)"}};
    for (guint i = 0; i < G_N_ELEMENTS(modes); i++) {
        char *y = g_strdup_printf("%sworkload: {type: performer, %s, "
                                  "town: {blocks: 1}}\n",
                                  one, modes[i].w);
        GError *err = NULL;
        assert_null(run(y, 2, &err));
        char *want = g_strdup_printf("expected %s and a pipe", modes[i].need);
        if (!g_str_has_suffix(err->message, want))
            fail_msg("%s: '%s'", modes[i].w, err->message);
        g_free(want);
        g_clear_error(&err);
        g_free(y);
    }
    /* one process and no ISECT run on one cpu */
    GError *err = NULL;
    char *y = g_strdup_printf("%sworkload: {type: performer, mode: "
                              "appculldraw, isect: false, app_work: 3 ms,\n"
                              "  cull: false, town: {blocks: 1, houses: 1, "
                              "cars: 5, speed: 0}}\n",
                              one);
    SimResult *r = run(y, 4, &err);
    if (!r)
        fail_msg("%s", err->message);
    SimEngine *eng = sim_engine_new(1);
    MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
    double dcs = mach_cost(m, "cpu", "app_dcs") * 1e-9;
    assert_true(fabs(metric(r, "app_ms") - (3 + 5 * dcs)) < 1e-9);
    /* 3 vertices of 32 B a triangle drawn, the default (the same
     * triangles every frame: no culling, a standing eye) */
    assert_true(r->comm_bytes == 4 * 3 * 32 * metric(r, "tris_per_frame"));
    sim_result_free(r);
    g_free(y);
    mach_free(m);
    sim_engine_free(eng);
    /* locked (the default): every swap on a frame boundary; floating:
     * not every one */
    const char *phase[3] = {"phase: locked, ", "phase: floating, ", ""};
    for (int k = 0; k < 3; k++) {
        y = g_strdup_printf("machine: {model: sgi-onyx}\n"
                            "workload: {type: performer, %s"
                            "app_work: 1 ms,\n  town: {blocks: 2}}\n",
                            phase[k]);
        r = run(y, 6, &err);
        if (!r)
            fail_msg("%s", err->message);
        SimTime T, end = 0;
        assert_true(sim_time_from_s(1.0 / 60, &T));
        T *= 2;
        guint on = 0;
        for (guint f = 0; f < 6; f++) {
            end += g_array_index(r->frame_times, SimTime, f);
            on += end % T == 0;
        }
        if (k != 1 ? on != 6 : on == 6)
            fail_msg("%s: %u of 6 swaps on a frame boundary", phase[k], on);
        sim_result_free(r);
        g_free(y);
    }
}

/* A trace that writes each flow down as "src>dst:bytes;". */
static void keep_flow(SimTrace *tr, uint32_t src, const char *src_name,
                      uint32_t dst, const char *dst_name, uint64_t bytes,
                      SimTime sent, SimTime arrived)
{
    (void)src_name, (void)dst_name, (void)sent, (void)arrived;
    g_string_append_printf(tr->state, "%u>%u:%" G_GUINT64_FORMAT ";", src,
                           dst, (guint64)bytes);
}

/* DRAW streams each frame's vertices from the cpu that runs DRAW (the
 * last of the mode's processes: cpu 2 of three, cpu 1 of two) to the
 * pipe, one flow per FIFO chunk (pf_gpipe.h), 3 vertices of vertex_bytes
 * a triangle in all. */
static void test_draw_stream_source(void **st)
{
    (void)st;
    static const SimTraceOps ops = {.flow = keep_flow};
    const char *mode[2] = {"app_cull_draw", "appcull_draw"};
    for (int k = 0; k < 2; k++) {
        SimTrace tr = {&ops, g_string_new(NULL)};
        trace = &tr;
        char *y = g_strdup_printf("machine: {model: sgi-onyx}\n"
                                  "workload: {type: performer, mode: %s,\n"
                                  "  town: {blocks: 1, houses: 1}}\n",
                                  mode[k]);
        GError *err = NULL;
        SimResult *r = run(y, 3, &err);
        trace = NULL;
        if (!r)
            fail_msg("%s", err->message);
        SimEngine *eng = sim_engine_new(1);
        MachMachine *m = mach_new_from_model(eng, "sgi-onyx", "analytic", &err);
        uint32_t src = mach_proc_id(mach_proc(m, "cpu", 2 - k));
        uint32_t dst = mach_proc_id(mach_proc(m, "pipe", 0));
        gchar **flows = g_strsplit(((GString *)tr.state)->str, ";", -1);
        guint nf = g_strv_length(flows) - 1;
        assert_true(nf >= 3);
        uint64_t sum = 0;
        for (guint f = 0; f < nf; f++) {
            guint a, b;
            guint64 bytes;
            assert_int_equal(sscanf(flows[f], "%u>%u:%" G_GUINT64_FORMAT, &a,
                                    &b, &bytes),
                             3);
            assert_int_equal(a, src);
            assert_int_equal(b, dst);
            assert_true(bytes > 0);
            sum += bytes;
        }
        assert_int_equal(sum, r->comm_bytes);
        assert_true(sum > 0 && sum % (3 * 32) == 0);
        g_strfreev(flows);
        mach_free(m);
        sim_engine_free(eng);
        g_string_free(tr.state, TRUE);
        sim_result_free(r);
        g_free(y);
    }
}

/* Stress feedback is off without a stress: key: a DRAW loaded past the
 * band's top (frame rate 60 Hz, nothing culled) leaves every frame at
 * stress 1; the same run with stress: {} raises it. */
static void test_stress_off_by_default(void **st)
{
    (void)st;
    const char *key[2] = {"", "stress: {}, "};
    for (int k = 0; k < 2; k++) {
        char *y = g_strdup_printf("machine: {model: sgi-onyx}\n"
                                  "workload: {type: performer, %s"
                                  "frame_rate: 60, cull: false,\n"
                                  "  town: {blocks: 4, houses: 6, "
                                  "lod_ranges: [1000, 2000, 3000]}}\n",
                                  key[k]);
        GError *err = NULL;
        SimResult *r = run(y, 8, &err);
        if (!r)
            fail_msg("%s", err->message);
        if (k == 0) {
            assert_true(metric(r, "draw_ms") > 0.9 * 1000 / 60.0);
            assert_true(metric(r, "stress_mean") == 1);
        } else {
            assert_true(metric(r, "stress_mean") > 1);
        }
        sim_result_free(r);
        g_free(y);
    }
}

/* With no LOD visited (no houses) the log's mean_lod column is 0. */
static void test_log_lod_without_houses(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pf-lod-XXXXXX", NULL);
    char *log = g_build_filename(dir, "f.csv", NULL);
    char *y = g_strdup_printf("machine: {model: sgi-onyx}\n"
                              "workload: {type: performer, frame_log: '%s',\n"
                              "  town: {blocks: 1, houses: 0}}\n",
                              log);
    GError *err = NULL;
    SimResult *r = run(y, 2, &err);
    if (!r)
        fail_msg("%s", err->message);
    guint n = 0;
    gchar **rows = read_lines(log, &n);
    assert_int_equal(n, 3);
    for (guint f = 1; f < 3; f++) {
        gchar **c = g_strsplit(rows[f], ",", -1);
        assert_true(g_ascii_strtod(c[10], NULL) == 0);
        assert_true(g_ascii_strtod(c[11], NULL) > 0);
        g_strfreev(c);
    }
    g_strfreev(rows);
    char *stages = g_build_filename(dir, "f_stages.csv", NULL);
    g_remove(stages);
    g_remove(log);
    g_rmdir(dir);
    g_free(stages);
    g_free(log);
    g_free(dir);
    g_free(y);
    sim_result_free(r);
}

/* Node `name`'s busy time in phase `phase` (0 when none). */
static SimTime phase_busy(const SimResult *r, const char *name,
                          const char *phase)
{
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        if (strcmp(n->name, name))
            continue;
        for (guint k = 0; k < r->phases->len; k++)
            if (!strcmp(g_ptr_array_index(r->phases, k), phase))
                return k < n->busy.per_phase->len
                           ? g_array_index(n->busy.per_phase, SimTime, k)
                           : 0;
    }
    return 0;
}

/* Each stage's work is charged to its phase on its process's cpu
 * (three processes and ISECT: cpu0 app, cpu1 cull, cpu2 draw, cpu3
 * isect), all of each cpu's busy time. */
static void test_stage_phases(void **st)
{
    (void)st;
    GError *err = NULL;
    SimResult *r = run("machine: {model: sgi-onyx}\n"
                       "workload: {type: performer, town: {blocks: 1}}\n",
                       3, &err);
    if (!r)
        fail_msg("%s", err->message);
    const char *stage[4][2] = {
        {"cpu0", "app"}, {"cpu1", "cull"}, {"cpu2", "draw"}, {"cpu3", "isect"}};
    guint seen = 0;
    for (guint i = 0; i < r->nodes->len; i++) {
        const SimNodeResult *n = g_ptr_array_index(r->nodes, i);
        for (guint k = 0; k < 4; k++)
            if (!strcmp(n->name, stage[k][0])) {
                assert_true(n->busy.total > 0);
                assert_int_equal(phase_busy(r, stage[k][0], stage[k][1]),
                                 n->busy.total);
                seen++;
            }
    }
    assert_int_equal(seen, 4);
    sim_result_free(r);
}

/* matrix_ops_saved_per_frame is the mean over the frames after the
 * first min(4, frames / 4) of the PUSH and POP that flattening saved
 * (pf_cull.c: 2 a flattened SCS drawn).  Without culling every SCS is
 * drawn every frame, so it is 2 x scs_flattened (2 x 2 blocks of 2
 * houses: 8 SCS, 16) for 1, 8 (2 skipped) and 12 frames (3 skipped). */
static void test_matrix_saved_mean(void **st)
{
    (void)st;
    const int frames[3] = {1, 8, 12};
    for (int i = 0; i < 3; i++) {
        GError *err = NULL;
        SimResult *r = run("machine: {model: sgi-onyx}\n"
                           "workload: {type: performer, cull: false,\n"
                           "  town: {blocks: 2, houses: 2, trees: 2, "
                           "cars: 2}}\n",
                           frames[i], &err);
        if (!r)
            fail_msg("%s", err->message);
        assert_true(metric(r, "scs_flattened") == 8);
        if (metric(r, "matrix_ops_saved_per_frame") != 16)
            fail_msg("%d frames: %g saved, expected 16", frames[i],
                     metric(r, "matrix_ops_saved_per_frame"));
        sim_result_free(r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pn_on_pixel_planes_5),
        cmocka_unit_test(test_pn_on_the_onyx),
        cmocka_unit_test(test_pn_defaults),
        cmocka_unit_test(test_pn_refusals),
        cmocka_unit_test(test_pn_no_frame_finished),
        cmocka_unit_test(test_pn_engine_error),
        cmocka_unit_test(test_frame_log),
        cmocka_unit_test(test_geoset_bound),
        cmocka_unit_test(test_sphere_union),
        cmocka_unit_test(test_parse_edges),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_run_summaries),
        cmocka_unit_test(test_metrics_are_log_means),
        cmocka_unit_test(test_needs_a_bus),
        cmocka_unit_test(test_free_null),
        cmocka_unit_test(test_frame_marks),
        cmocka_unit_test(test_one_frame_rate),
        cmocka_unit_test(test_matrix_ops_saved),
        cmocka_unit_test(test_machine_refused),
        cmocka_unit_test(test_missing_cost_refused),
        cmocka_unit_test(test_keys_reach_the_run),
        cmocka_unit_test(test_stage_phases),
        cmocka_unit_test(test_draw_stream_source),
        cmocka_unit_test(test_stress_off_by_default),
        cmocka_unit_test(test_log_lod_without_houses),
        cmocka_unit_test(test_matrix_saved_mean),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
