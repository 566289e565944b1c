/* test_pm_composite.c — the compositing schemes (pm_composite.h,
 * pm_stages.h): for binary swap, direct send, radix-k (several radix
 * vectors) and 2-3 swap at 1, 2, 3, 5, 8, 12, 16 and 64 processes, with
 * and without bounding rectangles and run-length encoding, in processor
 * order and in a shuffled visibility order, the z image
 * equals the serial z-buffer and the over image the serial front-to-back
 * blend; the checks are shown to fail on a wrong image; radix-k with
 * radices 2, 2, 2 is binary swap and with radix P direct send, message
 * for message; message bytes worked out by hand; the plans' shapes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "sim/workload/pixelmerge/pm_composite.h"

enum { W = 24, H = 20 };

static const guint counts[] = {1, 2, 3, 5, 8, 12, 16, 64};
static const WlPmFormat fmt = {8, 4, 2, 4, 8};

/* Processor p's local image: about a third of the locations, seeded. */
static WlPmWpa **random_locals(guint n, guint32 seed)
{
    GRand *r = g_rand_new_with_seed(seed);
    WlPmWpa **l = g_new(WlPmWpa *, n);
    for (guint p = 0; p < n; p++) {
        l[p] = wl_pm_wpa_new(W, H);
        guint x0 = g_rand_int_range(r, 0, W / 2), y0 = g_rand_int_range(r, 0, H / 2);
        for (guint y = y0; y < H; y++)
            for (guint x = x0; x < W; x++) {
                if (g_rand_int_range(r, 0, 3))
                    continue;
                WlPmPixel px = {(uint16_t)x, (uint16_t)y,
                                g_rand_int_range(r, 0, 8) / 8.0,
                                p * 1000 + y * W + x,
                                g_rand_int(r) & 0xffffff};
                wl_pm_wpa_push(l[p], &px);
            }
        wl_pm_wpa_finish(l[p]);
    }
    g_rand_free(r);
    return l;
}

static void free_locals(WlPmWpa **l, guint n)
{
    for (guint p = 0; p < n; p++)
        wl_pm_wpa_free(l[p]);
    g_free(l);
}

/* The serial z-buffer of the local images. */
static WlPmFrame *serial_z(WlPmWpa *const *l, guint n)
{
    WlPmFrame *f = wl_pm_frame_new(W, H);
    for (guint p = 0; p < n; p++)
        wl_pm_frame_put_wpa(f, l[p]);
    return f;
}

/* TRUE when the composite equals the serial reference. */
static gboolean matches(const WlPmComposite *c, WlPmWpa *const *l, guint n,
                        const WlPmCompose *o)
{
    if (o->op == WL_PM_OP_OVER) {
        double *ref = wl_pm_over_serial(l, n, o->order, o->opacity);
        gboolean ok = wl_pm_over_diff(ref, c->rgba, W * H * 4) < 0;
        g_free(ref);
        return ok;
    }
    WlPmFrame *f = serial_z(l, n);
    gboolean ok = wl_pm_frame_diff(f, c->merge->image) < 0;
    wl_pm_frame_free(f);
    return ok;
}

/* Every scheme's radix-k configurations to try at n processes. */
static guint radix_sets(guint n, WlPmCompose *sets)
{
    guint k = 0;
    sets[k++].n_radices = 0; /* the default factorisation */
    sets[k].radices[0] = n;  /* direct send */
    sets[k++].n_radices = n > 1;
    if (n == 12) {
        sets[k] = (WlPmCompose){.radices = {3, 4}, .n_radices = 2};
        k++;
        sets[k] = (WlPmCompose){.radices = {2, 3, 2}, .n_radices = 3};
        k++;
    }
    if (n == 64) {
        sets[k] = (WlPmCompose){.radices = {2, 8, 4}, .n_radices = 3};
        k++;
    }
    return k;
}

static void check_one(WlPmScheme s, const WlPmCompose *o, WlPmWpa **l,
                      guint n)
{
    WlPmComposite *c = wl_pm_composite_run(s, o, l, n, &fmt);
    if (!matches(c, l, n, o))
        fail_msg("%s P=%u op=%d rect=%d rle=%d: differs from serial",
                 wl_pm_scheme_names[s], n, o->op, o->bounding_rect, o->rle);
    /* the final pieces tile the image: every location held once */
    uint64_t held = 0;
    for (guint p = 0; p < n; p++)
        held += wl_pm_wpa_len(c->merge->held[p]);
    assert_int_equal(held, wl_pm_frame_count(c->merge->image));
    wl_pm_composite_free(c);
}

