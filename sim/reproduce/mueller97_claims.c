/* mueller97_claims.c — the claims of seed 000 §4.2 as computed rows
 * (mueller97.h).  Each claim is a row of table "claims" whose columns
 * are the figures behind it and `holds` (1 yes, 0 no, NaN when the runs
 * cannot decide it); the claim's words are the row's note.  The tests of
 * each claim, and where we chose a threshold:
 *
 *   C1 (Chart 2)  communication (bytes a frame, max-set, sorted) depends
 *      more on P than on the chunk size: the mean over chunk sizes of
 *      max/min over P exceeds the mean over P of max/min over chunk
 *      sizes; and the chunk size matters more as P grows, read on the
 *      chart's scale: the spread max - min in bytes over chunk sizes is
 *      larger at the largest P than at the smallest (the relative spread
 *      max/min at both is printed too; it is not what is tested).
 *   C2 (Chart 3)  chunk overlap grows with the ratio of chunk box size to
 *      region size: Spearman rank correlation over the (P, chunk size)
 *      cases >= 0.9 ("fairly direct", "steadily"; our threshold).  Beside
 *      it, per processor count: in how many P the overlap rises with the
 *      ratio (procs_rising), and the least and greatest mean (overlap -
 *      1) / ratio of one P; when the claim does not hold its note says
 *      whether it is these that part (the ranks across P) or the ratio.
 *   C3 (Charts 4-5)  max-set does fewer transformations than min-set: in
 *      every case with chunks larger than 1 (the charts omit size 1).
 *   C4  min-set transforms about three times (the instance count) as
 *      many slave chunk boxes as max-set: the mean ratio over those cases
 *      within 15 % of the instance count (our tolerance for "about").
 *   C5 (Chart 1)  "the sorted method was chosen": sorted chunking gives
 *      smaller boxes and less overlap than unsorted at every chunk size
 *      above 1, and than partially sorted where that was run.  Chart 1's
 *      values are not in the text, so whether partially sorted lies
 *      between the two is not a claim of the paper; cases_partial_between
 *      reports it as an observation (an earlier reading required it).
 *   C6 (§5)  "the additional overhead of the max-set method does not
 *      appear to be very significant": max-set / min-set in bytes sent a
 *      frame and in the largest processor store, each a mean over the
 *      cases with chunks larger than 1, at most 1.25 (our threshold for
 *      "not very significant"); the frame time ratio is printed beside.
 *   C7 (§3.3.2.2)  "the push method is the better choice": against the
 *      push case of its P and chunk size, every min-set pull case sends
 *      at least 1.25 times the messages ("a significant number"; our
 *      threshold), more bytes, and transforms more boxes (pull tests
 *      every chunk's box).  The unbuffered figure is 2 x the chunks
 *      requested (a request and a reply per chunk) over push's messages.
 *      Printed beside, not tested: the frame time ratio, and the time
 *      the masters spend in request interrupts a frame (request_interrupt
 *      per request served; the paper: "the request messages also
 *      require processors to interrupt their normal work").
 * O(n^2) in the points (n is tens).
 */
#include "sim/reproduce/mueller97.h"
#include <math.h>
#include <string.h>

/* Our thresholds for the paper's words: "not very significant" is at
 * most 25 % more, "a significant number" at least 25 % more. */
#define RP_MU_SMALL 1.25
#define RP_MU_SIGNIFICANT 1.25

typedef struct {
    const RpMuellerPoint *pts;
    guint n;
} Pts;

static const RpMuellerPoint *find_ch(Pts a, guint procs, guint g,
                                     gboolean minset, RpMuChunking ch)
{
    for (guint i = 0; i < a.n; i++)
        if (a.pts[i].procs == procs && a.pts[i].granularity == g &&
            a.pts[i].minset == minset && a.pts[i].chunking == ch)
            return &a.pts[i];
    return NULL;
}

/* The case (sorted: TRUE for sorted chunking, else unsorted). */
static const RpMuellerPoint *find(Pts a, guint procs, guint g, gboolean minset,
                                  gboolean sorted)
{
    return find_ch(a, procs, g, minset,
                   sorted ? RP_MU_SORTED : RP_MU_UNSORTED);
}

