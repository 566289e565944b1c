/* test_counts_dpscan.c — dpscan records its work as named counts of its
 * model's `dpscan:` constants (`c 1 4 dpscan.step=259 ...
 * dpscan.send_slice=38690`), and a replay prices them from the target
 * model's `dpscan:` section: raising one constant by 1 us moves every
 * processor's busy time, in every phase, by exactly its recorded count
 * of that constant x 1 us.  The same check rejects a trace of `w` times
 * (the old recording) and a trace with one count off by one; a target
 * without the SIMD router's constants (the CM-5) is a located error
 * naming each of them. */
#include "sim/app/replay/rpl_format.h"
#include "sim/app/replay/rpl_record.h"
#include "sim/app/replay/rpl_replay.h"
#include "sim/machine/machine.h"
#include "tests/workload/dpscan/dp_test_model.h"
#include <glib/gstdio.h>
#include <inttypes.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

static char *dir, *trace;

/* The shipped CM-200 config, made small (as test_roundtrip.c). */
static const char *const small[] = {"scene.grid=16", "workload.width=256",
                                    "workload.height=256", NULL};

static int record_once(void **s)
{
    (void)s;
    GError *e = NULL;
    dir = g_dir_make_tmp("pgsim-dpc-XXXXXX", NULL);
    trace = g_build_filename(dir, "t.pgt", NULL);
    CfgRun *r = cfg_run_load("configs/dpscan-cm200.yaml", small, &e);
    g_assert_no_error(e);
    RplRecorder *rec = rpl_recorder_new();
    CfgRunOpts o = {.quiet = TRUE, .recorder = rpl_recorder_hook(rec)};
    SimResult *res = cfg_run_exec(r, &o, &e);
    g_assert_no_error(e);
    gboolean ok = rpl_recorder_write(rec, trace, r, res, NULL, &e);
    g_assert_no_error(e);
    sim_result_free(res);
    rpl_recorder_free(rec);
    cfg_run_free(r);
    return ok ? 0 : -1;
}

static int remove_all(void **s)
{
    (void)s;
    g_remove(trace);
    g_rmdir(dir);
    g_free(trace);
    g_free(dir);
    return 0;
}

/* Per processor and header phase, the recorded count of `op`. */
typedef struct {
    guint procs, phases;
    GPtrArray *names; /* header phase names */
    uint64_t *k;      /* k[p * phases + ph] */
} Counts;

static Counts counts_of(const char *path, const char *op)
{
    GError *e = NULL;
    RplReader *r = rpl_reader_open(path, &e);
    g_assert_no_error(e);
    const RplHeader *h = rpl_reader_header(r);
    Counts c = {h->procs, h->phases->len,
                g_ptr_array_new_with_free_func(g_free), NULL};
    for (guint i = 0; i < c.phases; i++)
        g_ptr_array_add(c.names, g_strdup(h->phases->pdata[i]));
    c.k = g_new0(uint64_t, c.procs * c.phases);
    RplItem it;
    while (rpl_reader_next(r, &it, &e))
        for (guint i = 0; it.type == RPL_COMPUTE && i < it.n_ops; i++)
            if (!strcmp(it.op[i], op))
                c.k[it.proc * c.phases + it.phase] += it.count[i];
    g_assert_no_error(e);
    rpl_reader_free(r);
    return c;
}

static void counts_clear(Counts *c)
{
    g_ptr_array_unref(c->names);
    g_free(c->k);
}

static uint64_t counts_total(const Counts *c)
{
    uint64_t t = 0;
    for (guint i = 0; i < c->procs * c->phases; i++)
        t += c->k[i];
    return t;
}

/* `path` replayed on the CM-200 with dpscan.KEY = us microseconds (key
 * NULL: the model's costs). */
