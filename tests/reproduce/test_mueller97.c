/* test_mueller97.c — `pgsim reproduce mueller97`: each claim row of §4.2
 * comes out "yes" on points where the claim holds and "no" on points
 * made to break it (so no claim row is a constant); Spearman's rho on
 * known data; a reduced run (small vehicle, two processor counts, two
 * chunk sizes) fills Charts 1-5 and every claim row; a bad setup is a
 * located error. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <glib/gstdio.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "sim/reproduce/mueller97.h"

/* ---- synthetic points ------------------------------------------------- */

enum { NP = 2, NG = 2 };
static const guint procs[NP] = {4, 20}, grans[NG] = {5, 26};

/* A grid where every claim holds: sorted x {minset, maxset} x P x g, and
 * unsorted max-set at P = 4. */
static guint make_points(RpMuellerPoint *pts)
{
    static const double bytes[NP][NG] = {{100, 80}, {600, 400}};
    guint n = 0;
    for (guint p = 0; p < NP; p++)
        for (guint g = 0; g < NG; g++)
            for (int minset = 0; minset < 2; minset++) {
                double ratio = procs[p] * grans[g] / 100.0;
                pts[n++] = (RpMuellerPoint){
                    .procs = procs[p], .granularity = grans[g],
                    .minset = minset, .chunking = RP_MU_SORTED,
                    .instances = 3,
                    .bytes = bytes[p][g], .ratio = ratio,
                    .overlap = 1 + ratio, .slave = minset ? 300 : 100,
                    .transforms = minset ? 1000 : 800,
                    .messages = procs[p] * (procs[p] - 1),
                    .memory = minset ? 1000 : 1100, .frame_ms = 1};
            }
    for (guint g = 0; g < NG; g++) {
        RpMuellerPoint u = pts[2 * g], h = pts[2 * g]; /* P = 4, max-set */
        u.chunking = RP_MU_UNSORTED;
        u.ratio *= 1.5;
        u.overlap *= 1.2;
        pts[n++] = u;
        h.chunking = RP_MU_PARTIAL;
        h.ratio *= 1.25;
        h.overlap *= 1.1;
        pts[n++] = h;
    }
    return n;
}

static double holds(const RpMuellerPoint *pts, guint n, const char *claim)
{
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    rp_mueller97_claims(pts, n, rows);
    double v = -1;
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        if (g_str_has_prefix(r->row, claim) && !strcmp(r->column, "holds"))
            v = r->sim;
    }
    g_ptr_array_unref(rows);
    return v;
}

/* The note of claim `claim`'s holds row (a copy; "" when none). */
static char *holds_note(const RpMuellerPoint *pts, guint n, const char *claim)
{
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    rp_mueller97_claims(pts, n, rows);
    char *note = g_strdup("");
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        if (g_str_has_prefix(r->row, claim) && !strcmp(r->column, "holds") &&
            r->note) {
            g_free(note);
            note = g_strdup(r->note);
        }
    }
    g_ptr_array_unref(rows);
    return note;
}

static RpMuellerPoint *at(RpMuellerPoint *pts, guint n, guint p, guint g,
                          gboolean minset, gboolean sorted)
{
    RpMuChunking ch = sorted ? RP_MU_SORTED : RP_MU_UNSORTED;
    for (guint i = 0; i < n; i++)
        if (pts[i].procs == p && pts[i].granularity == g &&
            pts[i].minset == minset && pts[i].chunking == ch)
            return &pts[i];
    fail();
    return NULL;
}

static const char *const claims[] = {"C1", "C2", "C3", "C4",
                                     "C5", "C5", "C6"};
enum { N_BREAKS = 7 };