static gboolean is_sorted(const RpMuellerPoint *p)
{
    return p->chunking == RP_MU_SORTED;
}

/* Distinct values of procs (by_procs) or granularity, ascending. */
static guint distinct(Pts a, gboolean by_procs, guint *out, guint max)
{
    guint n = 0;
    for (guint i = 0; i < a.n; i++) {
        guint v = by_procs ? a.pts[i].procs : a.pts[i].granularity, k = 0;
        while (k < n && out[k] != v)
            k++;
        if (k == n && n < max)
            out[n++] = v;
    }
    for (guint i = 1; i < n; i++)
        for (guint j = i; j > 0 && out[j - 1] > out[j]; j--) {
            guint t = out[j];
            out[j] = out[j - 1];
            out[j - 1] = t;
        }
    return n;
}

/* The bookkeeping whose sorted cases C1 and C2 read: max-set when run
 * (overlap is the same for both; the paper's communication chart). */
static gboolean use_minset(Pts a)
{
    for (guint i = 0; i < a.n; i++)
        if (is_sorted(&a.pts[i]) && !a.pts[i].minset)
            return FALSE;
    return TRUE;
}

/* A figure of claim `id`; the claim's words go on its `holds` row. */
static void row(GPtrArray *rows, const char *id, const char *col, double v,
                const char *claim)
{
    gboolean holds = strcmp(col, "holds") == 0;
    g_ptr_array_add(rows,
                    rp_row_new("claims", id, col, v, holds ? claim : NULL));
}

/* ---- C1 ------------------------------------------------------------------ */

/* max/min (relative) or max - min of the bytes along one line of the
 * (P, g) grid; NaN if none. */
static double spread_of(Pts a, gboolean minset, guint fixed,
                        gboolean fix_procs, const guint *vals, guint nv,
                        gboolean relative)
{
    double lo = INFINITY, hi = -INFINITY;
    for (guint k = 0; k < nv; k++) {
        const RpMuellerPoint *p =
            fix_procs ? find(a, fixed, vals[k], minset, TRUE)
                      : find(a, vals[k], fixed, minset, TRUE);
        if (p && p->bytes > 0) {
            lo = MIN(lo, p->bytes);
            hi = MAX(hi, p->bytes);
        }
    }
    if (!(hi >= lo))
        return NAN;
    return relative ? hi / lo : hi - lo;
}

static double spread(Pts a, gboolean minset, guint fixed, gboolean fix_procs,
                     const guint *vals, guint nv)
{
    return spread_of(a, minset, fixed, fix_procs, vals, nv, TRUE);
}

static void claim_comm(Pts a, GPtrArray *rows)
{
    const char *id = "C1_comm_procs_over_chunk";
    const char *text = "Chart 2: communication depends more on the number of "
                       "processors than on chunk size, and chunk size "
                       "matters more as P grows";
    guint ps[32], gs[32];
    guint np = distinct(a, TRUE, ps, 32), ng = distinct(a, FALSE, gs, 32);
    gboolean minset = use_minset(a);
    double by_p = 0, by_g = 0;
    for (guint g = 0; g < ng; g++)
        by_p += spread(a, minset, gs[g], FALSE, ps, np) / ng;
    for (guint p = 0; p < np; p++)
        by_g += spread(a, minset, ps[p], TRUE, gs, ng) / np;
    double g_small = spread(a, minset, ps[0], TRUE, gs, ng);
    double g_large = spread(a, minset, ps[np - 1], TRUE, gs, ng);
    double b_small = spread_of(a, minset, ps[0], TRUE, gs, ng, FALSE);
    double b_large = spread_of(a, minset, ps[np - 1], TRUE, gs, ng, FALSE);
    double holds = isnan(by_p + by_g + b_small + b_large) || np < 2 || ng < 2
                       ? NAN
                       : (by_p > by_g && b_large > b_small);
    row(rows, id, "procs_effect", by_p, text);
    row(rows, id, "chunk_effect", by_g, text);
    row(rows, id, "chunk_bytes_spread_smallest_p", b_small, text);
    row(rows, id, "chunk_bytes_spread_largest_p", b_large, text);
    row(rows, id, "chunk_effect_smallest_p", g_small, text);
    row(rows, id, "chunk_effect_largest_p", g_large, text);
    row(rows, id, "holds", holds, text);
}

