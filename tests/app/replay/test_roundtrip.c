/* test_roundtrip.c — `pgsim run --record` then `pgsim replay` on the same
 * machine gives the run's frame times, busy times (so utilisation) and
 * communication volume exactly, for each workload that uses the machine
 * layer's processors and network (shipped configs, made small with
 * overrides); and the comparison fails when the target differs. */
#include "sim/app/replay/rpl_format.h"
#include "sim/app/replay/rpl_record.h"
#include "sim/app/replay/rpl_replay.h"
#include <glib/gstdio.h>
#include <inttypes.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

typedef struct {
    const char *config;
    const char *sets[8];
} Case;

static gboolean same(const SimResult *a, const SimResult *b);

/* Runs a config with a recorder and writes the trace to path; returns
 * the result of the same config run without one (recording must not
 * change it: checked). */
static SimResult *record(const Case *c, const char *path, char **machine,
                         char **fidelity)
{
    GError *e = NULL;
    /* a CfgRun runs once: the reference run has a load of its own */
    CfgRun *r = cfg_run_load(c->config, c->sets, &e);
    g_assert_no_error(e);
    CfgRunOpts plain = {.quiet = TRUE};
    SimResult *ref = cfg_run_exec(r, &plain, &e);
    g_assert_no_error(e);
    cfg_run_free(r);
    r = cfg_run_load(c->config, c->sets, &e);
    g_assert_no_error(e);
    RplRecorder *rec = rpl_recorder_new();
    CfgRunOpts o = {.quiet = TRUE, .recorder = rpl_recorder_hook(rec)};
    SimResult *res = cfg_run_exec(r, &o, &e);
    g_assert_no_error(e);
    if (!same(ref, res))
        fail_msg("%s: recording changed the run", c->config);
    assert_true(rpl_recorder_write(rec, path, r, res, NULL, &e));
    sim_result_free(res);
    res = ref;
    g_assert_no_error(e);
    rpl_recorder_free(rec);
    cfg_run_free(r);
    RplReader *rd = rpl_reader_open(path, &e);
    g_assert_no_error(e);
    *machine = g_strdup(rpl_reader_header(rd)->machine);
    *fidelity = g_strdup(rpl_reader_header(rd)->fidelity);
    rpl_reader_free(rd);
    return res;
}

/* TRUE when frame times, elapsed time, every node's busy time (total
 * and per phase) and the communication volume are equal. */
static gboolean same(const SimResult *a, const SimResult *b)
{
    gboolean ok = a->frame_times->len == b->frame_times->len &&
                  a->elapsed == b->elapsed && a->comm_bytes == b->comm_bytes &&
                  a->comm_messages == b->comm_messages &&
                  a->nodes->len == b->nodes->len &&
                  a->phases->len == b->phases->len;
    for (guint i = 0; ok && i < a->frame_times->len; i++)
        ok = g_array_index(a->frame_times, SimTime, i) ==
             g_array_index(b->frame_times, SimTime, i);
    for (guint i = 0; ok && i < a->nodes->len; i++) {
        const SimNodeResult *x = a->nodes->pdata[i], *y = b->nodes->pdata[i];
        ok = !strcmp(x->name, y->name) && x->busy.total == y->busy.total;
        for (guint k = 0; ok && k < a->phases->len; k++)
            ok = sim_busy_phase(&x->busy, k) == sim_busy_phase(&y->busy, k);
    }
    return ok;
}

static SimResult *replay(const char *path, const char *machine,
                         const char *fidelity, const char *const *sets)
{
    RplReplayOpts o = {
        .trace = path, .machine = machine, .fidelity = fidelity, .sets = sets};
    GError *e = NULL;
    SimResult *res = rpl_replay(&o, &e);
    g_assert_no_error(e);
    return res;
}

/* Removes the temporary trace and its directory; frees the names. */
static void tmp_clear(char *dir, char *path, char *machine, char *fidelity)
{
    g_remove(path);
    g_rmdir(dir);
    g_free(path);
    g_free(dir);
    g_free(machine);
    g_free(fidelity);
}