/* A seeded permutation of 0 .. n - 1 (a visibility order). */
static guint *shuffled(guint n, guint32 seed)
{
    GRand *r = g_rand_new_with_seed(seed);
    guint *o = g_new(guint, n);
    for (guint i = 0; i < n; i++)
        o[i] = i;
    for (guint i = n; i > 1; i--) {
        guint j = g_rand_int_range(r, 0, i), t = o[i - 1];
        o[i - 1] = o[j];
        o[j] = t;
    }
    g_rand_free(r);
    return o;
}

static void test_every_scheme_matches_serial(void **st)
{
    (void)st;
    for (guint i = 0; i < G_N_ELEMENTS(counts); i++) {
        guint n = counts[i];
        WlPmWpa **l = random_locals(n, 7 + n);
        guint *order = shuffled(n, 5 + n);
        for (int opt = 0; opt < 16; opt++) {
            WlPmCompose sets[5] = {0};
            guint ns = radix_sets(n, sets);
            for (guint s = WL_PM_BINARY_SWAP; s <= WL_PM_TWO_THREE_SWAP; s++)
                for (guint k = 0; k < (s == WL_PM_RADIX_K ? ns : 1); k++) {
                    WlPmCompose o = sets[k];
                    o.op = opt & 1 ? WL_PM_OP_OVER : WL_PM_OP_Z;
                    o.bounding_rect = (opt & 2) != 0;
                    o.rle = (opt & 4) != 0;
                    o.order = opt & 8 ? order : NULL;
                    o.opacity = 0.375;
                    check_one((WlPmScheme)s, &o, l, n);
                }
        }
        g_free(order);
        free_locals(l, n);
    }
}

/* The references can tell a wrong image: the blend in the wrong order,
 * a processor's pixels missing. */
static void test_checks_can_fail(void **st)
{
    (void)st;
    WlPmWpa **l = random_locals(3, 11);
    double *ref = wl_pm_over_serial(l, 3, NULL, 0.5);
    WlPmWpa *rev[3] = {l[2], l[1], l[0]};
    double *wrong = wl_pm_over_serial(rev, 3, NULL, 0.5);
    assert_true(wl_pm_over_diff(ref, wrong, W * H * 4) >= 0);
    assert_true(wl_pm_over_diff(ref, ref, W * H * 4) < 0);
    WlPmFrame *all = serial_z(l, 3), *two = serial_z(l, 2);
    assert_true(wl_pm_frame_diff(all, two) >= 0);
    wl_pm_frame_free(all);
    wl_pm_frame_free(two);
    g_free(ref);
    g_free(wrong);
    free_locals(l, 3);
}

static void assert_same_steps(const WlPmMerge *a, const WlPmMerge *b)
{
    assert_int_equal(a->steps->len, b->steps->len);
    for (guint s = 0; s < a->steps->len; s++) {
        const WlPmStep *x = g_ptr_array_index(a->steps, s);
        const WlPmStep *y = g_ptr_array_index(b->steps, s);
        assert_int_equal(x->n_msgs, y->n_msgs);
        for (guint i = 0; i < x->n_msgs; i++) {
            assert_int_equal(x->msg[i].src, y->msg[i].src);
            assert_int_equal(x->msg[i].dst, y->msg[i].dst);
            assert_int_equal(x->msg[i].bytes, y->msg[i].bytes);
        }
    }
}

