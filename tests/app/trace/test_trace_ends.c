/* test_trace_ends.c — on every registered workload, a trace's messages
 * start and end on the processors that sent and received them; on every
 * shipped config, each frame writes one mark "frame N" at its end.
 *
 * Each workload runs one frame of its example config (configs/NAME.yaml
 * whose workload.type names it) with a recording trace.  Spans name the
 * processor that computed; flows name the network endpoints.  The two
 * must agree: an id never stands for two processors, every flow end is a
 * named processor, and the ends that compute somewhere carry the name
 * their spans carry (issue 18: spans once used first-use entity numbers
 * while flows used processor ids, so arrows joined the wrong tracks).
 */
#include "sim/run/run.h"
#include "sim/core/trace.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

typedef struct {
    GHashTable *names; /* id + 1 -> name (first seen) */
    const char *where;
    uint64_t spans, flows;
} Ends;

static void see(Ends *e, uint32_t id, const char *name, const char *what)
{
    if (!name)
        fail_msg("%s: a %s end (node %u) has no processor name", e->where,
                 what, id);
    gpointer key = GUINT_TO_POINTER(id + 1);
    const char *old = g_hash_table_lookup(e->names, key);
    if (!old)
        g_hash_table_insert(e->names, key, g_strdup(name));
    else if (strcmp(old, name) != 0)
        fail_msg("%s: node %u is '%s' in one event and '%s' in a %s",
                 e->where, id, old, name, what);
}

static void on_span(SimTrace *tr, uint32_t node, const char *name,
                    const char *phase, SimTime start, SimTime end)
{
    (void)phase;
    Ends *e = tr->state;
    assert_true(start <= end);
    see(e, node, name, "span");
    e->spans++;
}

static void on_flow(SimTrace *tr, uint32_t src, const char *sn, uint32_t dst,
                    const char *dn, uint64_t bytes, SimTime sent,
                    SimTime arrived)
{
    (void)bytes;
    Ends *e = tr->state;
    assert_true(sent <= arrived);
    see(e, src, sn, "message's sending");
    see(e, dst, dn, "message's receiving");
    e->flows++;
}

static const SimTraceOps ops = {.span = on_span, .flow = on_flow};

/* Marks: "frame N" at index N holds its time (-1: not seen). */
static void on_mark(SimTrace *tr, const char *name, SimTime t)
{
    GArray *marks = tr->state;
    guint n;
    if (sscanf(name, "frame %u", &n) != 1)
        return;
    assert_true(n < 64);
    if (n >= marks->len)
        g_array_set_size(marks, n + 1);
    SimTime *at = &g_array_index(marks, SimTime, n);
    if (*at)
        fail_msg("'%s' marked twice", name);
    *at = t + 1; /* 0: not marked */
}

static const SimTraceOps mark_ops = {.mark = on_mark};

/* The first top-level example config running workload `name`. */
static char *config_for(const char *name)
{
    GDir *d = g_dir_open("configs", 0, NULL);
    assert_non_null(d);
    GPtrArray *files = g_ptr_array_new_with_free_func(g_free);
    for (const char *f; (f = g_dir_read_name(d));)
        if (g_str_has_suffix(f, ".yaml"))
            g_ptr_array_add(files, g_build_filename("configs", f, NULL));
    g_dir_close(d);
    g_ptr_array_sort(files, (GCompareFunc)g_strcmp0);
    char *hit = NULL;
    for (guint i = 0; !hit && i < files->len; i++) {
        CfgNode *root = cfg_load_file(files->pdata[i], NULL);
        const char *type =
            cfg_scalar(cfg_get(cfg_get(root, "workload"), "type"));
        if (root && cfg_get(root, "schema_version") && type &&
            strcmp(type, name) == 0)
            hit = g_strdup(files->pdata[i]);
        cfg_free(root);
    }
    g_ptr_array_free(files, TRUE);
    return hit;
}