/* ---- C2 ------------------------------------------------------------------ */

/* Ranks (1-based, ties averaged) of v[0 .. n-1] into r. */
static void ranks(const double *v, guint n, double *r)
{
    for (guint i = 0; i < n; i++) {
        guint below = 0, same = 0;
        for (guint j = 0; j < n; j++) {
            below += v[j] < v[i];
            same += v[j] == v[i];
        }
        r[i] = below + (same + 1) / 2.0;
    }
}

/* Spearman's rho: Pearson's correlation of the ranks. */
double rp_mueller97_spearman(const double *x, const double *y, guint n)
{
    double *rx = g_new(double, n), *ry = g_new(double, n);
    ranks(x, n, rx);
    ranks(y, n, ry);
    double mx = 0, my = 0, sxy = 0, sxx = 0, syy = 0;
    for (guint i = 0; i < n; i++) {
        mx += rx[i] / n;
        my += ry[i] / n;
    }
    for (guint i = 0; i < n; i++) {
        sxy += (rx[i] - mx) * (ry[i] - my);
        sxx += (rx[i] - mx) * (rx[i] - mx);
        syy += (ry[i] - my) * (ry[i] - my);
    }
    g_free(rx);
    g_free(ry);
    return sxx > 0 && syy > 0 ? sxy / sqrt(sxx * syy) : NAN;
}

/* The sorted cases of one bookkeeping at P (all P when procs is 0):
 * their ratios and overlaps into x, y; returns how many. */
static guint overlap_cases(Pts a, gboolean minset, guint procs, double *x,
                           double *y)
{
    guint n = 0;
    for (guint i = 0; i < a.n; i++)
        if (is_sorted(&a.pts[i]) && a.pts[i].minset == minset &&
            (!procs || a.pts[i].procs == procs)) {
            x[n] = a.pts[i].ratio;
            y[n++] = a.pts[i].overlap;
        }
    return n;
}

/* Within each P that has cases: how many P's overlap rises with the
 * ratio (*rising; strictly, in ratio order), and the least and greatest
 * mean over that P's cases of (overlap - 1) / ratio, the overlap a unit
 * of ratio adds (at P lo_hi_p[0] and lo_hi_p[1]).  Returns how many P. */
static guint per_procs(Pts a, gboolean minset, double *x, double *y,
                       guint *rising, double lo_hi[2], guint lo_hi_p[2])
{
    guint ps[32], np = distinct(a, TRUE, ps, 32), with = 0;
    *rising = 0;
    lo_hi[0] = INFINITY;
    lo_hi[1] = -INFINITY;
    lo_hi_p[0] = lo_hi_p[1] = 0;
    for (guint k = 0; k < np; k++) {
        guint n = overlap_cases(a, minset, ps[k], x, y), up = 0;
        double slope = 0;
        for (guint i = 0; i < n; i++) {
            double next = INFINITY, at = NAN; /* the next larger ratio */
            for (guint j = 0; j < n; j++)
                if (x[j] > x[i] && x[j] < next) {
                    next = x[j];
                    at = y[j];
                }
            up += isinf(next) || at > y[i];
            slope += (y[i] - 1) / x[i] / n;
        }
        if (n == 0)
            continue;
        with++;
        *rising += up == n;
        if (slope < lo_hi[0]) {
            lo_hi[0] = slope;
            lo_hi_p[0] = ps[k];
        }
        if (slope > lo_hi[1]) {
            lo_hi[1] = slope;
            lo_hi_p[1] = ps[k];
        }
    }
    return with;
}

/* The claim is read across every case, as Chart 3 plots them: a
 * "fairly direct relationship" ranks the overlaps as the ratios.  When
 * it does not hold, the note says why from the per-P figures. */
