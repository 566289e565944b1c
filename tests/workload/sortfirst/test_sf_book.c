/* test_sf_book.c — the sort-first book on a database worked out by hand:
 * one posted structure of 3 triangles in chunks of at most 2 (a chunk of
 * 2 mastered by processor 0, one of 1 by processor 1, one instance
 * each).  The initial memory per processor (master bit vectors, chunk
 * data, max-set pointers) and the migration invariant check, which
 * names the first instance a processor needs but does not hold. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "tests/workload/sortfirst/sf_testutil.h"

static const WlSfSizes Z = {64, 40, 36, 8, 4, 8, 16, 96};

/* Max-set: a master keeps a bit vector of ceil(P / 8) bytes for the
 * chunk and one per instance; a holder the chunk record (40 B), its
 * triangles (36 B each) and its instance pointers (8 B each).
 * p0: 2 + 40 + 72 + 8 = 122, p1: 2 + 40 + 36 + 8 = 86.  Min-set: no
 * pointers, one vector: 113 and 77.  With 9 processors the vectors are
 * 2 bytes. */
static void test_memory(void **st)
{
    (void)st;
    SceneDb *src;
    WlSfDb *db = sf_test_tiny_db(&src, 2);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    WlSfBook *b = wl_sf_book_new(db, &r, WL_SF_MAXSET, &Z);
    assert_int_equal(wl_sf_book_memory(b, 0), 122);
    assert_int_equal(wl_sf_book_memory(b, 1), 86);
    assert_int_equal(wl_sf_book_master(b, 0), 0);
    assert_int_equal(wl_sf_book_master(b, 1), 1);
    wl_sf_book_free(b);
    b = wl_sf_book_new(db, &r, WL_SF_MINSET, &Z);
    assert_int_equal(wl_sf_book_memory(b, 0), 113);
    assert_int_equal(wl_sf_book_memory(b, 1), 77);
    assert_int_equal(wl_sf_book_peak_memory(b), 113);
    wl_sf_book_free(b);
    wl_sf_db_free(db);
    scene_db_free(src);
    db = sf_test_tiny_db(&src, 9);
    wl_sf_regions_init(&r, 9, 18, 18);
    b = wl_sf_book_new(db, &r, WL_SF_MAXSET, &Z);
    assert_int_equal(wl_sf_book_memory(b, 0), 2 * 2 + 40 + 72 + 8);
    assert_int_equal(wl_sf_book_memory(b, 1), 2 * 2 + 40 + 36 + 8);
    assert_int_equal(wl_sf_book_memory(b, 2), 0);
    assert_int_equal(wl_sf_book_peak_memory(b), 2 * 2 + 40 + 72 + 8);
    wl_sf_book_free(b);
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* need[] from screen rectangles: instance 1 (processor 1's) seen in
 * region 0 only is a miss of processor 0; once nothing is on screen,
 * or each instance only in its master's region, the check holds. */
static void test_check(void **st)
{
    (void)st;
    SceneDb *src;
    WlSfDb *db = sf_test_tiny_db(&src, 2);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16); /* region 0: x < 8, region 1: x >= 8 */
    for (int bk = 0; bk < 2; bk++) {
        WlSfBook *b = wl_sf_book_new(db, &r, (WlSfBookkeeping)bk, &Z);
        guint inst = 99, proc = 99;
        WlSfScreen scr[2] = {{.on = FALSE}, {.on = FALSE}};
        wl_sf_book_need_from(b, scr);
        assert_true(wl_sf_book_check(b, &inst, &proc));
        scr[0] = (WlSfScreen){.on = TRUE, .x0 = 2, .y0 = 2, .x1 = 4, .y1 = 4};
        scr[1] = (WlSfScreen){.on = TRUE, .x0 = 12, .y0 = 2, .x1 = 14,
                              .y1 = 4};
        wl_sf_book_need_from(b, scr);
        assert_true(wl_sf_book_check(b, &inst, &proc));
        assert_int_equal(b->need[0], 1);
        assert_int_equal(b->need[1], 2);
        scr[1] = (WlSfScreen){.on = TRUE, .x0 = 2, .y0 = 2, .x1 = 4, .y1 = 4};
        wl_sf_book_need_from(b, scr);
        assert_false(wl_sf_book_check(b, &inst, &proc));
        assert_int_equal(inst, 1);
        assert_int_equal(proc, 0);
        /* used[] of a chunk: the union of its instances' needs, and the
         * previous frame's kept */
        assert_int_equal(b->used[1], 1);
        assert_int_equal(b->used_prev[1], 2);
        wl_sf_book_free(b);
    }
    wl_sf_db_free(db);
    scene_db_free(src);
}

/* A batch starts empty (no item, no polygon, no byte, src = dst = 0);
 * clearing leaves it zeroed, so a second clear does nothing. */
static void test_batch(void **st)
{
    (void)st;
    WlSfBatch bt;
    memset(&bt, 0xa5, sizeof bt);
    wl_sf_batch_init(&bt);
    assert_int_equal(bt.src, 0);
    assert_int_equal(bt.dst, 0);
    assert_int_equal(bt.polys, 0);
    assert_int_equal(bt.bytes, 0);
    assert_int_equal(bt.chunks->len + bt.insts->len + bt.masters->len, 0);
    guint c = 3;
    g_array_append_val(bt.chunks, c);
    bt.bytes = 64;
    wl_sf_batch_clear(&bt);
    assert_null(bt.chunks);
    assert_null(bt.insts);
    assert_null(bt.masters);
    assert_int_equal(bt.bytes, 0);
    wl_sf_batch_clear(&bt);
    assert_null(bt.chunks);
}

/* A database without a primitive: no chunk, no instance.  The book
 * works on it all the same: nothing to sort, send, hold or miss. */
static void test_empty(void **st)
{
    (void)st;
    SceneDb *src = scene_db_new();
    scene_db_post(src, scene_db_add_struct(src, "none"));
    WlSfDb *db = wl_sf_db_new(src, 2, 4, WL_SF_CHUNK_SORTED, NULL);
    assert_non_null(db);
    assert_int_equal(wl_sf_n_chunks(db), 0);
    assert_int_equal(wl_sf_n_insts(db), 0);
    WlSfRegions r;
    wl_sf_regions_init(&r, 2, 16, 16);
    for (int bk = 0; bk <= 1; bk++) {
        WlSfBook *b = wl_sf_book_new(db, &r, (WlSfBookkeeping)bk, &Z);
        wl_sf_book_need(b, mat4_identity());
        WlSfBatch out[2];
        wl_sf_batch_init(&out[0]);
        wl_sf_batch_init(&out[1]);
        WlSfBookWork w = {0};
        wl_sf_book_sort(b, 0, out, &w);
        assert_int_equal(w.sent_bytes, 64); /* the end-of-sort marker */
        GArray *render = g_array_new(FALSE, FALSE, sizeof(guint));
        wl_sf_book_render_set(b, 1, NULL, render, &w);
        assert_int_equal(render->len, 0);
        assert_int_equal(w.held_chunks, 0);
        WlSfRemapWork rw[2] = {{0}};
        wl_sf_book_remap(b, NULL, 0, rw);
        assert_int_equal(rw[0].ptr_collected + rw[1].ptr_created, 0);
        assert_int_equal(wl_sf_book_memory(b, 0), 0);
        guint inst = 7, proc = 7;
        assert_true(wl_sf_book_check(b, &inst, &proc));
        g_array_unref(render);
        wl_sf_batch_clear(&out[0]);
        wl_sf_batch_clear(&out[1]);
        wl_sf_book_free(b);
    }
    wl_sf_db_free(db);
    scene_db_free(src);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_batch),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_memory),
        cmocka_unit_test(test_check),
    };
    return cmocka_run_group_tests_name("sf_book", tests, NULL, NULL);
}