static void check_workload(const WlOps *wl)
{
    char *path = config_for(wl->name);
    if (!path)
        fail_msg("workload '%s' has no example config in configs/", wl->name);
    const char *const sets[] = {"run.frames=1", NULL};
    GError *err = NULL;
    CfgRun *r = cfg_run_load(path, sets, &err);
    g_assert_no_error(err);
    Ends e = {g_hash_table_new_full(NULL, NULL, NULL, g_free), path, 0, 0};
    SimTrace tr = {&ops, &e};
    CfgRunOpts o = {.quiet = TRUE, .trace = &tr};
    SimResult *res = cfg_run_exec(r, &o, &err);
    g_assert_no_error(err);
    /* every message the network delivered is drawn (a SIMD array's
     * router is part of its step cost: no messages, no arrows) */
    if (!e.spans || e.flows != res->comm_messages)
        fail_msg("%s: %" G_GUINT64_FORMAT " spans, %" G_GUINT64_FORMAT
                 " traced messages, %" G_GUINT64_FORMAT " delivered",
                 path, e.spans, e.flows, (uint64_t)res->comm_messages);
    sim_result_free(res);
    cfg_run_free(r);
    g_hash_table_destroy(e.names);
    g_free(path);
}

static void test_every_workload(void **state)
{
    (void)state;
    for (guint i = 0; wl_all[i]; i++)
        check_workload(wl_all[i]);
}

/* Frame k's mark is at least frame k's time after frame k-1's mark (equal
 * when frames run back to back, later when work comes between them, as
 * PPHIGS's edits) and no later than the run's end. */
static void check_marks(const char *path, const GArray *marks,
                        const SimResult *res)
{
    if (marks->len != res->frame_times->len)
        fail_msg("%s: %u frame marks for %u frames", path, marks->len,
                 res->frame_times->len);
    SimTime prev = 0;
    for (guint f = 0; f < marks->len; f++) {
        SimTime at = g_array_index(marks, SimTime, f);
        if (!at)
            fail_msg("%s: frame %u has no mark", path, f);
        at--;
        SimTime ft = g_array_index(res->frame_times, SimTime, f);
        if (at < prev || at - prev + 1 < ft || at > res->elapsed)
            fail_msg("%s: frame %u marked at %.3f us after %.3f us, frame "
                     "time %.3f us, run end %.3f us",
                     path, f, sim_time_to_us(at), sim_time_to_us(prev),
                     sim_time_to_us(ft), sim_time_to_us(res->elapsed));
        prev = at;
    }
}

/* Two frames of every top-level run config; sizes cut where a frame
 * takes long (keys a config lacks are refused, so only dpscan's). */
static void check_config_marks(const char *path)
{
    const char *small[] = {"run.frames=2", NULL, NULL, NULL};
    if (strstr(path, "dpscan")) {
        small[1] = "workload.width=320";
        small[2] = "workload.height=256";
    }
    GError *err = NULL;
    CfgRun *r = cfg_run_load(path, small, &err);
    g_assert_no_error(err);
    GArray *marks = g_array_new(FALSE, TRUE, sizeof(SimTime));
    SimTrace tr = {&mark_ops, marks};
    CfgRunOpts o = {.quiet = TRUE, .trace = &tr};
    SimResult *res = cfg_run_exec(r, &o, &err);
    g_assert_no_error(err);
    assert_int_equal(res->frame_times->len, 2);
    check_marks(path, marks, res);
    g_array_free(marks, TRUE);
    sim_result_free(res);
    cfg_run_free(r);
}

static void test_frame_marks(void **state)
{
    (void)state;
    GDir *d = g_dir_open("configs", 0, NULL);
    assert_non_null(d);
    guint runs = 0;
    for (const char *f; (f = g_dir_read_name(d));) {
        char *path = g_build_filename("configs", f, NULL);
        CfgNode *root =
            g_str_has_suffix(f, ".yaml") ? cfg_load_file(path, NULL) : NULL;
        if (root && cfg_get(root, "schema_version") &&
            cfg_get(cfg_get(root, "workload"), "type")) {
            check_config_marks(path);
            runs++;
        }
        cfg_free(root);
        g_free(path);
    }
    g_dir_close(d);
    assert_true(runs >= 9); /* each workload's example at least */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_workload),
        cmocka_unit_test(test_frame_marks),
    };
    return cmocka_run_group_tests_name("trace_ends", tests, NULL, NULL);
}
