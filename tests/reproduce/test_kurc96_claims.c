/* test_kurc96_claims.c — each statement of kurc96_claims.c on made-up
 * figures: a set on which all ten hold, then, one at a time, a change
 * that breaks exactly one claim and leaves the other nine holding, so
 * every claim is shown able to come out 0 (and its note to say why). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/reproduce/kurc96.h"

static const char *const claims[] = {
    "T2_merge", "T2_zbuf",    "C_active",       "F1_aapc",     "F1a_fewer",
    "F1b_hbp",  "F2_balance", "F2b_resolution", "F2a_scaling", "recommended",
    NULL};

/* Table 2 rows on which the three Table 2 claims hold: ZBUF-EXC's
 * phases 100, 50, 40 ms against PAIR-RS's 100, 20, 10. */
static void table2(GPtrArray *rows)
{
    static const char *const ps[] = {"P16", "P8"};
    static const char *const col[] = {"pair_rs_span_ms",  "pair_rs_zbuf_ms",
                                      "pair_rs_merge_ms", "zbuf_exc_span_ms",
                                      "zbuf_exc_zbuf_ms", "zbuf_exc_merge_ms"};
    static const double v[] = {100, 20, 10, 100, 50, 40};
    for (int p = 0; p < 2; p++)
        for (int s = 0; rp_kurc96_scenes[s]; s++) {
            char row[48];
            g_snprintf(row, sizeof row, "%s/%s", ps[p], rp_kurc96_scenes[s]);
            for (int c = 0; c < 6; c++)
                g_ptr_array_add(rows, rp_row_new("2", row, col[c], v[c], NULL));
        }
}

/* A Fig. 1-2 point on which every claim holds: volumes PAIR-RS,
 * PAIR-HBP, AAPC-RS, AAPC-HBP falling with P, imbalances RS, HBP. */
static RpKurcPoint point(guint procs, double scale, double rs_imb)
{
    RpKurcPoint p = {NULL, procs, {0}, {0}};
    double k = 1.0 / procs;
    p.volume[0] = 400 * k * scale;
    p.volume[1] = 300 * k * scale;
    p.volume[2] = 200 * k * scale;
    p.volume[3] = 100 * k * scale;
    p.imbalance[0] = rs_imb;
    p.imbalance[1] = rs_imb * 0.1;
    return p;
}

static void good_figs(RpKurcFigs *f)
{
    memset(f, 0, sizeof *f);
    static const guint P[] = {2, 4, 8, 16};
    for (guint i = 0; i < 4; i++)
        f->a[i] = point(P[i], 1, 0.1 * (i + 1)); /* RS grows with P */
    f->n_a = 4;
    for (guint i = 0; i < 12; i++) /* pairs (400, 640): better at 640 */
        f->b[i] = point(16, 1, i % 2 ? 0.2 : 0.3);
    f->n_b = 12;
}

static double holds(const GPtrArray *rows, const char *id)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (!strcmp(r->table, "claims") && !strcmp(r->row, id) &&
            !strcmp(r->column, "holds"))
            return r->sim;
    }
    fail_msg("no claim %s", id);
    return NAN;
}

/* ZBUF-EXC's three phases (span, z-buffer, merge), ms. */
typedef struct {
    double span, zbuf, merge;
} Zx;

/* Runs the claims on f and Table 2 with ZBUF-EXC's phases zx; every
 * claim must hold except `broken` (NULL: none), which must not. */
static void expect(const RpKurcFigs *f, Zx zx, const char *broken)
{
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    table2(rows);
    for (guint i = 0; i < rows->len; i++) {
        RpRow *r = rows->pdata[i];
        if (!strcmp(r->column, "zbuf_exc_span_ms"))
            r->sim = zx.span;
        if (!strcmp(r->column, "zbuf_exc_zbuf_ms"))
            r->sim = zx.zbuf;
        if (!strcmp(r->column, "zbuf_exc_merge_ms"))
            r->sim = zx.merge;
    }
    rp_kurc96_claims(f, rows);
    for (int k = 0; claims[k]; k++) {
        double h = holds(rows, claims[k]);
        gboolean want = !broken || strcmp(claims[k], broken) != 0;
        if (h != (want ? 1 : 0))
            fail_msg("claim %s: holds %g, expected %d (breaking %s)",
                     claims[k], h, want, broken ? broken : "none");
    }
    g_ptr_array_free(rows, TRUE);
}

static const Zx good = {100, 50, 40};

static void test_all_hold(void **state)
{
    (void)state;
    RpKurcFigs f;
    good_figs(&f);
    expect(&f, good, NULL);
}

static void test_each_can_fail(void **state)
{
    (void)state;
    RpKurcFigs f;
    good_figs(&f);
    /* a merge 1.5 times PAIR-RS's 10 ms, not twice */
    expect(&f, (Zx){100, 50, 15}, "T2_merge");
    /* a z-buffer phase under PAIR-RS's 20 ms, the sum still above */
    expect(&f, (Zx){100, 10, 40}, "T2_zbuf");
    /* both phases as claimed, a span so short the sum is below */
    expect(&f, (Zx){50, 30, 40}, "C_active");
    /* AAPC-RS above PAIR-RS at a Fig. 1b point (the HBP orders kept) */
    f.b[3].volume[2] = f.b[3].volume[0] * 1.01;
    f.b[3].volume[3] = f.b[3].volume[2] * 0.5;
    expect(&f, good, "F1_aapc");
    /* PAIR-HBP rising from P=4 to P=8 in Fig. 1a */
    good_figs(&f);
    f.a[2].volume[1] = f.a[1].volume[1] * 1.01;
    f.a[2].volume[0] = f.a[2].volume[1] * 1.5;
    expect(&f, good, "F1a_fewer");
    /* PAIR-HBP above PAIR-RS at a Fig. 1b point */
    good_figs(&f);
    f.b[5].volume[1] = f.b[5].volume[0] * 1.01;
    expect(&f, good, "F1b_hbp");
    /* HBP's imbalance above half of RS's at one point */
    good_figs(&f);
    f.b[0].imbalance[1] = 0.6 * f.b[0].imbalance[0];
    expect(&f, good, "F2_balance");
    /* RS's imbalance at 640 above its imbalance at 400 for one scene */
    good_figs(&f);
    f.b[7].imbalance[0] = 0.35;
    f.b[7].imbalance[1] = 0.02;
    expect(&f, good, "F2b_resolution");
    /* from P=8 to 16, RS's imbalance grows by 0.01, HBP's by 0.12 */
    good_figs(&f);
    f.a[3].imbalance[0] = 0.31;
    f.a[3].imbalance[1] = 0.15;
    expect(&f, good, "F2a_scaling");
    /* at P=2 (no AAPC/PAIR claim there), AAPC-HBP above PAIR-HBP */
    good_figs(&f);
    f.a[0].volume[3] = f.a[0].volume[1] * 1.1;
    expect(&f, good, "recommended");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_hold),
        cmocka_unit_test(test_each_can_fail),
    };
    return cmocka_run_group_tests_name("kurc96_claims", tests, NULL, NULL);
}