static SimResult *replay_with(const char *path, const char *key, unsigned us)
{
    char *set = key ? g_strdup_printf("machine.dpscan.%s=%u us", key, us)
                    : NULL;
    const char *sets[] = {set, NULL};
    RplReplayOpts o = {.trace = path, .machine = "cm200", .sets = sets};
    GError *e = NULL;
    SimResult *res = rpl_replay(&o, &e);
    g_assert_no_error(e);
    g_free(set);
    return res;
}

/* The name of CM-200 processor p ("array0"): the trace processor it
 * plays (the trace's processors are the model's, so the map is the
 * identity). */
static char *proc_name(guint p)
{
    SimEngine *eng = sim_engine_new(1);
    GError *e = NULL;
    CfgNode *sec = cfg_load_string("model: cm200\n", "test", &e);
    MachMachine *m = mach_new_from_cfg(eng, sec, NULL, &e);
    g_assert_no_error(e);
    char *name = g_strdup(mach_proc_name(mach_proc_at(m, p)));
    mach_free(m);
    cfg_free(sec);
    sim_engine_free(eng);
    return name;
}

/* Busy time of processor p in the phase named `phase` (0 if idle). */
static SimTime busy_in(const SimResult *res, guint p, const char *phase)
{
    char *name = proc_name(p);
    SimTime t = 0;
    for (guint i = 0; i < res->nodes->len; i++) {
        const SimNodeResult *x = res->nodes->pdata[i];
        for (guint k = 0; !strcmp(x->name, name) && k < res->phases->len; k++)
            if (!strcmp(res->phases->pdata[k], phase))
                t = sim_busy_phase(&x->busy, k);
    }
    g_free(name);
    return t;
}

/* TRUE when raising dpscan.KEY from base to base + 1 us moves the busy
 * time of every processor in every phase by exactly its count in c. */
static gboolean moves_by_counts(const char *path, const char *key,
                                unsigned base, const Counts *c)
{
    SimResult *a = replay_with(path, key, base);
    SimResult *b = replay_with(path, key, base + 1);
    gboolean ok = TRUE;
    for (guint p = 0; ok && p < c->procs; p++)
        for (guint ph = 0; ok && ph < c->phases; ph++) {
            const char *name = c->names->pdata[ph];
            SimTime d = busy_in(b, p, name) - busy_in(a, p, name);
            ok = d == c->k[p * c->phases + ph] * SIM_US;
            if (!ok)
                print_message("%s: processor %u, phase %s: busy moved by %" PRIu64
                              " ps, expected %" PRIu64 " x 1 us\n",
                              key, p, name, d, c->k[p * c->phases + ph]);
        }
    ok = ok && a->comm_bytes == b->comm_bytes;
    sim_result_free(a);
    sim_result_free(b);
    return ok;
}

/* Each constant the CM-200 charges (send_setup is 0 us there, so its
 * counts price to nothing until a target gives it a cost). */
static void test_each_cost_repriced(void **s)
{
    (void)s;
    static const struct {
        const char *key;
        unsigned base_us;
    } costs[] = {{"op", 2}, {"step", 10}, {"scan_slice", 37},
                 {"send_slice", 48}, {"send_setup", 0}};
    for (guint i = 0; i < G_N_ELEMENTS(costs); i++) {
        char *op = g_strconcat("dpscan.", costs[i].key, NULL);
        Counts c = counts_of(trace, op);
        if (counts_total(&c) == 0)
            fail_msg("no %s counts recorded", op);
        if (!moves_by_counts(trace, costs[i].key, costs[i].base_us, &c))
            fail_msg("%s: busy times not moved by count x delta", op);
        counts_clear(&c);
        g_free(op);
    }
}

/* Copies `src` to `dst`; w_times: every `c` line becomes the `w` time it
 * costs on the CM-200 (the old recording); else the first dpscan.op
 * count is one too many. */
