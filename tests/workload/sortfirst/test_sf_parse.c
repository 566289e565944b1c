/* test_sf_parse.c — the sortfirst section parser field by field: every
 * default, each word and the flags it sets, both ends of every count
 * range (one past either end refused at its file:line:column), the pull
 * policy's refusals, and the own-memory estimate (mem_bytes) worked out
 * from its formula. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/sortfirst/sf_workload.h"

#define HEAD "workload: {type: sortfirst"

/* Parses HEAD<extra>}; NULL with *err set on a refusal. */
static WlSfParams *parse(const char *extra, GError **err)
{
    char *text = g_strdup_printf(HEAD "%s}\n", extra);
    CfgNode *root = cfg_load_string(text, "sf.yaml", err);
    assert_non_null(root);
    WlSfParams *p = wl_sortfirst_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    g_free(text);
    return p;
}

static WlSfParams *parse_ok(const char *extra)
{
    GError *e = NULL;
    WlSfParams *p = parse(extra, &e);
    if (!p)
        fail_msg("%s: %s", extra, e->message);
    return p;
}

/* Refused, the message naming column `col` of line 1 and holding `what`. */
static void expect_refused_at(const char *extra, int col, const char *what)
{
    GError *e = NULL;
    assert_null(parse(extra, &e));
    assert_non_null(e);
    char *at = g_strdup_printf("sf.yaml:1:%d:", col);
    if (!strstr(e->message, at) || !strstr(e->message, what))
        fail_msg("%s: '%s' lacks '%s' or '%s'", extra, e->message, at, what);
    g_free(at);
    g_clear_error(&e);
}

/* ", key: v" refused at v's column. */
static void expect_refused(const char *key, guint64 v)
{
    char *extra = g_strdup_printf(", %s: %" G_GUINT64_FORMAT, key, v);
    expect_refused_at(extra, (int)(strlen(HEAD ", ") + strlen(key) + 3), "");
    g_free(extra);
}

static void test_defaults(void **st)
{
    (void)st;
    WlSfParams *p = parse_ok("");
    const WlSfSetup *s = &p->setup;
    assert_int_equal(s->procs, 16);
    assert_int_equal(p->granularity, 12);
    assert_int_equal(s->resolution, 256);
    assert_int_equal(s->grid, 64);
    assert_int_equal(s->bk, WL_SF_MAXSET);
    assert_int_equal(s->mig, WL_SF_PUSH);
    assert_int_equal(s->ms, WL_SF_FIXED);
    assert_int_equal(p->chunking, WL_SF_CHUNK_SORTED);
    assert_int_equal(s->trav, WL_SF_TRAV_PLAIN);
    assert_false(s->adaptive);
    assert_false(s->current);
    assert_true(s->predict);
    assert_false(s->feedback);
    assert_true(s->check_image);
    assert_true(s->cull_back);
    assert_false(s->edits);
    assert_true(p->edits.angle_deg == 10);
    assert_int_equal(p->bv, WL_SF_BV_AABB);
    assert_false(p->bv_fit);
    for (int k = 0; k < WL_SF_ED_N; k++)
        assert_int_equal(p->edits.per_frame[k], 0);
    static const uint64_t z[] = {64, 40, 36, 8, 4, 8, 16, 96};
    assert_memory_equal(&s->sizes, z, sizeof z);
    assert_null(p->frame_log);
    assert_null(p->database);
    assert_null(p->dump_db);
    wl_sortfirst_ops.free_params(p);
}

/* estimate: previous sets neither flag, current only `current`,
 * predicted only `predict`. */
static void test_estimate_words(void **st)
{
    (void)st;
    static const char *const w[] = {"previous", "current", "predicted"};
    for (int i = 0; i < 3; i++) {
        char *extra = g_strdup_printf(", estimate: %s", w[i]);
        WlSfParams *p = parse_ok(extra);
        assert_int_equal(p->setup.current, i == 1);
        assert_int_equal(p->setup.predict, i == 2);
        wl_sortfirst_ops.free_params(p);
        g_free(extra);
    }
}