static void round_trip(const Case *c, gboolean gz)
{
    char *dir = g_dir_make_tmp("pgsim-rt-XXXXXX", NULL);
    char *path = g_build_filename(dir, gz ? "t.pgt.gz" : "t.pgt", NULL);
    char *machine, *fidelity;
    SimResult *orig = record(c, path, &machine, &fidelity);
    assert_true(orig->frame_times->len > 0);
    SimResult *rep = replay(path, machine, fidelity, NULL);
    if (!same(orig, rep))
        fail_msg("%s: the replay differs from the run", c->config);
    sim_result_free(rep);
    sim_result_free(orig);
    tmp_clear(dir, path, machine, fidelity);
}

static const Case pixelmerge = {"configs/pixelmerge-2pot.yaml", {NULL}};
static const Case quickstart = {"configs/quickstart.yaml", {NULL}};
static const Case pphigs = {"configs/pphigs-flock.yaml",
                            {"run.frames=2", NULL}};
static const Case sortfirst = {
    "configs/sortfirst-vehicle.yaml",
    {"run.frames=2", "scene.triangles=8000", "scene.structures=60", NULL}};
static const Case dpscan = {
    "configs/dpscan-cm200.yaml",
    {"scene.grid=16", "workload.width=256", "workload.height=256", NULL}};
/* The CM-5 (SPMD, every node the same counts), its sends priced by the
 * fat-tree formula: the network variant's messages are not in the trace. */
static const Case dpscan_cm5 = {
    "configs/dpscan-cm200.yaml",
    {"machine.model=cm5", "workload.processors=32", "workload.wire=formula",
     "scene.grid=16", "workload.width=256", "workload.height=256"}};
static const Case argus = {"configs/argus-nurbs.yaml", {NULL}};
static const Case march = {"configs/argus-march.yaml", {NULL}};
static const Case pn = {"configs/pn-onyx.yaml", {NULL}};
static const Case performer = {"configs/performer-town.yaml",
                               {"run.frames=40", NULL}};

static void test_pixelmerge(void **s)
{
    (void)s;
    round_trip(&pixelmerge, FALSE);
    round_trip(&quickstart, TRUE); /* gzip, analytic network */
}

static void test_pphigs(void **s)
{
    (void)s;
    round_trip(&pphigs, FALSE);
}

static void test_sortfirst(void **s)
{
    (void)s;
    round_trip(&sortfirst, FALSE);
}

static void test_dpscan(void **s)
{
    (void)s;
    round_trip(&dpscan, FALSE);
    round_trip(&dpscan_cm5, FALSE);
}

static void test_argus(void **s)
{
    (void)s;
    round_trip(&argus, FALSE);
    round_trip(&march, FALSE);
}

/* PN triangles on the Onyx: the CPU -> pipe stream is a shared-memory
 * transfer (`b`), in the volume. */
static void test_pn(void **s)
{
    (void)s;
    round_trip(&pn, FALSE);
}

/* Performer's pipelined frames, locked to the refresh: refresh waits
 * (`v`), frames ending at the swap (`swap`), the pipe's stream (`b`). */
static void test_performer(void **s)
{
    (void)s;
    round_trip(&performer, FALSE);
}

/* The comparison can fail: the same trace on a slower network (or at
 * another fidelity) gives other frame times. */
static void test_other_machine_differs(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-rt-XXXXXX", NULL);
    char *path = g_build_filename(dir, "t.pgt", NULL);
    char *machine, *fidelity;
    SimResult *orig = record(&pixelmerge, path, &machine, &fidelity);
    const char *slow[] = {"machine.network.bandwidth=0.5 MB/s", NULL};
    SimResult *rep = replay(path, machine, fidelity, slow);
    assert_false(same(orig, rep));
    assert_int_equal(orig->comm_bytes, rep->comm_bytes);
    assert_true(sim_result_mean_frame_s(rep) > sim_result_mean_frame_s(orig));
    sim_result_free(rep);
    sim_result_free(orig);
    tmp_clear(dir, path, machine, fidelity);
}

/* Per processor, the counts of `op` on its `c` lines in any phase;
 * names[p] gets its name on the recording machine ("gp3"). */
