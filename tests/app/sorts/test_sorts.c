/* test_sorts.c — one scene, three sorts (sim/app/sorts/sorts.h): the
 * load balance from per-processor busy times (idle workers counted, the
 * machine's unused processors not; a wrong count fails), the comparison
 * file's located refusals, a comparison run whose table holds a row
 * per sort and processor count with the overlap of its definition, the
 * shipped comparison made small (all three sorts, each overlap within
 * its definition's range), and the bytes' definitions as claims that
 * could come out false: uncompressed sort-last bytes follow the image
 * size and not the primitives, sort-first's follow the primitives. */
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
    "    workload: {type: sortfirst, resolution: 64, cull_back: false,\n"  \
    "               framebuffer: none}\n"                                 \
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

/* A file whose name cannot stem the outputs (quotes, backquotes, a
 * semicolon: they would reach gnuplot's script as a file name) is
 * refused at load, located at the file, before anything runs or is
 * written; the same text under a plain name loads. */
static void test_hostile_file_name(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-sorts-XXXXXX", NULL);
    const char *text = "three_sorts: 1\nprocessors: [2]\n" SF_SORT;
    char *bad = g_build_filename(dir, "a'b;`touch x`.yaml", NULL);
    char *good = g_build_filename(dir, "plain.yaml", NULL);
    assert_true(g_file_set_contents(bad, text, -1, NULL));
    assert_true(g_file_set_contents(good, text, -1, NULL));
    GError *e = NULL;
    assert_null(sorts_spec_load(bad, NULL, &e));
    assert_non_null(e);
    if (!strstr(e->message, ":1:1: found the comparison (from the file "
                            "name) name 'a'b;`touch x`'"))
        fail_msg("%s", e->message);
    assert_int_equal(sim_error_exit_status(e), 2);
    g_clear_error(&e);
    SortsSpec *s = sorts_spec_load(good, NULL, &e);
    assert_non_null(s);
    sorts_spec_free(s);
    support_rm_tree(dir);
    g_free(bad);
    g_free(good);
    g_free(dir);
}

/* The comparison at path after sets, run: its table (dt_free). */
static DataTable *run_spec(const char *path, const char *const *sets,
                           const char *dir)
{
    GError *e = NULL;
    SortsSpec *s = sorts_spec_load(path, sets, &e);
    if (!s)
        fail_msg("%s", e->message);
    DataTable *t = sorts_run(s, dir, &e);
    if (!t)
        fail_msg("%s", e->message);
    sorts_spec_free(s);
    return t;
}

/* Column col of the row of sort at P. */
static double cell(const DataTable *t, const char *sort, guint procs,
                   const char *col)
{
    int cs = dt_col(t, "sort"), cp = dt_col(t, "processors"),
        cc = dt_col(t, col);
    assert_true(cs >= 0 && cp >= 0 && cc >= 0);
    for (guint r = 0; r < t->rows->len; r++)
        if (!strcmp(dt_cell(t, r, cs), sort) &&
            g_ascii_strtoull(dt_cell(t, r, cp), NULL, 10) == procs)
            return g_ascii_strtod(dt_cell(t, r, cc), NULL);
    fail_msg("no row %s at %u", sort, procs);
    return NAN;
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
    DataTable *t = run_spec(path, NULL, dir);
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
    g_free(path);
    support_rm_tree(dir);
    g_free(dir);
}

/* configs/sorts/three-sorts.yaml at P = 2 and 8, 2 frames: a row for
 * each sort and P; sort-first's and sort-middle's overlap at least 1
 * (a primitive on screen meets a region), sort-middle's the same at
 * every P (its regions are fixed), sort-last's within 1 .. P (images
 * covering a covered pixel); every balance at least 1. */