static void test_words_and_values(void **st)
{
    (void)st;
    WlSfParams *p = parse_ok(
        ", processors: 64, granularity: 1, resolution: 16, regions: adaptive,"
        " bookkeeping: minset, mastership: dynamic, chunking: partially_sorted,"
        " traversal: flags_culled, feedback: true, check_image: false,"
        " cull_back: false, frame_log: f.csv, database: d.yaml,"
        " dump_db: o.yaml, bounding_volume: slabs,"
        " edits: {matrix: 0, execute: 0, unpost: 0, post: 3, delete: 2},"
        " edit_angle_deg: -360,"
        " bytes: {message: 1 B, chunk: 2 B, triangle: 3 B, instance: 4 B,"
        " cell: 5 B, request: 6 B, mastership: 7 B, edit: 8 B}");
    const WlSfSetup *s = &p->setup;
    assert_int_equal(s->procs, 64);
    assert_int_equal(p->granularity, 1);
    assert_int_equal(s->resolution, 16);
    assert_int_equal(s->grid, 16); /* the default, capped at the resolution */
    assert_true(s->adaptive);
    assert_int_equal(s->bk, WL_SF_MINSET);
    assert_int_equal(s->ms, WL_SF_DYNAMIC);
    assert_int_equal(p->chunking, WL_SF_CHUNK_PARTIAL);
    assert_int_equal(s->trav, WL_SF_TRAV_BOTH);
    assert_true(s->feedback);
    assert_false(s->check_image);
    assert_false(s->cull_back);
    assert_string_equal(p->frame_log, "f.csv");
    assert_string_equal(p->database, "d.yaml");
    assert_string_equal(p->dump_db, "o.yaml");
    assert_true(s->edits);
    assert_int_equal(p->edits.per_frame[WL_SF_ED_POST], 3);
    assert_int_equal(p->edits.per_frame[WL_SF_ED_DELETE], 2);
    assert_int_equal(p->bv, WL_SF_BV_SLABS);
    assert_true(p->bv_fit);
    assert_int_equal(p->edits.per_frame[0], 0);
    assert_true(p->edits.angle_deg == -360);
    static const uint64_t z[] = {1, 2, 3, 4, 5, 6, 7, 8};
    assert_memory_equal(&s->sizes, z, sizeof z);
    wl_sortfirst_ops.free_params(p);
    p = parse_ok(", chunking: unsorted, traversal: flags, regions: static,"
                 " grid: 8, edits: {matrix: 1}, edit_angle_deg: 360");
    assert_int_equal(p->chunking, WL_SF_CHUNK_UNSORTED);
    assert_int_equal(p->setup.trav, WL_SF_TRAV_FLAGS);
    assert_false(p->setup.adaptive);
    assert_int_equal(p->setup.grid, 8);
    assert_true(p->setup.edits);
    assert_int_equal(p->edits.per_frame[0], 1);
    assert_true(p->edits.angle_deg == 360);
    wl_sortfirst_ops.free_params(p);
}

/* Each count: lowest and highest accepted, one past either refused; the
 * grid at most the resolution. */