static uint64_t *op_counts(const char *path, const char *op, guint *n,
                           GPtrArray *names)
{
    GError *e = NULL;
    RplReader *r = rpl_reader_open(path, &e);
    g_assert_no_error(e);
    const RplHeader *h = rpl_reader_header(r);
    *n = h->procs;
    for (guint p = 0; p < *n; p++) {
        const RplKind *kd = rpl_header_kind_of(h, p);
        g_ptr_array_add(names,
                        kd ? g_strdup_printf("%s%u", kd->name, p - kd->first)
                           : g_strdup("?"));
    }
    uint64_t *k = g_new0(uint64_t, *n);
    RplItem it;
    while (rpl_reader_next(r, &it, &e))
        for (guint i = 0; it.type == RPL_COMPUTE && i < it.n_ops; i++)
            if (!strcmp(it.op[i], op))
                k[it.proc] += it.count[i];
    g_assert_no_error(e);
    rpl_reader_free(r);
    return k;
}

/* The busy time of the node named `name` (0 if it did nothing). */
static SimTime busy_of(const SimResult *res, const char *name)
{
    for (guint i = 0; i < res->nodes->len; i++) {
        const SimNodeResult *x = res->nodes->pdata[i];
        if (!strcmp(x->name, name))
            return x->busy.total;
    }
    return 0;
}

/* The workload records `op` (a cost of `kind`) as a named count: a
 * replay with that cost 1 us and then 2 us gives every processor
 * exactly its recorded count x 1 us more busy time (a `w` trace has no
 * counts: fails), and nothing else moves the volume. */
static void counts_repriced(const Case *c, const char *kind, const char *op)
{
    char *dir = g_dir_make_tmp("pgsim-rt-XXXXXX", NULL);
    char *path = g_build_filename(dir, "t.pgt", NULL);
    char *machine, *fidelity;
    sim_result_free(record(c, path, &machine, &fidelity));
    guint n;
    GPtrArray *names = g_ptr_array_new_with_free_func(g_free);
    uint64_t *k = op_counts(path, op, &n, names), total = 0;
    char *one = g_strdup_printf("machine.nodes.%s.costs.%s=1 us", kind, op);
    char *two = g_strdup_printf("machine.nodes.%s.costs.%s=2 us", kind, op);
    const char *s1[] = {one, NULL}, *s2[] = {two, NULL};
    SimResult *a = replay(path, machine, fidelity, s1);
    SimResult *b = replay(path, machine, fidelity, s2);
    for (guint p = 0; p < n; p++) {
        SimTime d = busy_of(b, names->pdata[p]) - busy_of(a, names->pdata[p]);
        if (d != k[p] * SIM_US)
            fail_msg("%s: processor %u: %s busy moved by %" PRIu64
                     " ps, expected %" PRIu64 " x 1 us",
                     c->config, p, op, d, k[p]);
        total += k[p];
    }
    g_ptr_array_unref(names);
    if (total == 0)
        fail_msg("%s: no %s counts recorded", c->config, op);
    assert_int_equal(a->comm_bytes, b->comm_bytes);
    sim_result_free(a);
    sim_result_free(b);
    g_free(one);
    g_free(two);
    g_free(k);
    tmp_clear(dir, path, machine, fidelity);
}

static void test_counts_repriced(void **s)
{
    (void)s;
    counts_repriced(&pn, "pipe", "triangle");
    counts_repriced(&pn, "cpu", "draw_vertex");
    counts_repriced(&performer, "cpu", "cull_node");
    counts_repriced(&performer, "cpu",
                    "draw_vertex"); /* DRAW: CPU-bound at 1 us */
    counts_repriced(&argus, "cpu", "geom_vertex");
    counts_repriced(&march, "cpu", "march_voxel");
    counts_repriced(&sortfirst, "node", "transform_vertex");
    counts_repriced(&sortfirst, "node", "chunk_pack");
    counts_repriced(&pphigs, "gp", "vertex");
    counts_repriced(&pphigs, "renderer", "expression");
    counts_repriced(&pphigs, "frame_buffer", "store_region");
}

/* Work is recorded as named counts: per processor, the `span` counts of
 * its `c` lines in phase "span" (a trace of `w` times has none). */