static void claim_overlap(Pts a, GPtrArray *rows)
{
    const char *id = "C2_overlap_follows_box_ratio";
    const char *text = "Chart 3: the chunk overlap factor grows with the "
                       "ratio of chunk box size to region size";
    double *x = g_new(double, a.n + 1), *y = g_new(double, a.n + 1);
    gboolean minset = use_minset(a);
    guint n = overlap_cases(a, minset, 0, x, y);
    double rho = n >= 3 ? rp_mueller97_spearman(x, y, n) : NAN;
    double rlo = INFINITY, rhi = -INFINITY, sl[2];
    for (guint i = 0; i < n; i++) {
        rlo = MIN(rlo, x[i]);
        rhi = MAX(rhi, x[i]);
    }
    guint rising, sp[2];
    guint np = per_procs(a, minset, x, y, &rising, sl, sp);
    double holds = isnan(rho) ? NAN : rho >= 0.9;
    char *why =
        holds == 0 && rising == np
            ? g_strdup_printf(
                  "%s; does not hold, because the overlap at one ratio "
                  "depends on the processor count: within each P it rises "
                  "with the ratio (%u of %u), but a unit of ratio adds "
                  "%.2f overlap at P = %u and %.2f at P = %u, so across P "
                  "the ranks differ (Spearman %.2f < 0.9)",
                  text, rising, np, sl[0], sp[0], sl[1], sp[1], rho)
        : holds == 0
            ? g_strdup_printf("%s; does not hold: Spearman %.2f < 0.9, and "
                              "within P the overlap rises with the ratio "
                              "in %u of %u",
                              text, rho, rising, np)
            : g_strdup(text);
    row(rows, id, "cases", n, text);
    row(rows, id, "spearman", rho, text);
    row(rows, id, "ratio_min", n ? rlo : NAN, text);
    row(rows, id, "ratio_max", n ? rhi : NAN, text);
    row(rows, id, "procs_rising", rising, text);
    row(rows, id, "overlap_per_ratio_min", np ? sl[0] : NAN, text);
    row(rows, id, "overlap_per_ratio_max", np ? sl[1] : NAN, text);
    row(rows, id, "holds", holds, why);
    g_free(why);
    g_free(x);
    g_free(y);
}

/* ---- C3, C4 -------------------------------------------------------------- */

/* The max-set case paired with min-set case mn (sorted, chunks above 1:
 * the charts omit size 1), or NULL. */
static const RpMuellerPoint *maxset_of(Pts a, const RpMuellerPoint *mn)
{
    if (!mn->minset || !is_sorted(mn) || mn->granularity < 2)
        return NULL;
    return find(a, mn->procs, mn->granularity, FALSE, TRUE);
}

static void claim_bookkeeping(Pts a, GPtrArray *rows)
{
    const char *id3 = "C3_maxset_fewer_transforms";
    const char *t3 = "Charts 4-5: max-set performs fewer transformations "
                     "than min-set";
    const char *id4 = "C4_minset_slave_boxes_x_instances";
    const char *t4 = "min-set transforms about three times as many slave "
                     "chunk boxes as max-set with three instances";
    guint cases = 0, fewer = 0, inst = 0;
    double tr = 0, sl = 0, slo = INFINITY, shi = -INFINITY;
    for (guint i = 0; i < a.n; i++) {
        const RpMuellerPoint *mn = &a.pts[i], *mx = maxset_of(a, mn);
        if (!mx || mx->slave <= 0 || mn->transforms <= 0)
            continue;
        cases++;
        fewer += mx->transforms < mn->transforms;
        tr += mx->transforms / mn->transforms;
        double r = mn->slave / mx->slave;
        sl += r;
        slo = MIN(slo, r);
        shi = MAX(shi, r);
        inst = mn->instances;
    }
    double c = cases ? cases : NAN;
    row(rows, id3, "cases", cases, t3);
    row(rows, id3, "cases_maxset_fewer", fewer, t3);
    row(rows, id3, "mean_maxset_over_minset", tr / c, t3);
    row(rows, id3, "holds", cases ? fewer == cases : NAN, t3);
    row(rows, id4, "instances", inst, t4);
    row(rows, id4, "mean_slave_ratio", sl / c, t4);
    row(rows, id4, "min_slave_ratio", cases ? slo : NAN, t4);
    row(rows, id4, "max_slave_ratio", cases ? shi : NAN, t4);
    row(rows, id4, "holds",
        cases && inst ? fabs(sl / c / inst - 1) <= 0.15 : NAN, t4);
}

