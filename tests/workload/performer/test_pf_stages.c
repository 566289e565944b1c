/* test_pf_stages.c — the Performer stages on the town (pf_stages.c):
 * every stage's time is its counts times the model's costs, worked out
 * here from the counts the traversals report (issue 21: results checked
 * exactly).  APP: app_frame + app_dcs per moved car; CULL: nodes, LODs,
 * billboards and display-list items; DRAW: the slowest of the CPU
 * (geosets, state changes — lazy or eager —, matrix operations, three
 * vertices a triangle), the bus (three vertices a triangle at the
 * bus's bandwidth, plus its start-up) and the pipe (triangles, state
 * changes); ISECT: nodes and triangles tested, and the ground it finds
 * is what a later APP uses.  Run from the repository root (models/).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>

#include "sim/machine/machine.h"
#include "sim/workload/performer/pf_stages.h"

typedef struct {
    SimEngine *eng;
    MachMachine *m;
    WlPfTown *town, *twin;
    WlPfCosts c;
    WlPfStages *s;
} Rig;

static void rig_init(Rig *r, gboolean lazy)
{
    GError *err = NULL;
    r->eng = sim_engine_new(1);
    r->m = mach_new_from_model(r->eng, "sgi-onyx", "analytic", &err);
    if (!r->m)
        fail_msg("%s", err->message);
    WlPfTownParams tp = wl_pf_town_defaults();
    tp.blocks = 3;
    r->town = wl_pf_town_new(&tp);
    r->twin = wl_pf_town_new(&tp);
    assert_true(wl_pf_costs_read(r->m, 40, &r->c, &err));
    r->s = wl_pf_stages_new(r->m, r->town, &r->c, TRUE, lazy, TRUE, 4, &err);
    assert_non_null(r->s);
    r->s->draw_cpu = mach_proc(r->m, "cpu", 0);
}

static void rig_free(Rig *r)
{
    wl_pf_stages_free(r->s);
    wl_pf_town_free(r->town);
    wl_pf_town_free(r->twin);
    mach_free(r->m);
    sim_engine_free(r->eng);
}

static SimTime cost(Rig *r, const char *kind, const char *op)
{
    return mach_cost(r->m, kind, op);
}

static void test_costs_read(void **st)
{
    (void)st;
    Rig r;
    rig_init(&r, TRUE);
    const WlPfCosts *c = &r.c;
    assert_int_equal(c->vertex_bytes, 40);
    assert_int_equal(c->app_frame, cost(&r, "cpu", "app_frame"));
    assert_int_equal(c->app_dcs, cost(&r, "cpu", "app_dcs"));
    assert_int_equal(c->cull_node, cost(&r, "cpu", "cull_node"));
    assert_int_equal(c->cull_lod, cost(&r, "cpu", "cull_lod"));
    assert_int_equal(c->cull_billboard, cost(&r, "cpu", "cull_billboard"));
    assert_int_equal(c->cull_item, cost(&r, "cpu", "cull_item"));
    assert_int_equal(c->draw_geoset, cost(&r, "cpu", "draw_geoset"));
    assert_int_equal(c->draw_state, cost(&r, "cpu", "draw_state"));
    assert_int_equal(c->draw_matrix, cost(&r, "cpu", "draw_matrix"));
    assert_int_equal(c->draw_vertex, cost(&r, "cpu", "draw_vertex"));
    assert_int_equal(c->isect_node, cost(&r, "cpu", "isect_node"));
    assert_int_equal(c->isect_triangle, cost(&r, "cpu", "isect_triangle"));
    assert_int_equal(c->pipe_triangle, cost(&r, "pipe", "triangle"));
    assert_int_equal(c->pipe_state, cost(&r, "pipe", "state"));
    rig_free(&r);
}

/* The CPU's DRAW time from hand-made counts, lazy and eager. */
static void test_draw_cpu(void **st)
{
    (void)st;
    WlPfCosts c = {
        .draw_geoset = 2, .draw_state = 3, .draw_matrix = 5, .draw_vertex = 7};
    WlPfDrawStats d = {.geosets = 11,
                       .tris = 13,
                       .matrix_ops = 17,
                       .state_changes = 19,
                       .state_naive = 23};
    assert_int_equal(wl_pf_draw_cpu(&c, &d, TRUE),
                     11 * 2 + 19 * 3 + 17 * 5 + 3 * 13 * 7);
    assert_int_equal(wl_pf_draw_cpu(&c, &d, FALSE),
                     11 * 2 + 23 * 3 + 17 * 5 + 3 * 13 * 7);
}

/* The named counts of the last stage price to the time it returned. */
static void counts_price_to(Rig *r, SimTime t)
{
    assert_true(r->s->last.n > 0);
    assert_int_equal(mach_proc_ops_cost(r->s->draw_cpu, &r->s->last), t);
}