static uint64_t *span_counts(const char *path, guint *n, unsigned *phase)
{
    GError *e = NULL;
    RplReader *r = rpl_reader_open(path, &e);
    g_assert_no_error(e);
    const RplHeader *h = rpl_reader_header(r);
    *n = h->procs;
    *phase = G_MAXUINT;
    for (guint i = 0; i < h->phases->len; i++)
        if (!strcmp(h->phases->pdata[i], "span"))
            *phase = i;
    uint64_t *k = g_new0(uint64_t, *n);
    RplItem it;
    while (rpl_reader_next(r, &it, &e))
        for (guint i = 0; it.type == RPL_COMPUTE && i < it.n_ops; i++)
            if (it.phase == *phase && !strcmp(it.op[i], "span"))
                k[it.proc] += it.count[i];
    g_assert_no_error(e);
    rpl_reader_free(r);
    return k;
}

static SimTime busy_in(const SimResult *res, guint node, const char *phase)
{
    for (guint k = 0; k < res->phases->len; k++)
        if (!strcmp(res->phases->pdata[k], phase))
            return sim_busy_phase(
                &((const SimNodeResult *)res->nodes->pdata[node])->busy, k);
    fail_msg("no phase %s", phase);
    return 0;
}

/* Doubling the target's `span` cost (100 -> 200 us) adds, on every
 * processor, exactly its recorded span count x 100 us to the span phase
 * and nothing to the zbuf phase; the frame grows. */
static void test_pixelmerge_counts_repriced(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-rt-XXXXXX", NULL);
    char *path = g_build_filename(dir, "t.pgt", NULL);
    char *machine, *fidelity;
    sim_result_free(record(&pixelmerge, path, &machine, &fidelity));
    guint n;
    unsigned ph;
    uint64_t *k = span_counts(path, &n, &ph);
    const char *one[] = {"machine.nodes.node.costs.span=100 us", NULL};
    const char *two[] = {"machine.nodes.node.costs.span=200 us", NULL};
    SimResult *a = replay(path, machine, fidelity, one);
    SimResult *b = replay(path, machine, fidelity, two);
    uint64_t total = 0;
    for (guint p = 0; p < n; p++) {
        SimTime da = busy_in(a, p, "span"), db = busy_in(b, p, "span");
        assert_int_equal(db - da, k[p] * 100 * SIM_US);
        assert_int_equal(busy_in(a, p, "zbuf"), busy_in(b, p, "zbuf"));
        total += k[p];
    }
    assert_true(total > 0); /* a `w` trace has no counts: fails here */
    assert_true(sim_result_mean_frame_s(b) > sim_result_mean_frame_s(a));
    sim_result_free(a);
    sim_result_free(b);
    g_free(k);
    tmp_clear(dir, path, machine, fidelity);
}

/* A target without pixel-merging costs (the CM-5) is a located error
 * naming them; with --costs-from ipsc2 each operation costs the iPSC/2's
 * scaled by the clocks, so every processor's busy time in every phase
 * is the run's times one ratio (< 1: a faster clock), to rounding. */
static void test_costs_from(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-rt-XXXXXX", NULL);
    char *path = g_build_filename(dir, "t.pgt", NULL);
    char *machine, *fidelity;
    SimResult *orig = record(&pixelmerge, path, &machine, &fidelity);
    RplReplayOpts o = {.trace = path, .machine = "cm5", .nodes = 16};
    GError *e = NULL;
    assert_null(rpl_replay(&o, &e));
    assert_non_null(e);
    assert_non_null(strstr(e->message, "nodes.node.costs.span"));
    g_clear_error(&e);
    o.costs_from = "ipsc2";
    SimResult *rep = rpl_replay(&o, &e);
    g_assert_no_error(e);
    const char *ph[] = {"span", "zbuf", "merge"};
    double ratio = 0;
    for (guint p = 0; p < 16; p++)
        for (guint k = 0; k < G_N_ELEMENTS(ph); k++) {
            double r = (double)busy_in(rep, p, ph[k]) /
                       (double)busy_in(orig, p, ph[k]);
            ratio = ratio ? ratio : r;
            assert_true(fabs(r - ratio) < 1e-6 * ratio);
        }
    assert_true(ratio > 0 && ratio < 1);
    sim_result_free(rep);
    sim_result_free(orig);
    tmp_clear(dir, path, machine, fidelity);
}

