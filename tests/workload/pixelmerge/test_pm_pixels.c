/* test_pm_pixels.c — active pixel arrays and reference frames
 * (pm_pixels.h) value by value (issue 21): row offsets after pushes that
 * skip rows, per-row counts added to what is there, the depth order with
 * its tie and empty cases, a new frame's locations, put's verdicts, the
 * count, the first differing index for each field, and a frame back to
 * an array. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_pixels.h"

static WlPmPixel px(guint x, guint y, double z, uint32_t poly)
{
    return (WlPmPixel){(uint16_t)x, (uint16_t)y, z, poly, poly * 0x10101u};
}

/* Pixels on rows 1, 1, 3 of a 4 x 5 screen: rows 0, 2 and 4 empty. */
static WlPmWpa *sample(void)
{
    WlPmWpa *w = wl_pm_wpa_new(4, 5);
    WlPmPixel a = px(2, 1, 0.5, 7), b = px(0, 1, 0.25, 8), c = px(3, 3, 1, 9);
    wl_pm_wpa_push(w, &a);
    wl_pm_wpa_push(w, &b);
    wl_pm_wpa_push(w, &c);
    wl_pm_wpa_finish(w);
    return w;
}

static void test_wpa_rows(void **state)
{
    (void)state;
    WlPmWpa *e = wl_pm_wpa_new(3, 2);
    assert_int_equal(e->width, 3);
    assert_int_equal(e->height, 2);
    assert_int_equal(e->next_row, 1);
    wl_pm_wpa_finish(e);
    assert_int_equal(e->next_row, 3);
    for (guint y = 0; y <= 2; y++)
        assert_int_equal(e->row_start[y], 0);
    wl_pm_wpa_free(e);
    wl_pm_wpa_free(NULL);

    WlPmWpa *w = sample();
    static const uint32_t want[] = {0, 0, 2, 2, 3, 3};
    assert_memory_equal(w->row_start, want, sizeof want);
    assert_int_equal(w->next_row, 6);
    assert_int_equal(wl_pm_wpa_len(w), 3);
    assert_int_equal(wl_pm_wpa_row_len(w, 0), 0);
    assert_int_equal(wl_pm_wpa_row_len(w, 1), 2);
    assert_int_equal(wl_pm_wpa_row_len(w, 3), 1);
    assert_int_equal(wl_pm_wpa_row(w, 1)[1].poly, 8); /* push order kept */
    assert_int_equal(wl_pm_wpa_row(w, 3)[0].x, 3);
    uint64_t counts[5] = {10, 20, 30, 40, 50};
    wl_pm_wpa_add_row_counts(w, counts);
    static const uint64_t added[] = {10, 22, 30, 41, 50};
    assert_memory_equal(counts, added, sizeof added);
    wl_pm_wpa_free(w);
}

/* Nearer wins; equal depths go to the lower id; an empty pixel loses to
 * anything and beats nothing. */
static void test_front(void **state)
{
    (void)state;
    WlPmPixel a = px(0, 0, 0.5, 4), b = px(0, 0, 0.75, 2),
              c = px(0, 0, 0.5, 5), e = px(0, 0, 0.0, WL_PM_EMPTY);
    assert_true(wl_pm_pixel_front(&a, &b));
    assert_false(wl_pm_pixel_front(&b, &a));
    assert_true(wl_pm_pixel_front(&a, &c));
    assert_false(wl_pm_pixel_front(&c, &a));
    assert_false(wl_pm_pixel_front(&a, &a));
    assert_true(wl_pm_pixel_front(&b, &e));
    assert_false(wl_pm_pixel_front(&e, &b));
    assert_false(wl_pm_pixel_front(&e, &e));
}

static void test_frame(void **state)
{
    (void)state;
    WlPmFrame *f = wl_pm_frame_new(3, 2);
    assert_int_equal(f->width, 3);
    assert_int_equal(f->height, 2);
    for (guint i = 0; i < 6; i++) {
        assert_int_equal(f->px[i].x, i % 3);
        assert_int_equal(f->px[i].y, i / 3);
        assert_true(f->px[i].z == 0);
        assert_int_equal(f->px[i].poly, WL_PM_EMPTY);
        assert_int_equal(f->px[i].color, 0);
    }
    assert_int_equal(wl_pm_frame_count(f), 0);
    WlPmPixel a = px(2, 1, 0.5, 4), far = px(2, 1, 0.75, 1),
              tie = px(2, 1, 0.5, 3), d = px(0, 0, 0.9, 6);
    assert_true(wl_pm_frame_put(f, &a));
    assert_false(wl_pm_frame_put(f, &far));
    assert_true(wl_pm_frame_put(f, &tie));
    assert_int_equal(f->px[5].poly, 3);
    assert_true(wl_pm_frame_put(f, &d));
    assert_int_equal(wl_pm_frame_count(f), 2);
    WlPmWpa *w = wl_pm_frame_to_wpa(f);
    assert_int_equal(wl_pm_wpa_len(w), 2);
    assert_int_equal(wl_pm_wpa_row(w, 0)[0].poly, 6);
    assert_int_equal(wl_pm_wpa_row(w, 1)[0].poly, 3);
    assert_int_equal(w->row_start[1], 1);
    WlPmFrame *g = wl_pm_frame_new(3, 2);
    wl_pm_frame_put_wpa(g, w);
    assert_int_equal(wl_pm_frame_diff(f, g), -1);
    wl_pm_wpa_free(w);
    wl_pm_frame_free(g);
    wl_pm_frame_free(f);
    wl_pm_frame_free(NULL);
}

/* The first index where two frames differ, field by field; empty
 * locations are equal whatever else they hold. */
static void test_diff(void **state)
{
    (void)state;
    WlPmFrame *a = wl_pm_frame_new(4, 3), *b = wl_pm_frame_new(4, 3);
    WlPmPixel p = px(1, 2, 0.5, 9);
    wl_pm_frame_put(a, &p);
    wl_pm_frame_put(b, &p);
    assert_int_equal(wl_pm_frame_diff(a, b), -1);
    b->px[3].z = 0.7; /* empty: depth ignored */
    b->px[3].color = 5;
    assert_int_equal(wl_pm_frame_diff(a, b), -1);
    WlPmPixel *q = &b->px[9];
    q->z = 0.25;
    assert_int_equal(wl_pm_frame_diff(a, b), 9);
    q->z = 0.5;
    q->color++;
    assert_int_equal(wl_pm_frame_diff(a, b), 9);
    q->color--;
    q->x = 0;
    assert_int_equal(wl_pm_frame_diff(a, b), 9);
    q->x = 1;
    q->y = 0;
    assert_int_equal(wl_pm_frame_diff(a, b), 9);
    q->y = 2;
    q->poly = 8;
    assert_int_equal(wl_pm_frame_diff(a, b), 9);
    b->px[0].poly = 1; /* an earlier difference comes first */
    assert_int_equal(wl_pm_frame_diff(a, b), 0);
    assert_int_equal(wl_pm_frame_diff(b, a), 0);
    b->px[0].poly = WL_PM_EMPTY;
    q->poly = 9;
    b->px[11].poly = 2; /* the last location */
    assert_int_equal(wl_pm_frame_diff(a, b), 11);
    wl_pm_frame_free(a);
    wl_pm_frame_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wpa_rows),
        cmocka_unit_test(test_front),
        cmocka_unit_test(test_frame),
        cmocka_unit_test(test_diff),
    };
    return cmocka_run_group_tests_name("pm_pixels", tests, NULL, NULL);
}