static void test_count_ranges(void **st)
{
    (void)st;
    static const struct {
        const char *key;
        guint64 lo, hi;
    } k[] = {{"processors", 1, WL_SF_MAX_PROCS},
             {"granularity", 1, 1u << 20},
             {"resolution", 16, 4096},
             {"grid", 8, 256}};
    for (guint i = 0; i < G_N_ELEMENTS(k); i++) {
        for (guint j = 0; j < 2; j++) {
            char *extra = g_strdup_printf(", %s: %" G_GUINT64_FORMAT, k[i].key,
                                          j ? k[i].hi : k[i].lo);
            wl_sortfirst_ops.free_params(parse_ok(extra));
            g_free(extra);
        }
        expect_refused(k[i].key, k[i].lo - 1);
        if (i < 3)
            expect_refused(k[i].key, k[i].hi + 1);
    }
    expect_refused("grid", 257); /* above the resolution (256) */
    WlSfParams *p = parse_ok(", resolution: 4096, grid: 1024");
    assert_int_equal(p->setup.grid, 1024);
    wl_sortfirst_ops.free_params(p);
    expect_refused_at(", resolution: 4096, grid: 1025",
                      (int)strlen(HEAD ", resolution: 4096, grid: ") + 1, "");
    expect_refused_at(", edits: {post: 100001}",
                      (int)strlen(HEAD ", edits: {post: ") + 1, "");
    expect_refused_at(", edit_angle_deg: 361",
                      (int)strlen(HEAD ", edit_angle_deg: ") + 1, "");
}

/* bytes and edits must be maps of known keys with valid values: each
 * refused at the offending node. */
static void test_sub_maps(void **st)
{
    (void)st;
    static const char *const bad[][2] = {
        {", bytes: 5", "a map {message"},
        {", bytes: {chunk: [1]}", ""},
        {", edits: 5", "a map {matrix"},
        {", edits: {post: -1}", ""},
        {", edits: {posts: 1}", "posts"},
    };
    static const char *const at[] = {", bytes: ", ", bytes: {chunk: ",
                                     ", edits: ", ", edits: {post: ",
                                     ", edits: {"};
    for (guint k = 0; k < G_N_ELEMENTS(bad); k++)
        expect_refused_at(bad[k][0], (int)(strlen(HEAD) + strlen(at[k])) + 1,
                          bad[k][1]);
}

/* migration: pull is refused, at the word, unless min-set, fixed,
 * static and plain. */
static void test_pull_policy(void **st)
{
    (void)st;
    const int col = (int)strlen(HEAD ", migration: ") + 1;
    WlSfParams *p = parse_ok(", migration: pull, bookkeeping: minset");
    assert_int_equal(p->setup.mig, WL_SF_PULL);
    wl_sortfirst_ops.free_params(p);
    expect_refused_at(", migration: pull", col, "bookkeeping: minset");
    expect_refused_at(", migration: pull, bookkeeping: minset,"
                      " mastership: dynamic",
                      col, "mastership: fixed");
    expect_refused_at(", migration: pull, bookkeeping: minset,"
                      " regions: adaptive",
                      col, "regions: static");
    expect_refused_at(", migration: pull, bookkeeping: minset,"
                      " traversal: culled",
                      col, "traversal: plain");
}

/* mem_bytes: N^2 16 (x 2 with the serial check) + G^2 16 + P^2 64. */
static void test_mem_bytes(void **st)
{
    (void)st;
    WlSfParams *p = parse_ok(", processors: 3, resolution: 20, grid: 10");
    GString *what = g_string_new(NULL);
    assert_true(wl_sortfirst_ops.mem_bytes(p, what) ==
                400 * 16 * 2 + 100 * 16 + 9 * 64);
    assert_string_equal(what->str, "3 processors, 20 x 20 pixels, grid 10");
    wl_sortfirst_ops.free_params(p);
    p = parse_ok(", processors: 2, resolution: 16, check_image: false");
    g_string_truncate(what, 0);
    assert_true(wl_sortfirst_ops.mem_bytes(p, what) ==
                256 * 16 + 256 * 16 + 4 * 64);
    wl_sortfirst_ops.free_params(p);
    g_string_free(what, TRUE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_estimate_words),
        cmocka_unit_test(test_words_and_values),
        cmocka_unit_test(test_count_ranges),
        cmocka_unit_test(test_pull_policy),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_sub_maps),
    };
    return cmocka_run_group_tests_name("sf_parse", tests, NULL, NULL);
}