static void test_radix_k_configurations(void **st)
{
    (void)st;
    WlPmWpa **l = random_locals(8, 3);
    WlPmCompose two = {.radices = {2, 2, 2}, .n_radices = 3, .rle = TRUE};
    WlPmCompose eight = {.radices = {8}, .n_radices = 1, .rle = TRUE};
    WlPmComposite *bs = wl_pm_composite_run(WL_PM_BINARY_SWAP, &two, l, 8, &fmt);
    WlPmComposite *ds = wl_pm_composite_run(WL_PM_DIRECT_SEND, &two, l, 8, &fmt);
    WlPmComposite *r2 = wl_pm_composite_run(WL_PM_RADIX_K, &two, l, 8, &fmt);
    WlPmComposite *r8 = wl_pm_composite_run(WL_PM_RADIX_K, &eight, l, 8, &fmt);
    assert_same_steps(bs->merge, r2->merge);
    assert_same_steps(ds->merge, r8->merge);
    assert_int_equal(bs->stages, 3);
    assert_int_equal(ds->stages, 1);
    /* binary swap: one message each way per pair and stage */
    const WlPmStep *s0 = g_ptr_array_index(bs->merge->steps, 0);
    assert_int_equal(s0->n_msgs, 8);
    for (guint i = 0; i < 8; i++)
        assert_int_equal(s0->msg[i].dst, s0->msg[i].src ^ 1);
    /* direct send: P - 1 messages each */
    const WlPmStep *d0 = g_ptr_array_index(ds->merge->steps, 0);
    assert_int_equal(d0->n_msgs, 8 * 7);
    wl_pm_composite_free(bs);
    wl_pm_composite_free(ds);
    wl_pm_composite_free(r2);
    wl_pm_composite_free(r8);
    free_locals(l, 8);
}

/* W x H = 8 x 4; processor 0 holds 0, 1, 2 and 20, processor 1 nothing;
 * direct send gives 0 the pixels 0 .. 15 and 1 the pixels 16 .. 31. */
static void test_message_bytes_by_hand(void **st)
{
    (void)st;
    WlPmWpa *l[2] = {wl_pm_wpa_new(8, 4), wl_pm_wpa_new(8, 4)};
    const guint at[] = {0, 1, 2, 20};
    for (guint i = 0; i < 4; i++) {
        WlPmPixel px = {(uint16_t)(at[i] % 8), (uint16_t)(at[i] / 8), 0.5, i,
                        0xffffff};
        wl_pm_wpa_push(l[0], &px);
    }
    wl_pm_wpa_finish(l[0]);
    wl_pm_wpa_finish(l[1]);
    /* {0 -> 1, 1 -> 0} bytes for plain, rect, rle, rect + rle; bpl 4,
     * bytes_per_run 4, bytes_per_rect 8 */
    const uint64_t want[4][2] = {{16 * 4, 16 * 4},
                                 {1 * 4 + 8, 0 + 8},
                                 {1 * 4 + 2 * 4, 0 + 1 * 4},
                                 {1 * 4 + 2 * 4 + 8, 0 + 1 * 4 + 8}};
    for (int opt = 0; opt < 4; opt++) {
        WlPmCompose o = {.bounding_rect = opt & 1, .rle = (opt & 2) != 0};
        WlPmComposite *c = wl_pm_composite_run(WL_PM_DIRECT_SEND, &o, l, 2, &fmt);
        const WlPmStep *s = g_ptr_array_index(c->merge->steps, 0);
        assert_int_equal(s->n_msgs, 2);
        assert_int_equal(s->msg[0].dst, 1);
        assert_int_equal(s->msg[0].bytes, want[opt][0]);
        assert_int_equal(s->msg[1].bytes, want[opt][1]);
        assert_int_equal(s->work[1].compare, s->msg[0].pixels);
        wl_pm_composite_free(c);
    }
    /* visibility order 1, 0: rank 0 is processor 1 and owns 0 .. 15, so
     * processor 0 sends it its three pixels there */
    const guint order[] = {1, 0};
    WlPmCompose o = {.rle = TRUE, .order = order};
    WlPmComposite *c = wl_pm_composite_run(WL_PM_DIRECT_SEND, &o, l, 2, &fmt);
    const WlPmStep *s = g_ptr_array_index(c->merge->steps, 0);
    assert_int_equal(s->msg[0].src * 10 + s->msg[0].dst, 1);
    assert_int_equal(s->msg[0].bytes, 3 * 4 + 2 * 4);
    assert_int_equal(wl_pm_wpa_len(c->merge->held[1]), 3);
    assert_int_equal(wl_pm_wpa_len(c->merge->held[0]), 1);
    wl_pm_composite_free(c);
    const guint dup[] = {1, 1}, big[] = {0, 2};
    assert_true(wl_pm_order_ok(order, 2));
    assert_false(wl_pm_order_ok(dup, 2));
    assert_false(wl_pm_order_ok(big, 2));
    wl_pm_wpa_free(l[0]);
    wl_pm_wpa_free(l[1]);
}

