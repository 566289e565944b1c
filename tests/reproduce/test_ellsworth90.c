/* test_ellsworth90.c — the PPHIGS reproduction's table from runs of a
 * cell config (sim/reproduce/ellsworth90.h): every cell of every
 * database at each GP count, then the database rows; a database the
 * generator cannot build is an error, not a number; a key of the cell
 * nobody reads is refused where it stands. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/reproduce/ellsworth90.h"
#include "tests/support.h"

/* Two small databases (a flock, two shallow figures) and one whose
 * depth cannot be met, with a 640 x 512 frame. */
static const char *dbs_yaml =
    "flock: {kind: flock_old_well, seed: 9, verts: 4, size: 10, boids: 30,\n"
    "  boid_polygons: 5, boid_colors: 4, well_structs: 10,\n"
    "  well_polygons: 60, well_attributes: 5}\n"
    "humans: {kind: two_human_figures, seed: 9, verts: 4, size: 10,\n"
    "  boids: 30, boid_polygons: 5, boid_colors: 4, well_structs: 10,\n"
    "  well_polygons: 60, well_attributes: 5, figures: 2, structures: 20,\n"
    "  polygons: 200, levels: 5}\n"
    "too_deep: {kind: two_human_figures, seed: 9, verts: 4, size: 10,\n"
    "  figures: 2, structures: 20, polygons: 200, levels: 50}\n";
static const char *frame_yaml =
    "{width: 640, height: 512, region: 128, cmd_bytes: 100, end_bytes: 16,\n"
    " batch: 16, pixel_bytes: 4, element_bytes: 80,\n"
    " cluster_scale: {value: 64, assumption: test}}\n";

typedef struct {
    char *dir;
    CfgNode *cell;
} Fix;

static int setup(void **state)
{
    Fix *f = g_new0(Fix, 1);
    f->dir = g_dir_make_tmp("ellsworth90-XXXXXX", NULL);
    assert_non_null(f->dir);
    char *dbs = g_build_filename(f->dir, "dbs.yaml", NULL);
    char *fr = g_build_filename(f->dir, "frame.yaml", NULL);
    assert_true(g_file_set_contents(dbs, dbs_yaml, -1, NULL));
    assert_true(g_file_set_contents(fr, frame_yaml, -1, NULL));
    char *cell = g_strdup_printf(
        "schema_version: 1\n"
        "machine: {model: pixel-planes-5}\n"
        "workload: {type: pphigs, databases: %s, frame: %s,\n"
        "  rebalance: {enabled: false}}\n"
        "run: {frames: 1}\n",
        dbs, fr);
    f->cell = cfg_load_string(cell, "cell.yaml", NULL);
    assert_non_null(f->cell);
    g_free(cell);
    g_free(dbs);
    g_free(fr);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    Fix *f = *state;
    cfg_free(f->cell);
    support_rm_tree(f->dir);
    g_free(f->dir);
    g_free(f);
    return 0;
}

static void test_table_rows(void **state)
{
    Fix *f = *state;
    const guint gps[] = {4, 16};
    RpEllRig rig = {f->cell, "analytic", gps, 2, NULL};
    const char *dbs[] = {"flock", "humans", "too_deep"};
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    assert_true(rp_ellsworth90_table1(&rig, dbs, 2, rows, NULL));
    /* + by-structure, + the rates of the million claims */
    assert_int_equal(rows->len, 2 * (8 + 6 + 5 + 2));
    guint table1 = 0;
    for (guint i = 0; i < rows->len; i++) {
        RpRow *r = g_ptr_array_index(rows, i);
        if (g_strcmp0(r->table, "1") == 0)
            table1++;
        if (g_strcmp0(r->column, "depth") == 0)
            assert_true(r->sim == (i < 21 ? 2 : 5));
    }
    assert_int_equal(table1, 28);
    g_ptr_array_unref(rows);
    GError *err = NULL; /* levels 50 cannot be met */
    rows = g_ptr_array_new_with_free_func(rp_row_free);
    assert_false(rp_ellsworth90_table1(&rig, dbs + 1, 2, rows, &err));
    assert_non_null(err);
    g_clear_error(&err);
    g_ptr_array_unref(rows);
}

/* The cells of the flock database, run with ctx (NULL: none). */
static GPtrArray *flock_rows(const Fix *f, const RpContext *ctx,
                             GError **err)
{
    static const guint gps[] = {4};
    RpEllRig rig = {f->cell, "analytic", gps, 1, ctx};
    const char *dbs[] = {"flock"};
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    if (!rp_ellsworth90_table1(&rig, dbs, 1, rows, err)) {
        g_ptr_array_unref(rows);
        return NULL;
    }
    return rows;
}

/* `reproduce --set machine...` reaches every run: a dearer polygon on
 * the GPs moves the efficiency cells; a bad machine key is an error. */
static void test_what_if_set(void **state)
{
    Fix *f = *state;
    const char *const sets[] = {"machine.nodes.gp.costs.polygon=40 us", NULL};
    const char *const bad[] = {"machine.nodes.gp.costs.polygon=fast", NULL};
    RpContext what_if = {.fidelity = "analytic", .sets = sets};
    RpContext broken = {.fidelity = "analytic", .sets = bad};
    GPtrArray *a = flock_rows(f, NULL, NULL), *b = flock_rows(f, &what_if,
                                                               NULL);
    assert_non_null(a);
    assert_non_null(b);
    assert_int_equal(a->len, b->len);
    guint moved = 0;
    for (guint i = 0; i < a->len; i++) {
        const RpRow *x = g_ptr_array_index(a, i), *y = g_ptr_array_index(b, i);
        assert_string_equal(x->column, y->column);
        moved += x->sim != y->sim;
    }
    assert_true(moved > 0);
    GError *err = NULL;
    assert_null(flock_rows(f, &broken, &err));
    assert_non_null(err);
    g_clear_error(&err);
    g_ptr_array_unref(a);
    g_ptr_array_unref(b);
}

/* A misspelt key of the cell: the runner refuses it, located. */
static void test_cell_unknown_key(void **state)
{
    Fix *f = *state;
    CfgNode *cell = cfg_copy(f->cell);
    assert_true(cfg_set_override(cell, "workload.rebalnce=1", NULL));
    const guint gps[] = {4};
    RpEllRig rig = {cell, "analytic", gps, 1, NULL};
    const char *dbs[] = {"flock"};
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    GError *err = NULL;
    assert_false(rp_ellsworth90_table1(&rig, dbs, 1, rows, &err));
    assert_non_null(strstr(err->message, "rebalnce"));
    assert_int_equal(rows->len, 0);
    g_clear_error(&err);
    g_ptr_array_unref(rows);
    cfg_free(cell);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_rows),
        cmocka_unit_test(test_cell_unknown_key),
        cmocka_unit_test(test_what_if_set),
    };
    return cmocka_run_group_tests_name("ellsworth90", tests, setup, teardown);
}