static void one_frame(Rig *r, WlPfStageFns *f, guint n, gboolean lazy)
{
    const WlPfCosts *c = &r->c;
    WlPfFrameStats *fs = wl_pf_frame_stats(r->s, n);
    /* APP: the same town moved on its own gives the count */
    guint moved = wl_pf_town_update(r->twin, n);
    assert_true(moved > 0);
    SimTime a = f->app(r->s, n);
    assert_int_equal(a, c->app_frame + moved * c->app_dcs);
    counts_price_to(r, a);
    assert_true(fs->ground == r->s->ground);
    /* ISECT */
    double before = r->s->ground;
    SimTime i = f->isect(r->s, n);
    assert_true(fs->isect.nodes_tested > 0 && fs->isect.tris_tested > 0);
    assert_int_equal(i, fs->isect.nodes_tested * c->isect_node +
                            fs->isect.tris_tested * c->isect_triangle);
    counts_price_to(r, i);
    assert_true(r->s->ground == (fs->isect.hit ? fs->isect.height : before));
    /* CULL, at stress 1.5: the twin town culled by hand at the frame's
     * camera (on the ground APP used) gives the same list and counts */
    SimTime k = f->cull(r->s, n, 1.5);
    const WlPfCullStats *cs = &fs->cull;
    SceneCamera cam = wl_pf_town_camera(r->twin, n, fs->ground);
    WlPfView v = wl_pf_view(&cam, 1.5, TRUE);
    GArray *dl = g_array_new(FALSE, FALSE, sizeof(WlPfDlItem));
    WlPfCullStats hand = {0};
    wl_pf_cull(r->twin->g, &v, dl, &hand);
    assert_int_equal(fs->dl_items, dl->len);
    assert_int_equal(cs->nodes_visited, hand.nodes_visited);
    assert_int_equal(cs->nodes_culled, hand.nodes_culled);
    assert_int_equal(cs->lod_sum, hand.lod_sum);
    assert_int_equal(cs->tris_culled, hand.tris_culled);
    WlPfDrawStats dhand = {0};
    wl_pf_draw(r->twin->g, dl, &dhand);
    g_array_free(dl, TRUE);
    assert_true(cs->nodes_visited > 0 && cs->lods > 0 && fs->dl_items > 0);
    assert_int_equal(k, cs->nodes_visited * c->cull_node +
                            cs->lods * c->cull_lod +
                            cs->billboards * c->cull_billboard +
                            fs->dl_items * c->cull_item);
    counts_price_to(r, k);
    /* DRAW */
    SimTime d = f->draw(r->s, n);
    const WlPfDrawStats *ds = &fs->draw;
    assert_true(ds->tris > 0 && ds->geosets > 0);
    assert_int_equal(ds->tris, dhand.tris);
    assert_int_equal(ds->matrix_ops, dhand.matrix_ops);
    assert_int_equal(ds->state_changes, dhand.state_changes);
    assert_true(ds->state_naive > ds->state_changes);
    uint64_t states = lazy ? ds->state_changes : ds->state_naive;
    assert_int_equal(fs->cpu, ds->geosets * c->draw_geoset +
                                  states * c->draw_state +
                                  ds->matrix_ops * c->draw_matrix +
                                  3 * ds->tris * c->draw_vertex);
    assert_int_equal(fs->pipe,
                     ds->tris * c->pipe_triangle + states * c->pipe_state);
    assert_int_equal(d, MAX(fs->cpu, MAX(fs->bus, fs->pipe)));
    /* DRAW: the CPU's counts, the pipe's counts and the stream as terms */
    assert_int_equal(mach_proc_ops_cost(r->s->draw_cpu, &r->s->last), fs->cpu);
    assert_int_equal(r->s->over.n, 2);
}

static void noop(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng, (void)ctx, (void)arg;
}

static void run_frames(gboolean lazy)
{
    Rig r;
    rig_init(&r, lazy);
    WlPfStageFns f = wl_pf_stage_fns(TRUE);
    assert_non_null(f.isect);
    assert_null(wl_pf_stage_fns(FALSE).isect);
    assert_true(r.s->ground == wl_pf_town_height(0, 0));
    for (guint n = 0; n < 4; n++) {
        /* frame n's stages run at n x 50 ms, the bus idle since frame
         * n - 1 */
        sim_schedule_at(r.eng, n * 50 * SIM_MS, noop, NULL, NULL);
        assert_true(sim_engine_run(r.eng, SIM_TIME_MAX, NULL));
        assert_int_equal(sim_now(r.eng), n * 50 * SIM_MS);
        SimTime busy = r.s->bus.busy;
        one_frame(&r, &f, n, lazy);
        const WlPfFrameStats *fs = wl_pf_frame_stats(r.s, n);
        /* the bus: 3 vertices of 40 B a triangle, at the bus's rate, and
         * its latency: DRAW's stream lasts that long from now */
        uint64_t bytes = 3 * 40 * fs->draw.tris;
        SimTime wire = sim_time_for_bytes((double)bytes, r.s->bus.bandwidth);
        assert_int_equal(r.s->bus.busy - busy, wire);
        assert_int_equal(fs->bus, wire + r.s->bus.latency);
    }
    rig_free(&r);
}

static void test_stages_lazy(void **st)
{
    (void)st;
    run_frames(TRUE);
}

static void test_stages_eager(void **st)
{
    (void)st;
    run_frames(FALSE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_costs_read),
        cmocka_unit_test(test_draw_cpu),
        cmocka_unit_test(test_stages_lazy),
        cmocka_unit_test(test_stages_eager),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
