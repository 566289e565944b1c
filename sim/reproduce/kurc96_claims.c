/* kurc96_claims.c — the statements of seed 003 §5 and §6 about Table 2,
 * Figures 1-2 and the recommended scheme, computed on the simulated data
 * (kurc96.h).  Each claim is a group of rows of table "claims": the
 * counts it is decided on, then `holds` (1 yes, 0 no) with the sentence
 * and either "holds" or "does not hold, because ..." (the failing cases)
 * as the note.  Only simulated values are read.  Tests, and where we
 * chose a threshold:
 *
 *   T2_merge      "PAIR-RS gives much better results than ZBUF-EXC in
 *                 pixel merging phase": every Table 2 row (P=16 and 8),
 *                 ZBUF-EXC merge / PAIR-RS merge >= 2 ("much": ours).
 *   T2_zbuf       "PAIR-RS performs better than ZBUF-EXC also in local
 *                 z-buffer phase": PAIR-RS z-buffer < ZBUF-EXC's, every row.
 *   C_active      §6 "active pixel merging with modified scanline z-buffer
 *                 performs better than full z-buffer merging": the sum of
 *                 the three phases, PAIR-RS < ZBUF-EXC, every row.
 *   F1_aapc       "AAPC scheme results in less volume of communication
 *                 than PAIR scheme": AAPC < PAIR at every Fig. 1 point, RS
 *                 and HBP alike, but P=2, where both are the same single
 *                 exchange.
 *   F1a_fewer     "volume of communication decreases as the number of
 *                 processors increases" (Fig. 1a, 2POT): each scheme's
 *                 volume at P=16 below its volume at P=2, and not rising
 *                 from one P to the next except PAIR-RS at P=4, which the
 *                 paper names ("store-and-forward overheads").
 *   F1b_hbp       "HBP scheme results in less volume of communication than
 *                 RS scheme" (Fig. 1b): HBP < RS at every Fig. 1b point,
 *                 PAIR and AAPC alike.
 *   F2_balance    "HBP achieves much better load balance than RS": HBP's
 *                 imbalance below RS's at every Fig. 2 point, at most half
 *                 of it ("much": ours).
 *   F2b_resolution "Load balance improves with increasing screen
 *                 resolution": imbalance at 640 below 400, every scene, RS
 *                 and HBP alike.
 *   F2a_scaling   "HBP scales better than RS for larger number of
 *                 processors" (Fig. 2a): from each P to 2P, HBP's
 *                 imbalance grows by less than RS's.
 *   recommended   §6 "AAPC with HBP should be utilized": AAPC-HBP has the
 *                 least volume of the four schemes at every Fig. 1 point
 *                 (its balance is F2_balance).
 *
 * O(rows) per figure read; a few hundred figures.
 */
#include "sim/reproduce/kurc96.h"
#include <math.h>
#include <stdarg.h>
#include <string.h>

enum { PAIR_RS, PAIR_HBP, AAPC_RS, AAPC_HBP };

typedef struct {
    GPtrArray *out;
    guint cases, ok;
    GString *why; /* failing cases, "; "-separated */
} KClaim;

static void add(GPtrArray *out, const char *id, const char *col, double v,
                const char *note)
{
    g_ptr_array_add(out, rp_row_new("claims", id, col, v, note));
}

static void check(KClaim *c, gboolean yes, const char *fmt, ...)
    G_GNUC_PRINTF(3, 4);