/* Breaks claim k in pts. */
static void breaks(RpMuellerPoint *pts, guint n, int k)
{
    switch (k) {
    case 0: /* chunk size matters less at P = 20 than at P = 4 */
        at(pts, n, 20, 26, FALSE, TRUE)->bytes = 595;
        break;
    case 1: /* overlap falls as the box ratio grows */
        for (guint i = 0; i < n; i++)
            pts[i].overlap = 2 - pts[i].ratio;
        break;
    case 2: /* one case where max-set transforms more */
        at(pts, n, 20, 5, FALSE, TRUE)->transforms = 1200;
        break;
    case 3: /* min-set slave boxes only 1.5 times max-set's */
        for (guint i = 0; i < n; i++)
            if (pts[i].minset)
                pts[i].slave = 150;
        break;
    case 4: /* unsorted boxes smaller than sorted ones */
        for (guint i = 0; i < n; i++)
            if (pts[i].chunking == RP_MU_UNSORTED)
                pts[i].ratio /= 2;
        break;
    case 5: /* partially sorted overlap below sorted's: sorted not chosen */
        for (guint i = 0; i < n; i++)
            if (pts[i].chunking == RP_MU_PARTIAL)
                pts[i].overlap /= 1.2;
        break;
    case 6: /* max-set stores 1.3 times min-set's: a significant overhead */
        for (guint i = 0; i < n; i++)
            if (!pts[i].minset)
                pts[i].memory = 1300;
        break;
    }
}

static void test_claims_can_fail(void **state)
{
    (void)state;
    RpMuellerPoint pts[NP * NG * 2 + 2 * NG];
    for (int k = 0; k < N_BREAKS; k++) {
        guint n = make_points(pts);
        assert_true(holds(pts, n, claims[k]) == 1);
        breaks(pts, n, k);
        if (holds(pts, n, claims[k]) != 0)
            fail_msg("claim %s did not come out no", claims[k]);
        /* the other claims are untouched by this break (C2 excepted:
         * overlaps feed C5 as well) */
        for (int j = 0; j < N_BREAKS; j++)
            if (j != k && j != 5 && !(k == 1 && j == 4) &&
                !(k == 5 && j == 4))
                assert_true(holds(pts, n, claims[j]) == 1);
    }
    /* partially sorted outside [sorted, unsorted] is an observation, not
     * the paper's claim: C5 still holds, cases_partial_between drops */
    guint n = make_points(pts);
    for (guint i = 0; i < n; i++)
        if (pts[i].chunking == RP_MU_PARTIAL)
            pts[i].overlap *= 2;
    assert_true(holds(pts, n, "C5") == 1);
    /* no unsorted nor partially sorted case: C5 cannot be decided */
    n = make_points(pts);
    assert_true(isnan(holds(pts, n - 2 * NG, "C5")));
}

/* C2 read across P: overlap rising with the ratio within each P but
 * by a different amount per unit of ratio at each P ranks the pooled
 * cases apart (rho 0.6 here): no, and the note says it is the processor
 * count; overlap falling with the ratio is a no without that reason. */
static void test_overlap_reason(void **state)
{
    (void)state;
    RpMuellerPoint pts[NP * NG * 2 + 2 * NG];
    guint n = make_points(pts);
    char *note = holds_note(pts, n, "C2");
    assert_null(strstr(note, "does not hold"));
    g_free(note);
    for (guint i = 0; i < n; i++)
        pts[i].overlap = 1 + pts[i].ratio * (pts[i].procs == 4 ? 10 : 1);
    assert_true(holds(pts, n, "C2") == 0);
    note = holds_note(pts, n, "C2");
    assert_non_null(strstr(note, "because the overlap at one ratio depends "
                                 "on the processor count"));
    assert_non_null(strstr(note, "(2 of 2)"));
    assert_non_null(strstr(note, "1.00 overlap at P = 20 and 10.00 at P = 4"));
    g_free(note);
    breaks(pts, n, 1);
    assert_true(holds(pts, n, "C2") == 0);
    note = holds_note(pts, n, "C2");
    assert_null(strstr(note, "because"));
    assert_non_null(strstr(note, "in 0 of 2"));
    g_free(note);
}

/* C7: pull against push at one P and chunk size; each of the paper's
 * three reasons (a significant number of messages, more bytes, more
 * transforms) failing makes it a no, and the note says which. */