/* --costs-from prices an operation on the processor's recording kind:
 * a PPHIGS frame (GPs, renderers, host, frame buffer) replayed on the
 * cluster (one kind, `node`) fails without it, naming a GP operation,
 * and with it (and clocks for the kinds Pixel-Planes 5 gives none)
 * every processor's busy time is the run's times the ratio of its
 * recording kind's clock (40 MHz, the i860's, for all four here) to the
 * cluster's, to the rounding of each scaled cost to a picosecond. */
static void test_costs_from_kinds(void **s)
{
    (void)s;
    char *dir = g_dir_make_tmp("pgsim-rt-XXXXXX", NULL);
    char *path = g_build_filename(dir, "t.pgt", NULL);
    char *machine, *fidelity;
    const Case one = {"configs/pphigs-flock.yaml", {"run.frames=1", NULL}};
    SimResult *orig = record(&one, path, &machine, &fidelity);
    RplReplayOpts o = {.trace = path, .machine = "cluster-ib", .nodes = 34};
    GError *e = NULL;
    assert_null(rpl_replay(&o, &e));
    assert_non_null(strstr(e->message, "nodes.node.costs.vertex"));
    g_clear_error(&e);
    const char *clocks[] = {"host=40MHz", "frame_buffer=40MHz", NULL};
    o.costs_from = "pixel-planes-5";
    o.clocks = clocks;
    SimResult *rep = rpl_replay(&o, &e);
    g_assert_no_error(e);
    assert_int_equal(orig->nodes->len, 34);
    for (guint i = 0; i < orig->nodes->len; i++) {
        const SimNodeResult *x = orig->nodes->pdata[i];
        char name[16];
        g_snprintf(name, sizeof name, "node%u", i);
        double r = (double)busy_of(rep, name) / (double)x->busy.total;
        if (fabs(r - 40e6 / 2.25e9) > 1e-3 * r)
            fail_msg("%s: ratio %g, expected 40 MHz / 2.25 GHz", x->name, r);
    }
    sim_result_free(rep);
    sim_result_free(orig);
    tmp_clear(dir, path, machine, fidelity);
}

/* Every trace shipped in traces/ reads and replays on its own machine
 * and has actions. */
static void test_shipped_traces(void **s)
{
    (void)s;
    GDir *d = g_dir_open("traces", 0, NULL);
    assert_non_null(d);
    const char *f;
    guint n = 0;
    while ((f = g_dir_read_name(d))) {
        if (!g_str_has_suffix(f, ".pgt") && !g_str_has_suffix(f, ".pgt.gz"))
            continue;
        char *path = g_build_filename("traces", f, NULL);
        GError *e = NULL;
        RplReader *r = rpl_reader_open(path, &e);
        g_assert_no_error(e);
        char *machine = g_strdup(rpl_reader_header(r)->machine);
        char *fid = g_strdup(rpl_reader_header(r)->fidelity);
        rpl_reader_free(r);
        SimResult *res = replay(path, machine, fid, NULL);
        double actions = 0;
        assert_true(sim_result_get_metric(res, "actions", &actions));
        if (actions < 1)
            fail_msg("%s: no actions", path);
        sim_result_free(res);
        g_free(machine);
        g_free(fid);
        g_free(path);
        n++;
    }
    g_dir_close(d);
    assert_true(n >= 8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pixelmerge),
        cmocka_unit_test(test_pphigs),
        cmocka_unit_test(test_sortfirst),
        cmocka_unit_test(test_dpscan),
        cmocka_unit_test(test_argus),
        cmocka_unit_test(test_pn),
        cmocka_unit_test(test_performer),
        cmocka_unit_test(test_counts_repriced),
        cmocka_unit_test(test_other_machine_differs),
        cmocka_unit_test(test_pixelmerge_counts_repriced),
        cmocka_unit_test(test_costs_from),
        cmocka_unit_test(test_costs_from_kinds),
        cmocka_unit_test(test_shipped_traces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