/* Runs in a bounding box count row by row: a run that ends on the box's
 * right edge goes on at its left edge on the next row. */
static void test_rle_runs_in_box(void **st)
{
    (void)st;
    WlPmWpa *l[2] = {wl_pm_wpa_new(8, 4), wl_pm_wpa_new(8, 4)};
    const guint at[] = {18, 19, 26, 27}; /* a 2 x 2 square at x 2, y 2 */
    for (guint i = 0; i < 4; i++) {
        WlPmPixel px = {(uint16_t)(at[i] % 8), (uint16_t)(at[i] / 8), 0.5, i,
                        1};
        wl_pm_wpa_push(l[0], &px);
    }
    wl_pm_wpa_finish(l[0]);
    wl_pm_wpa_finish(l[1]);
    WlPmCompose lin = {.rle = TRUE}, box = {.rle = TRUE, .bounding_rect = TRUE};
    WlPmComposite *a = wl_pm_composite_run(WL_PM_DIRECT_SEND, &lin, l, 2, &fmt);
    WlPmComposite *b = wl_pm_composite_run(WL_PM_DIRECT_SEND, &box, l, 2, &fmt);
    const WlPmStep *sa = g_ptr_array_index(a->merge->steps, 0);
    const WlPmStep *sb = g_ptr_array_index(b->merge->steps, 0);
    assert_int_equal(sa->msg[0].bytes, 4 * 4 + 3 * 4);     /* 2 runs */
    assert_int_equal(sb->msg[0].bytes, 4 * 4 + 2 * 4 + 8); /* 1 run */
    wl_pm_composite_free(a);
    wl_pm_composite_free(b);
    wl_pm_wpa_free(l[0]);
    wl_pm_wpa_free(l[1]);
}

static guint plan_groups(const WlPmPlan *p, guint s)
{
    return p->stage[s].n_groups;
}

static void test_plans(void **st)
{
    (void)st;
    guint r[WL_PM_MAX_RADICES];
    assert_int_equal(wl_pm_radices_default(64, r), 2);
    assert_int_equal(r[0] * 10 + r[1], 88);
    assert_int_equal(wl_pm_radices_default(12, r), 2);
    assert_int_equal(r[0] * 10 + r[1], 43);
    assert_int_equal(wl_pm_radices_default(13, r), 1);
    assert_int_equal(wl_pm_radices_default(1, r), 0);
    const guint ok[] = {3, 4}, bad[] = {3, 3}, one[] = {1, 12};
    assert_true(wl_pm_radices_ok(ok, 2, 12));
    assert_false(wl_pm_radices_ok(bad, 2, 12));
    assert_false(wl_pm_radices_ok(one, 2, 12));
    /* binary swap at 12: a fold of 4 pairs into 8 blocks, then 3 stages */
    WlPmPlan *bs = wl_pm_plan_new(WL_PM_BINARY_SWAP, 12, NULL, 0);
    assert_int_equal(bs->n_stages, 4);
    assert_true(bs->stage[0].fold);
    assert_int_equal(plan_groups(bs, 0), 8);
    assert_int_equal(bs->stage[0].size[3], 2);
    assert_int_equal(bs->stage[0].size[4], 1);
    wl_pm_plan_free(bs);
    /* 2-3 swap at 5: a pair and a triple, then the two together */
    WlPmPlan *tt = wl_pm_plan_new(WL_PM_TWO_THREE_SWAP, 5, NULL, 0);
    assert_int_equal(tt->n_stages, 2);
    assert_int_equal(tt->stage[0].size[0] * 10 + tt->stage[0].size[1], 23);
    assert_int_equal(plan_groups(tt, 1), 1);
    wl_pm_plan_free(tt);
    WlPmPlan *one_proc = wl_pm_plan_new(WL_PM_TWO_THREE_SWAP, 1, NULL, 0);
    assert_int_equal(one_proc->n_stages, 0);
    wl_pm_plan_free(one_proc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_scheme_matches_serial),
        cmocka_unit_test(test_checks_can_fail),
        cmocka_unit_test(test_radix_k_configurations),
        cmocka_unit_test(test_message_bytes_by_hand),
        cmocka_unit_test(test_rle_runs_in_box),
        cmocka_unit_test(test_plans),
    };
    return cmocka_run_group_tests_name("pm_composite", tests, NULL, NULL);
}
