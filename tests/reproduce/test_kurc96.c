/* test_kurc96.c — `pgsim reproduce kurc96` on a reduced setup (the
 * real configs/papers/kurc96/setup.yaml with 300-polygon teapots, through
 * RpContext.setup): every row key and column the issue names is
 * produced once, joined to configs/papers/kurc96/published.yaml with no
 * published cell left unsimulated, values are finite and sensible, the P=8
 * ZBUF-EXC cells carry the out-of-memory note, and the run honours the
 * context's fidelity.  The cross-validation's cost scaling reaches the
 * machine (a merge cost moves the merge time, and only it; a scale of 1
 * changes nothing), and the memory note's format. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <glib/gstdio.h>
#include <string.h>

#include "sim/reproduce/rp_driver.h"
#include "sim/reproduce/kurc96.h"

static char *small_setup(void)
{
    char *text = NULL;
    assert_true(g_file_get_contents("configs/papers/kurc96/setup.yaml", &text,
                                    NULL, NULL));
    GString *s = g_string_new(text);
    guint n = g_string_replace(s, "polygons_per_teapot: 3751",
                               "polygons_per_teapot: 300", 0);
    assert_int_equal(n, 6);
    char *path =
        g_build_filename(g_get_tmp_dir(), "pgsim-kurc96-test.yaml", NULL);
    assert_true(g_file_set_contents(path, s->str, -1, NULL));
    g_string_free(s, TRUE);
    g_free(text);
    return path;
}

static const RpJoined *cell(const RpTable *t, const char *table,
                            const char *row, const char *col)
{
    const RpJoined *j = rp_table_find(t, table, row, col);
    if (!j)
        fail_msg("missing %s %s %s", table, row, col);
    assert_true(isfinite(j->sim));
    return j;
}

static void check_tables(const RpTable *t)
{
    static const char *const t1[] = {"polygons", "tpg_400", "tpf_400",
                                     "tpg_640", "tpf_640"};
    static const char *const t2[] = {"pair_rs_span_ms",  "pair_rs_zbuf_ms",
                                     "pair_rs_merge_ms", "zbuf_exc_span_ms",
                                     "zbuf_exc_zbuf_ms", "zbuf_exc_merge_ms"};
    for (int i = 0; rp_kurc96_scenes[i]; i++) {
        const char *s = rp_kurc96_scenes[i];
        for (int c = 0; c < 5; c++)
            assert_true(cell(t, "1", s, t1[c])->sim > 0);
        /* TPF <= TPG, and more pixels at N=640 */
        assert_true(cell(t, "1", s, "tpf_400")->sim <=
                    cell(t, "1", s, "tpg_400")->sim);
        assert_true(cell(t, "1", s, "tpf_640")->sim >
                    cell(t, "1", s, "tpf_400")->sim);
        for (int p = 16; p >= 8; p /= 2) {
            char *row = g_strdup_printf("P%d/%s", p, s);
            for (int c = 0; c < 6; c++) {
                const RpJoined *j = cell(t, "2", row, t2[c]);
                assert_true(j->sim > 0);
                /* every ZBUF-EXC cell has the memory verdict in MiB;
                 * every P=16 run fitted (the paper has its times) */
                if (c >= 3)
                    assert_non_null(j->note && strstr(j->note, "MiB"));
                if (p == 16)
                    assert_true(!j->note || g_str_has_prefix(j->note, "fits"));
            }
            g_free(row);
        }
    }
}

static void check_figs(const RpTable *t)
{
    static const char *const f1[] = {"pair_rs_bytes", "pair_hbp_bytes",
                                     "aapc_rs_bytes", "aapc_hbp_bytes"};
    char row[64];
    for (int p = 2; p <= 16; p *= 2) {
        g_snprintf(row, sizeof row, "a/P%d", p);
        for (int c = 0; c < 4; c++)
            assert_true(cell(t, "fig1", row, f1[c])->sim > 0);
        assert_true(cell(t, "fig2", row, "rs_imbalance")->sim >= 0);
        assert_true(cell(t, "fig2", row, "hbp_imbalance")->sim >= 0);
    }
    for (int i = 0; rp_kurc96_scenes[i]; i++)
        for (int n = 400; n <= 640; n += 240) {
            g_snprintf(row, sizeof row, "b/%s/%d", rp_kurc96_scenes[i], n);
            for (int c = 0; c < 4; c++)
                assert_true(cell(t, "fig1", row, f1[c])->sim > 0);
            /* HBP balances at least as well as RS (seed 003 Fig. 2) */
            assert_true(cell(t, "fig2", row, "hbp_imbalance")->sim <=
                        cell(t, "fig2", row, "rs_imbalance")->sim + 1e-9);
        }
    const RpJoined *s = cell(t, "text", "P16/2POT/640", "aapc_hbp_speedup");
    assert_true(s->sim > 1 && s->sim <= 16); /* no speed-up above P */
    assert_int_equal(s->status, RP_WITHHELD);
}

