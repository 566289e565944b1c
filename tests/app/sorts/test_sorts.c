/* test_sorts.c — one scene, three sorts (sim/app/sorts/sorts.h): the
 * load balance from per-processor busy times (idle workers counted, the
 * machine's unused processors not; a wrong count fails), the comparison
 * file's located refusals, and a comparison run whose table holds a row
 * per sort and processor count with the overlap of its definition. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include <glib.h>

#include "tests/support.h"

#include "sim/app/sorts/sorts.h"
#include "sim/core/error.h"

static void add_node(SimResult *r, const char *kind, guint i, SimTime busy)
{
    SimNodeResult *n = g_new0(SimNodeResult, 1);
    n->name = g_strdup_printf("%s%u", kind, i);
    n->kind = g_strdup(kind);
    sim_busy_init(&n->busy);
    n->busy.total = busy;
    g_ptr_array_add(r->nodes, n);
}

/* Busy 1, 1, 1, 5 on four nodes and 9 on a gp: node balance 5 / 2 over
 * the four, 5 / 1 over eight workers (four did nothing); the gp is not
 * in it; more busy nodes than workers is no balance (NAN). */
static void test_balance(void **st)
{
    (void)st;
    SimResult *r = sim_result_new("test", "m");
    SimTime b[] = {1000, 1000, 1000, 5000};
    for (guint i = 0; i < 4; i++)
        add_node(r, "node", i, b[i]);
    add_node(r, "gp", 0, 9000);
    assert_true(fabs(sorts_kind_balance(r, "node", 4) - 2.5) < 1e-12);
    assert_true(fabs(sorts_kind_balance(r, "node", 8) - 5.0) < 1e-12);
    assert_true(fabs(sorts_kind_balance(r, "gp", 2) - 2.0) < 1e-12);
    assert_true(isnan(sorts_kind_balance(r, "node", 3)));
    assert_true(isnan(sorts_kind_balance(r, "renderer", 4)));
    sim_result_free(r);
}

static char *write_spec(const char *dir, const char *text)
{
    char *path = g_build_filename(dir, "spec.yaml", NULL);
    assert_true(g_file_set_contents(path, text, -1, NULL));
    return path;
}

/* The file's refusals are located in it (line:column), exit status 2. */
static void expect_refused(const char *dir, const char *text,
                           const char *where, const char *what)
{
    char *path = write_spec(dir, text);
    GError *e = NULL;
    SortsSpec *s = sorts_spec_load(path, NULL, &e);
    DataTable *t = NULL;
    if (s) { /* refused only when run (a share that is no whole count) */
        t = sorts_run(s, dir, &e);
        sorts_spec_free(s);
    }
    assert_null(t);
    assert_non_null(e);
    if (!strstr(e->message, where) || !strstr(e->message, what))
        fail_msg("expected '%s' and '%s' in: %s", where, what, e->message);
    assert_int_equal(sim_error_exit_status(e), 2);
    g_error_free(e);
    g_free(path);
}

#define SF_SORT                                                              \
    "sorts:\n"                                                               \
    "  - sort: sort-first\n"                                                 \
    "    workload: {type: sortfirst, resolution: 64, cull_back: false}\n"    \
    "    processors: {workload.processors: 1}\n"                             \
    "    overlap: chunk_overlap\n"                                           \
    "    bytes: migrated_bytes_per_frame\n"                                  \
    "    balance: {node: 1}\n"

#define FLOCK                                                                \
    "scene: {generator: flock_old_well, seed: 3, verts: 4, size: 100,\n"     \
    "        boids: 16, boid_polygons: 5, boid_colors: 4, well_structs: 2,\n" \
    "        well_polygons: 40, well_attributes: 10,\n"                      \
    "        path: {kind: orbit, degrees_per_frame: 3}}\n"

static void test_refusals(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-sorts-XXXXXX", NULL);
    expect_refused(dir, "three_sorts: 2\nprocessors: [2]\n" SF_SORT,
                   "spec.yaml:1:14", "three_sorts: 1");
    expect_refused(dir, "three_sorts: 1\nprocessors: [2, 0]\n" SF_SORT,
                   "spec.yaml:2:17", "a processor count");
    expect_refused(dir, "three_sorts: 1\nprocessors: [2]\n",
                   "spec.yaml:1:1", "sorts:");
    expect_refused(dir, "three_sorts: 1\nprocessors: [2]\nwhat: 1\n" SF_SORT,
                   "spec.yaml:3:1", "what");
    expect_refused(dir,
                   "three_sorts: 1\nprocessors: [3]\n"
                   "machine: {model: cluster-ib}\n" FLOCK
                   "sorts:\n  - sort: half\n"
                   "    workload: {type: sortfirst}\n"
                   "    processors: {workload.processors: 0.5}\n"
                   "    overlap: chunk_overlap\n    bytes: initial_bytes\n"
                   "    balance: {node: 1}\n",
                   "sort 'half'", "0.5 x 3 = 1.5");
    expect_refused(dir,
                   "three_sorts: 1\nprocessors: [2]\n"
                   "machine: {model: cluster-ib}\n" FLOCK
                   "sorts:\n  - sort: db\n"
                   "    workload: {type: sortfirst}\n"
                   "    scene: databases\n"
                   "    processors: {workload.processors: 1}\n"
                   "    overlap: chunk_overlap\n    bytes: initial_bytes\n"
                   "    balance: {node: 1}\n",
                   "spec.yaml:", "section");
    support_rm_tree(dir);
    g_free(dir);
}

/* Sort-first alone on the cluster: a row per processor count, overlap
 * (regions per on-screen chunk) at least 1 and growing with the regions,
 * balance at least 1, and the scene's database written for a sort that
 * reads it as a file. */
static void test_sort_first_rows(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-sorts-XXXXXX", NULL);
    char *path = write_spec(dir, "three_sorts: 1\nname: t\n"
                                 "processors: [2, 8]\n"
                                 "machine: {model: cluster-ib}\n" FLOCK
                                 "run: {frames: 2, fidelity: analytic}\n"
                                 SF_SORT);
    GError *e = NULL;
    SortsSpec *s = sorts_spec_load(path, NULL, &e);
    if (!s)
        fail_msg("%s", e->message);
    DataTable *t = sorts_run(s, dir, &e);
    if (!t)
        fail_msg("%s", e->message);
    assert_int_equal(t->rows->len, 2);
    int c_sort = dt_col(t, "sort"), c_p = dt_col(t, "processors"),
        c_ov = dt_col(t, "overlap"), c_bal = dt_col(t, "balance");
    assert_true(c_sort >= 0 && c_p >= 0 && c_ov >= 0 && c_bal >= 0);
    assert_true(dt_col(t, "bytes") >= 0 && dt_col(t, "frame_ms") >= 0);
    assert_string_equal(dt_cell(t, 0, c_sort), "sort-first");
    assert_string_equal(dt_cell(t, 1, c_p), "8");
    double ov2 = g_ascii_strtod(dt_cell(t, 0, c_ov), NULL);
    double ov8 = g_ascii_strtod(dt_cell(t, 1, c_ov), NULL);
    assert_true(ov2 >= 1 && ov8 > ov2);
    assert_true(g_ascii_strtod(dt_cell(t, 1, c_bal), NULL) >= 1);
    dt_free(t);
    sorts_spec_free(s);
    g_free(path);
    support_rm_tree(dir);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_balance),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_sort_first_rows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