/* One case of the claim: counted, and described when it fails. */
static void check(KClaim *c, gboolean yes, const char *fmt, ...)
{
    c->cases++;
    if (yes) {
        c->ok++;
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    char *s = g_strdup_vprintf(fmt, ap);
    va_end(ap);
    if (c->why->len < 300)
        g_string_append_printf(c->why, "%s%s", c->why->len ? "; " : "", s);
    g_free(s);
}

/* The claim's closing rows: cases, cases_holding, holds. */
static void close_claim(KClaim *c, const char *id, const char *sentence)
{
    add(c->out, id, "cases", c->cases, NULL);
    add(c->out, id, "cases_holding", c->ok, NULL);
    gboolean holds = c->cases > 0 && c->ok == c->cases;
    char *note = holds ? g_strdup_printf("%s: holds", sentence)
                       : g_strdup_printf("%s: does not hold, because %s",
                                         sentence,
                                         c->cases ? c->why->str
                                                  : "no case was simulated");
    add(c->out, id, "holds", c->cases ? holds : NAN, note);
    g_free(note);
    g_string_truncate(c->why, 0);
    c->cases = c->ok = 0;
}

/* The simulated value of (table, row, column); NaN if absent. */
static double value(const GPtrArray *rows, const char *table, const char *row,
                    const char *column)
{
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = rows->pdata[i];
        if (!strcmp(r->table, table) && !strcmp(r->row, row) &&
            !strcmp(r->column, column))
            return r->sim;
    }
    return NAN;
}

/* Table 2's three phases of PAIR-RS (ph 0) or ZBUF-EXC (ph 1). */
static void phases(const GPtrArray *rows, const char *row, int scheme,
                   double *v)
{
    static const char *const col[2][3] = {
        {"pair_rs_span_ms", "pair_rs_zbuf_ms", "pair_rs_merge_ms"},
        {"zbuf_exc_span_ms", "zbuf_exc_zbuf_ms", "zbuf_exc_merge_ms"}};
    for (int i = 0; i < 3; i++)
        v[i] = value(rows, "2", row, col[scheme][i]);
}

static void table2_claims(KClaim *c, const GPtrArray *rows)
{
    static const char *const ps[] = {"P16", "P8"};
    static const char *const id[] = {"T2_merge", "T2_zbuf", "C_active"};
    static const char *const say[] = {
        "PAIR-RS gives much better results than ZBUF-EXC in pixel merging "
        "(ZBUF-EXC merge at least twice PAIR-RS's, every row)",
        "PAIR-RS performs better than ZBUF-EXC also in local z-buffer phase",
        "active pixel merging (PAIR-RS) performs better than full z-buffer "
        "merging (sum of the three phases)"};
    for (int k = 0; k < 3; k++) {
        for (int p = 0; p < 2; p++)
            for (int s = 0; rp_kurc96_scenes[s]; s++) {
                char row[48];
                double a[3], b[3];
                g_snprintf(row, sizeof row, "%s/%s", ps[p],
                           rp_kurc96_scenes[s]);
                phases(rows, row, 0, a);
                phases(rows, row, 1, b);
                double x = k == 0 ? b[2] / a[2]
                           : k == 1 ? b[1] - a[1]
                                    : (b[0] + b[1] + b[2]) - (a[0] + a[1] + a[2]);
                check(c, k == 0 ? x >= 2 : x > 0, "%s: %s %.3g", row,
                      k == 0 ? "ratio" : "ZBUF-EXC - PAIR-RS ms", x);
            }
        close_claim(c, id[k], say[k]);
    }
}