/* ---- C5 ------------------------------------------------------------------ */

/* x of the partially sorted case lies between sorted and unsorted. */
static gboolean between(double sorted, double partial, double unsorted)
{
    return sorted <= partial && partial <= unsorted;
}

/* Sorted beats the other strategy in both box ratio and overlap. */
static gboolean beats(const RpMuellerPoint *s, const RpMuellerPoint *o)
{
    return s->ratio < o->ratio && s->overlap < o->overlap;
}

static void claim_chunking(Pts a, GPtrArray *rows)
{
    const char *id = "C5_sorted_smaller_boxes_less_overlap";
    const char *text = "Chart 1: the sorted method was chosen: smaller boxes "
                       "and less overlap than unsorted and partially sorted";
    guint cases = 0, both = 0, np = 0, mid = 0, pbeat = 0;
    double box = 0, ovl = 0, pbox = 0, povl = 0;
    for (guint i = 0; i < a.n; i++) {
        const RpMuellerPoint *u = &a.pts[i];
        if (u->chunking != RP_MU_UNSORTED || u->granularity < 2)
            continue;
        const RpMuellerPoint *s =
            find(a, u->procs, u->granularity, u->minset, TRUE);
        const RpMuellerPoint *p = find_ch(a, u->procs, u->granularity,
                                          u->minset, RP_MU_PARTIAL);
        if (!s || u->ratio <= 0 || u->overlap <= 0)
            continue;
        cases++;
        both += beats(s, u);
        box += s->ratio / u->ratio;
        ovl += s->overlap / u->overlap;
        if (!p)
            continue;
        np++;
        pbeat += beats(s, p);
        mid += between(s->ratio, p->ratio, u->ratio) &&
               between(s->overlap, p->overlap, u->overlap);
        pbox += p->ratio / u->ratio;
        povl += p->overlap / u->overlap;
    }
    double c = cases ? cases : NAN, cp = np ? np : NAN;
    row(rows, id, "cases", cases, text);
    row(rows, id, "cases_sorted_smaller", both, text);
    row(rows, id, "mean_box_sorted_over_unsorted", box / c, text);
    row(rows, id, "mean_overlap_sorted_over_unsorted", ovl / c, text);
    row(rows, id, "cases_partial", np, text);
    row(rows, id, "cases_sorted_beats_partial", pbeat, text);
    row(rows, id, "cases_partial_between", mid, text);
    row(rows, id, "mean_box_partial_over_unsorted", pbox / cp, text);
    row(rows, id, "mean_overlap_partial_over_unsorted", povl / cp, text);
    row(rows, id, "holds", cases ? both == cases && pbeat == np : NAN, text);
}

/* ---- C6 ------------------------------------------------------------------ */

static void claim_overhead(Pts a, GPtrArray *rows)
{
    const char *id = "C6_maxset_overhead_small";
    const char *text = "§5: the additional overhead of the max-set method "
                       "does not appear to be very significant";
    guint cases = 0;
    double bytes = 0, mem = 0, ms = 0, worst = 0;
    for (guint i = 0; i < a.n; i++) {
        const RpMuellerPoint *mn = &a.pts[i], *mx = maxset_of(a, mn);
        if (!mx || mn->bytes <= 0 || mn->memory <= 0 || mn->frame_ms <= 0)
            continue;
        cases++;
        bytes += mx->bytes / mn->bytes;
        mem += mx->memory / mn->memory;
        ms += mx->frame_ms / mn->frame_ms;
        worst = MAX(worst, MAX(mx->bytes / mn->bytes, mx->memory / mn->memory));
    }
    double c = cases ? cases : NAN;
    double holds = cases ? bytes / c <= RP_MU_SMALL && mem / c <= RP_MU_SMALL
                         : NAN;
    char *why = holds == 0
        ? g_strdup_printf("%s; does not hold, because max-set / min-set is "
                          "%.2f in bytes sent and %.2f in the largest "
                          "store, above our %.2f",
                          text, bytes / c, mem / c, RP_MU_SMALL)
        : g_strdup(text);
    row(rows, id, "cases", cases, text);
    row(rows, id, "mean_bytes_maxset_over_minset", bytes / c, text);
    row(rows, id, "mean_memory_maxset_over_minset", mem / c, text);
    row(rows, id, "max_ratio", cases ? worst : NAN, text);
    row(rows, id, "mean_frame_maxset_over_minset", ms / c, text);
    row(rows, id, "holds", holds, why);
    g_free(why);
}