static void test_push_pull(void **state)
{
    (void)state;
    RpMuellerPoint pts[NP * NG * 2 + 2 * NG];
    guint n = make_points(pts);
    RpMuellerPoint pull = *at(pts, n, 4, 5, TRUE, TRUE);
    pull.pull = TRUE;
    pull.messages = 24; /* push: 4 x 3 = 12 */
    pull.bytes *= 1.5;
    pull.transforms *= 2;
    pull.requests = 30;
    for (int k = 0; k < 4; k++) {
        RpMuellerPoint pl = pull;
        const char *want = NULL;
        if (k == 1) {
            pl.messages = 13; /* 1.08 times: not significant */
            want = "pull sends 1.08 times push's 12 messages a frame "
                   "(below our 1.25: requests go one message per master a "
                   "frame; one per chunk would be 5.0 times)";
        } else if (k == 2) {
            pl.bytes = 90;
            want = "pull sends 0.90 times the bytes";
        } else if (k == 3) {
            pl.transforms = 900;
            want = "pull transforms 0.90 times";
        }
        GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
        rp_mueller97_claims_pull(pts, n, &pl, 1, rows);
        const RpRow *h = g_ptr_array_index(rows, rows->len - 1);
        assert_string_equal(h->column, "holds");
        assert_true(h->sim == (k == 0 ? 1 : 0));
        if (want && !strstr(h->note, want))
            fail_msg("note '%s' lacks '%s'", h->note, want);
        g_ptr_array_unref(rows);
    }
    /* no push case of its P and chunk size: cannot be decided */
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    pull.granularity = 12;
    rp_mueller97_claims_pull(pts, n, &pull, 1, rows);
    assert_true(isnan(((const RpRow *)g_ptr_array_index(rows, rows->len - 1))
                          ->sim));
    g_ptr_array_unref(rows);
}

static void test_spearman(void **state)
{
    (void)state;
    double x[] = {1, 2, 3, 4, 5}, up[] = {1, 4, 9, 16, 100},
           down[] = {5, 4, 3, 2, 1}, flat[] = {2, 2, 2, 2, 2};
    assert_true(fabs(rp_mueller97_spearman(x, up, 5) - 1) < 1e-12);
    assert_true(fabs(rp_mueller97_spearman(x, down, 5) + 1) < 1e-12);
    assert_true(isnan(rp_mueller97_spearman(x, flat, 5)));
    double swap[] = {2, 1, 3, 4, 5}; /* one swap: rho = 1 - 6*2/120 */
    assert_true(fabs(rp_mueller97_spearman(x, swap, 5) - 0.9) < 1e-12);
}

/* ---- a reduced run --------------------------------------------------- */

static char *write_tmp(const char *name, const char *text)
{
    GError *e = NULL;
    char *path = NULL;
    int fd = g_file_open_tmp(name, &path, &e);
    assert_true(fd >= 0);
    close(fd);
    assert_true(g_file_set_contents(path, text, -1, &e));
    return path;
}

static const char *scene =
    "scene: {generator: vehicle, structures: 40, triangles: 3000,\n"
    "        instances: 3, circle_radius: 6, camera_radius: 15,\n"
    "        camera_height: 5, fov: 30, degrees_per_frame: 12}\n";

static char *setup_text(const char *scene_path, const char *extra)
{
    return g_strdup_printf(
        "cell:\n"
        "  schema_version: 1\n"
        "  machine: {model: cluster-ib}\n"
        "  workload: {type: sortfirst, regions: static, check_image: false,\n"
        "    cull_back: true, resolution: 64,\n"
        "    bytes: {message: 64 B, chunk: 40 B, triangle: 36 B, "
        "instance: 8 B}}\n"
        "  run: {frames: 3}\n"
        "scene: %s\n"
        "granularities: [1, 5]\nprocessors: [2, 4]\n"
        "bookkeeping: [minset, maxset]\n"
        "chart1: {processors: 4, bookkeeping: maxset,\n"
        "         chunking: [sorted, partially_sorted, unsorted]}\n"
        "pull: {processors: 4, granularities: [5]}\n%s",
        scene_path, extra);
}

static gboolean run(const char *setup, GPtrArray *rows, GError **err)
{
    RpContext ctx = {.setup = setup, .fidelity = "analytic", .quiet = TRUE};
    return rp_mueller97.rows(&ctx, rows, err);
}

static guint count(GPtrArray *rows, const char *table, const char *col)
{
    guint n = 0;
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        n += !strcmp(r->table, table) && !strcmp(r->column, col) &&
             isfinite(r->sim);
    }
    return n;
}