static void rewrite(const char *src, const char *dst, gboolean w_times)
{
    GError *e = NULL;
    WlDpMachine m = {0};
    assert_true(dp_test_model("cm200", &m, &e));
    RplReader *r = rpl_reader_open(src, &e);
    RplWriter *w = rpl_writer_open(dst, &e);
    g_assert_no_error(e);
    rpl_write_header(w, rpl_reader_header(r));
    RplItem it;
    gboolean bumped = FALSE;
    while (rpl_reader_next(r, &it, &e)) {
        SimTime t = 0;
        for (guint i = 0; it.type == RPL_COMPUTE && i < it.n_ops; i++) {
            for (int k = 0; k < WL_DP_N_COSTS; k++)
                if (!strcmp(it.op[i], wl_dp_cost_path((WlDpCost)k)))
                    t += it.count[i] * wl_dp_cost_value(&m, (WlDpCost)k);
            if (!w_times && !bumped && !strcmp(it.op[i], "dpscan.op"))
                it.count[i]++, bumped = TRUE;
        }
        if (w_times && it.type == RPL_COMPUTE)
            it.type = RPL_WORK, it.value = t, it.n_ops = 0;
        rpl_write_item(w, &it);
    }
    g_assert_no_error(e);
    assert_true(rpl_writer_close(w, &e));
    rpl_reader_free(r);
}

/* The check is not vacuous: a trace of times is not repriced, and one
 * with a wrong count is repriced by the wrong amount. */
static void test_check_rejects_wrong_traces(void **s)
{
    (void)s;
    char *wt = g_build_filename(dir, "w.pgt", NULL);
    char *off = g_build_filename(dir, "off.pgt", NULL);
    Counts c = counts_of(trace, "dpscan.op");
    rewrite(trace, wt, TRUE);
    rewrite(trace, off, FALSE);
    assert_true(moves_by_counts(trace, "op", 2, &c));
    assert_false(moves_by_counts(wt, "op", 2, &c));
    assert_false(moves_by_counts(off, "op", 2, &c));
    /* ... though the time trace replays as the counts do on the CM-200's
     * own costs: only repricing tells them apart */
    SimResult *a = replay_with(trace, NULL, 0), *b = replay_with(wt, NULL, 0);
    assert_int_equal(a->elapsed, b->elapsed);
    for (guint p = 0; p < c.procs; p++)
        for (guint ph = 0; ph < c.phases; ph++)
            assert_int_equal(busy_in(a, p, c.names->pdata[ph]),
                             busy_in(b, p, c.names->pdata[ph]));
    sim_result_free(a);
    sim_result_free(b);
    counts_clear(&c);
    g_remove(wt);
    g_remove(off);
    g_free(wt);
    g_free(off);
}

/* The CM-5's dpscan: section has no SIMD router constants: one located
 * error lists each (where first used), and nothing it has. */
static void test_target_lacking_costs(void **s)
{
    (void)s;
    RplReplayOpts o = {.trace = trace, .machine = "cm5"};
    GError *e = NULL;
    SimResult *res = rpl_replay(&o, &e);
    assert_null(res);
    assert_non_null(e);
    static const char *const missing[] = {"dpscan.send_setup",
                                          "dpscan.send_slice",
                                          "dpscan.send_vp", "dpscan.send_msg"};
    for (guint i = 0; i < G_N_ELEMENTS(missing); i++) {
        const char *m = strstr(e->message, missing[i]);
        /* "  DIR/t.pgt:LINE:COL: dpscan.send_setup" */
        if (!m || m - e->message < 8 || strncmp(m - 2, ": ", 2) ||
            !strstr(e->message, "t.pgt:17:"))
            fail_msg("'%s' not listed, located, in: %s", missing[i],
                     e->message);
    }
    assert_null(strstr(e->message, "dpscan.op"));
    assert_null(strstr(e->message, "dpscan.step"));
    g_error_free(e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_cost_repriced),
        cmocka_unit_test(test_check_rejects_wrong_traces),
        cmocka_unit_test(test_target_lacking_costs),
    };
    return cmocka_run_group_tests(tests, record_once, remove_all);
}