static void test_shipped(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-sorts-XXXXXX", NULL);
    const char *sets[] = {"processors=[2, 8]", "run.frames=2", NULL};
    DataTable *t = run_spec("configs/sorts/three-sorts.yaml", sets, dir);
    assert_int_equal(t->rows->len, 6);
    static const char *const sorts[] = {"sort-first", "sort-middle",
                                        "sort-last"};
    guint ps[] = {2, 8};
    for (guint i = 0; i < 3; i++)
        for (guint j = 0; j < 2; j++) {
            assert_true(cell(t, sorts[i], ps[j], "overlap") >= 1);
            assert_true(cell(t, sorts[i], ps[j], "balance") >= 1);
            assert_true(cell(t, sorts[i], ps[j], "bytes") > 0);
            assert_true(cell(t, sorts[i], ps[j], "frame_ms") > 0);
        }
    assert_true(cell(t, "sort-last", 8, "overlap") <= 8);
    assert_true(cell(t, "sort-last", 8, "overlap") >
                cell(t, "sort-last", 2, "overlap"));
    assert_true(cell(t, "sort-middle", 2, "overlap") ==
                cell(t, "sort-middle", 8, "overlap"));
    assert_true(cell(t, "sort-first", 8, "overlap") >
                cell(t, "sort-first", 2, "overlap"));
    dt_free(t);
    support_rm_tree(dir);
    g_free(dir);
}

/* Sort-middle (2 GPs, 2 renderers) and sort-last (no bounding
 * rectangles, no RLE; resolution R) of a flock, P = 4. */
static char *claims_spec(const char *dir, guint res)
{
    char *text = g_strdup_printf(
        "three_sorts: 1\nprocessors: [4]\nmachine: {model: cluster-ib}\n"
        FLOCK "run: {frames: 3, fidelity: analytic}\n"
        "sorts:\n"
        "  - sort: middle\n"
        "    workload: {type: pphigs, frame: configs/sorts/frame.yaml,\n"
        "               rebalance: {enabled: false}}\n"
        "    scene: database\n"
        "    processors: {workload.gps: 0.5,\n"
        "                 machine.nodes.renderer.count: 0.5}\n"
        "    overlap: region_overlap\n"
        "    bytes: sort_bytes_per_frame\n"
        "    balance: {gp: 0.5, renderer: 0.5}\n"
        "  - sort: last\n"
        "    workload: {type: pixelmerge, scheme: radix_k, resolution: %u}\n"
        "    processors: {workload.processors: 1}\n"
        "    overlap: image_overlap\n"
        "    bytes: merge_bytes\n"
        "    balance: {node: 1}\n",
        res);
    char *path = write_spec(dir, text);
    g_free(text);
    return path;
}

/* Sort-last's uncompressed images: 4 x the bytes at twice the image
 * side, the same bytes with half the boids; sort-middle's commands:
 * fewer bytes with half the boids.  Each could fail (a sort-last that
 * sent primitives, a sort-middle that sent images). */
static void test_bytes_claims(void **st)
{
    (void)st;
    char *dir = g_dir_make_tmp("pgsim-sorts-XXXXXX", NULL);
    const char *half[] = {"scene.boids=8", NULL}; /* of 16 */
    char *p128 = claims_spec(dir, 128);
    DataTable *a = run_spec(p128, NULL, dir);
    DataTable *b = run_spec(p128, half, dir);
    char *p256 = claims_spec(dir, 256);
    DataTable *c = run_spec(p256, NULL, dir);
    double last = cell(a, "last", 4, "bytes");
    assert_true(last > 0);
    assert_true(cell(c, "last", 4, "bytes") == 4 * last);
    assert_true(cell(b, "last", 4, "bytes") == last);
    double middle = cell(a, "middle", 4, "bytes");
    assert_true(cell(b, "middle", 4, "bytes") < middle);
    dt_free(a);
    dt_free(b);
    dt_free(c);
    g_free(p128);
    g_free(p256);
    support_rm_tree(dir);
    g_free(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_balance),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_hostile_file_name),
        cmocka_unit_test(test_sort_first_rows),
        cmocka_unit_test(test_shipped),
        cmocka_unit_test(test_bytes_claims),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