static void test_rows_complete(void **state)
{
    (void)state;
    char *path = small_setup();
    RpContext ctx = {
        .setup = path, .fidelity = "faithful", .out_dir = NULL, .quiet = TRUE};
    GError *err = NULL;
    RpTable *t = rp_drive(&rp_kurc96, RP_PAPERS_DIR, &ctx, &err);
    if (!t)
        fail_msg("%s", err->message);
    assert_string_equal(t->fidelity, "faithful: ipsc2 packet");
    for (guint i = 0; i < t->cells->len; i++) {
        const RpJoined *j = g_ptr_array_index(t->cells, i);
        if (j->status == RP_MISSING)
            fail_msg("not simulated: %s %s %s", j->table, j->row, j->column);
    }
    check_tables(t);
    check_figs(t);
    /* 6 x 6 + 12 x 6 + 36 + 4 (cross-validation) + 16 x 6 (fig rows) + 1
     * + 10 claims x (cases, cases_holding, holds) */
    assert_int_equal(t->cells->len, 36 + 72 + 40 + 96 + 1 + 30);
    assert_true(isfinite(cell(t, "claims", "recommended", "holds")->sim));
    for (int i = 0; rp_kurc96_scenes[i]; i++) /* end points: below 2.56 */
        assert_true(cell(t, "1", rp_kurc96_scenes[i], "tpg_640_over_400")->sim <
                    2.56);
    assert_true(cell(t, "cv", "P16", "loso_mean_abs_pct")->sim >= 0);
    assert_int_equal(t->compared, 54);
    rp_table_free(t);
    g_unlink(path);
    g_free(path);
}

/* One P=16, N=400 PAIR-RS run of the reduced 1POT at the analytic
 * network, its fitted cost groups scaled by scale (NULL: none). */
static RpKurcRun run_scaled(const char *path, const double *scale)
{
    RpContext ctx = {.setup = path, .fidelity = "analytic", .quiet = TRUE};
    RpKurcSpec sp = {"1POT", 400, 16, "pair", "rs"};
    RpKurcRun r;
    GError *err = NULL;
    if (!rp_kurc96_simulate(&ctx, &sp, scale, &r, &err))
        fail_msg("%s", err->message);
    return r;
}

/* A scaled cost group is an override of the model's node costs, so it
 * reaches the machine that prices the work: compare (group 5) x 1.1
 * lengthens the merge, which the processors time, and leaves the local
 * phases alone; polygon (group 0) x 1.1 lengthens span creation only;
 * all factors 1 give the unscaled run bit for bit. */
static void test_cost_scale_override(void **state)
{
    (void)state;
    char *path = small_setup();
    double one[RP_KURC_GROUPS], cmp[RP_KURC_GROUPS], poly[RP_KURC_GROUPS];
    for (int g = 0; g < RP_KURC_GROUPS; g++)
        one[g] = cmp[g] = poly[g] = 1;
    cmp[5] = poly[0] = 1.1;
    RpKurcRun base = run_scaled(path, NULL), same = run_scaled(path, one);
    RpKurcRun c = run_scaled(path, cmp), p = run_scaled(path, poly);
    assert_true(same.span_ms == base.span_ms && same.zbuf_ms == base.zbuf_ms &&
                same.merge_ms == base.merge_ms && same.speedup == base.speedup);
    assert_true(c.merge_ms > base.merge_ms);
    assert_true(c.span_ms == base.span_ms && c.zbuf_ms == base.zbuf_ms);
    assert_true(p.span_ms > base.span_ms);
    assert_true(p.zbuf_ms == base.zbuf_ms && p.merge_ms == base.merge_ms);
    assert_true(p.volume == base.volume && c.volume == base.volume);
    g_unlink(path);
    g_free(path);
}

/* The memory note: the peak against the node's memory (at it: fits),
 * every part in MiB. */
static void test_memory_note(void **state)
{
    (void)state;
    RpKurcRun r = {.memory = 3250,
                   .node_memory = 3250,
                   .mem_part = {1000, 600, 210, 640, 800}};
    char *v = rp_kurc96_memory_note(&r);
    assert_string_equal(v, "fits: 0.00 of 0.00 MiB (base 0.00, polygons "
                           "0.00, spans 0.00, z-buffer/WPA 0.00, message "
                           "buffers 0.00)");
    g_free(v);
    r.node_memory = 3249;
    v = rp_kurc96_memory_note(&r);
    assert_true(g_str_has_prefix(v, "* out of memory: 0.00 of 0.00 MiB"));
    g_free(v);
    const double mb = 1048576;
    r = (RpKurcRun){.memory = 15 * mb,
                    .node_memory = 16 * mb,
                    .mem_part = {mb, 2 * mb, 3 * mb, 4 * mb, 5 * mb}};
    v = rp_kurc96_memory_note(&r);
    assert_string_equal(v, "fits: 15.00 of 16.00 MiB (base 1.00, polygons "
                           "2.00, spans 3.00, z-buffer/WPA 4.00, message "
                           "buffers 5.00)");
    g_free(v);
    r.memory = 16 * mb + 1;
    v = rp_kurc96_memory_note(&r);
    assert_true(g_str_has_prefix(v, "* out of memory: 16.00 of 16.00 MiB"));
    g_free(v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rows_complete),
        cmocka_unit_test(test_cost_scale_override),
        cmocka_unit_test(test_memory_note),
    };
    return cmocka_run_group_tests_name("rp_kurc96", tests, NULL, NULL);
}