static void test_reduced_run(void **state)
{
    (void)state;
    char *sc = write_tmp("mu-scene-XXXXXX.yaml", scene);
    char *text = setup_text(sc, "");
    char *setup = write_tmp("mu-setup-XXXXXX.yaml", text);
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    GError *e = NULL;
    if (!run(setup, rows, &e))
        fail_msg("%s", e->message);
    assert_int_equal(count(rows, "1", "chunk_overlap"), 6);  /* 3 x 2 */
    assert_int_equal(count(rows, "2", "bytes_maxset"), 4);   /* P x g */
    assert_int_equal(count(rows, "3", "chunk_overlap"), 4);
    assert_int_equal(count(rows, "4", "transforms"), 4);
    assert_int_equal(count(rows, "5", "transforms"), 4);
    /* every claim decided (C2..C5 read the chunk size 5 cases) */
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        if (!strcmp(r->table, "claims") && !strcmp(r->column, "holds"))
            assert_true(r->sim == 0 || r->sim == 1);
    }
    assert_int_equal(count(rows, "claims", "holds"), 7);
    g_ptr_array_unref(rows);
    /* an unknown key is a located error */
    g_free(text);
    text = setup_text(sc, "frame: 3\n");
    g_unlink(setup);
    g_free(setup);
    setup = write_tmp("mu-setup-XXXXXX.yaml", text);
    rows = g_ptr_array_new_with_free_func(rp_row_free);
    assert_false(run(setup, rows, &e));
    assert_non_null(strstr(e->message, "frame"));
    assert_int_equal(rows->len, 0);
    g_clear_error(&e);
    g_ptr_array_unref(rows);
    g_unlink(setup);
    g_unlink(sc);
    g_free(setup);
    g_free(sc);
    g_free(text);
}


/* ---- C8: the instancing trade-off (mueller97_inst.c) -------------------- */

static double c8(const RpMuInstPoint *p, guint n, char **note)
{
    GPtrArray *rows = g_ptr_array_new_with_free_func(rp_row_free);
    rp_mueller97_claims_instancing(p, n, rows);
    double v = NAN;
    for (guint i = 0; i < rows->len; i++) {
        const RpRow *r = g_ptr_array_index(rows, i);
        if (!strcmp(r->table, "claims") && !strcmp(r->column, "holds")) {
            v = r->sim;
            if (note)
                *note = g_strdup(r->note);
        }
    }
    g_ptr_array_unref(rows);
    return v;
}

static void test_instancing_claim(void **state)
{
    (void)state;
    /* none: max-set 1 % faster (within 5 %); heavy: 1.8 times */
    RpMuInstPoint p[4] = {
        {.db = "none", .minset = TRUE, .per_chunk = 1, .frame_ms = 1.01},
        {.db = "none", .minset = FALSE, .per_chunk = 1, .frame_ms = 1.0},
        {.db = "heavy", .minset = TRUE, .per_chunk = 12, .frame_ms = 1.8},
        {.db = "heavy", .minset = FALSE, .per_chunk = 12, .frame_ms = 1.0}};
    assert_true(c8(p, 4, NULL) == 1);
    /* without instancing max-set 20 % faster: min-set is not the choice */
    char *note = NULL;
    p[0].frame_ms = 1.2;
    assert_true(c8(p, 4, &note) == 0);
    assert_non_null(strstr(note, "does not hold, because on none"));
    g_free(note);
    p[0].frame_ms = 1.01;
    /* with heavy instancing max-set no faster: it is not the choice */
    p[2].frame_ms = 1.0;
    assert_true(c8(p, 4, &note) == 0);
    assert_non_null(strstr(note, "on heavy (12.00 instances a chunk)"));
    g_free(note);
    /* one kind of database only: undecided */
    assert_true(isnan(c8(p, 2, NULL)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_claims_can_fail),
        cmocka_unit_test(test_overlap_reason),
        cmocka_unit_test(test_push_pull),
        cmocka_unit_test(test_spearman),
        cmocka_unit_test(test_reduced_run),
        cmocka_unit_test(test_instancing_claim),
    };
    return cmocka_run_group_tests_name("mueller97", tests, NULL, NULL);
}