static void fig1_claims(KClaim *c, const RpKurcFigs *f)
{
    for (guint i = 0; i < f->n_a + f->n_b; i++) {
        const RpKurcPoint *p = i < f->n_a ? &f->a[i] : &f->b[i - f->n_a];
        if (p->procs == 2)
            continue; /* one exchange: the two schemes coincide */
        for (int h = 0; h < 2; h++)
            check(c, p->volume[AAPC_RS + h] < p->volume[PAIR_RS + h],
                  "%s %s: AAPC %.4g >= PAIR %.4g bytes", p->label,
                  h ? "HBP" : "RS", p->volume[AAPC_RS + h],
                  p->volume[PAIR_RS + h]);
    }
    close_claim(c, "F1_aapc", "AAPC results in less volume of communication "
                              "than PAIR (every Fig. 1 point with P > 2; at P = 2 both are one "
                              "exchange)");
    static const char *const sch[] = {"PAIR-RS", "PAIR-HBP", "AAPC-RS",
                                      "AAPC-HBP"};
    for (int s = 0; s < 4; s++) {
        const double *first = &f->a[0].volume[s];
        check(c, f->a[f->n_a - 1].volume[s] < *first,
              "%s: P=16 not below P=2", sch[s]);
        for (guint i = 1; i < f->n_a; i++) {
            gboolean named = s == PAIR_RS && f->a[i].procs == 4;
            check(c, named || f->a[i].volume[s] <= f->a[i - 1].volume[s],
                  "%s: rises from P=%u to P=%u", sch[s], f->a[i - 1].procs,
                  f->a[i].procs);
        }
    }
    close_claim(c, "F1a_fewer", "volume of communication decreases as the "
                                "number of processors increases (Fig. 1a; "
                                "PAIR-RS at P=4 excepted, as the paper does)");
    for (guint i = 0; i < f->n_b; i++)
        for (int pr = 0; pr < 2; pr++) {
            const double *v = &f->b[i].volume[2 * pr];
            check(c, v[1] < v[0], "%s %s: HBP %.4g >= RS %.4g bytes",
                  f->b[i].label, pr ? "AAPC" : "PAIR", v[1], v[0]);
        }
    close_claim(c, "F1b_hbp", "HBP results in less volume of communication "
                              "than RS (Fig. 1b)");
}

static void fig2_claims(KClaim *c, const RpKurcFigs *f)
{
    for (guint i = 0; i < f->n_a + f->n_b; i++) {
        const RpKurcPoint *p = i < f->n_a ? &f->a[i] : &f->b[i - f->n_a];
        check(c, p->imbalance[1] <= 0.5 * p->imbalance[0],
              "%s: HBP %.3g vs RS %.3g", p->label, p->imbalance[1],
              p->imbalance[0]);
    }
    close_claim(c, "F2_balance", "HBP achieves much better load balance than "
                                 "RS (HBP's imbalance at most half of RS's)");
    for (guint i = 0; i + 1 < f->n_b; i += 2)
        for (int h = 0; h < 2; h++)
            check(c, f->b[i + 1].imbalance[h] < f->b[i].imbalance[h],
                  "%s %s: %.3g at 640 >= %.3g at 400", f->b[i].label,
                  h ? "HBP" : "RS", f->b[i + 1].imbalance[h],
                  f->b[i].imbalance[h]);
    close_claim(c, "F2b_resolution", "load balance improves with increasing "
                                     "screen resolution (Fig. 2b)");
    for (guint i = 1; i < f->n_a; i++) {
        double rs = f->a[i].imbalance[0] - f->a[i - 1].imbalance[0];
        double hbp = f->a[i].imbalance[1] - f->a[i - 1].imbalance[1];
        check(c, hbp < rs, "P=%u to %u: HBP grows %.3g, RS %.3g",
              f->a[i - 1].procs, f->a[i].procs, hbp, rs);
    }
    close_claim(c, "F2a_scaling", "HBP scales better than RS for larger "
                                  "numbers of processors (Fig. 2a)");
}

static void recommended(KClaim *c, const RpKurcFigs *f)
{
    for (guint i = 0; i < f->n_a + f->n_b; i++) {
        const RpKurcPoint *p = i < f->n_a ? &f->a[i] : &f->b[i - f->n_a];
        double best = MIN(MIN(p->volume[0], p->volume[1]), p->volume[2]);
        check(c, p->volume[AAPC_HBP] <= best,
              "%s: AAPC-HBP %.4g above %.4g bytes", p->label,
              p->volume[AAPC_HBP], best);
    }
    close_claim(c, "recommended", "AAPC with HBP is the scheme to use: the "
                                  "least volume of the four at every Fig. 1 "
                                  "point (its balance: F2_balance)");
}

void rp_kurc96_claims(const RpKurcFigs *f, GPtrArray *rows)
{
    KClaim c = {rows, 0, 0, g_string_new(NULL)};
    table2_claims(&c, rows);
    fig1_claims(&c, f);
    fig2_claims(&c, f);
    recommended(&c, f);
    g_string_free(c.why, TRUE);
}