/* ---- C7 ------------------------------------------------------------------ */

void rp_mueller97_claims_pull(const RpMuellerPoint *pts, guint n,
                              const RpMuellerPoint *pull, guint n_pull,
                              GPtrArray *rows)
{
    const char *id = "C7_push_beats_pull";
    const char *text = "§3.3.2.2: the push method is the better choice: "
                       "pull adds a significant number of request messages, "
                       "more bandwidth, and its processors test every "
                       "chunk's box";
    Pts a = {pts, n};
    guint cases = 0, msgs = 0, bytes = 0, work = 0;
    double rm = 0, rb = 0, rt = 0, req = 0, push_msgs = 0, rf = 0, irq = 0;
    for (guint k = 0; k < n_pull; k++) {
        const RpMuellerPoint *pl = &pull[k];
        const RpMuellerPoint *ps =
            find(a, pl->procs, pl->granularity, TRUE, TRUE);
        if (!ps || ps->messages <= 0 || ps->bytes <= 0 || ps->transforms <= 0)
            continue;
        cases++;
        msgs += pl->messages >= RP_MU_SIGNIFICANT * ps->messages;
        bytes += pl->bytes > ps->bytes;
        work += pl->transforms > ps->transforms;
        rm += pl->messages / ps->messages;
        rb += pl->bytes / ps->bytes;
        rt += pl->transforms / ps->transforms;
        rf += ps->frame_ms > 0 ? pl->frame_ms / ps->frame_ms : NAN;
        irq += pl->interrupt_ms;
        req += 2 * pl->requests / ps->messages;
        push_msgs = ps->messages;
    }
    double c = cases ? cases : NAN;
    double holds = cases ? msgs == cases && bytes == cases && work == cases
                         : NAN;
    char *why = NULL;
    if (holds == 0) {
        GString *g = g_string_new(text);
        g_string_append(g, "; does not hold, because");
        if (msgs < cases)
            g_string_append_printf(
                g, " pull sends %.2f times push's %.0f messages a frame "
                   "(below our %.2f: requests go one message per master a "
                   "frame; one per chunk would be %.1f times);",
                rm / c, push_msgs, RP_MU_SIGNIFICANT, req / c);
        if (bytes < cases)
            g_string_append_printf(g, " pull sends %.2f times the bytes;",
                                   rb / c);
        if (work < cases)
            g_string_append_printf(g, " pull transforms %.2f times;", rt / c);
        g_string_truncate(g, g->len - 1);
        g_string_append_printf(g, " (not tested: pull's frame is %.2f times "
                                  "push's, with %.3f ms of request "
                                  "interrupts a frame)",
                               rf / c, irq / c);
        why = g_string_free(g, FALSE);
    }
    row(rows, id, "cases", cases, text);
    row(rows, id, "mean_messages_pull_over_push", rm / c, text);
    row(rows, id, "mean_request_messages_unbuffered_over_push", req / c, text);
    row(rows, id, "mean_bytes_pull_over_push", rb / c, text);
    row(rows, id, "mean_transforms_pull_over_push", rt / c, text);
    row(rows, id, "mean_frame_pull_over_push", rf / c, text);
    row(rows, id, "mean_interrupt_ms", irq / c, text);
    row(rows, id, "cases_significantly_more_messages", msgs, text);
    row(rows, id, "cases_more_bytes", bytes, text);
    row(rows, id, "cases_more_transforms", work, text);
    row(rows, id, "holds", holds, why ? why : text);
    g_free(why);
}

void rp_mueller97_claims(const RpMuellerPoint *pts, guint n, GPtrArray *rows)
{
    Pts a = {pts, n};
    if (n == 0)
        return;
    claim_comm(a, rows);
    claim_overlap(a, rows);
    claim_bookkeeping(a, rows);
    claim_chunking(a, rows);
    claim_overhead(a, rows);
}
