/* test_pm_parse.c — the pixelmerge section parser field by field: every
 * default, every word, each count key at both ends of its range (the
 * value one past either end refused with its file:line:column), the
 * block images' keys (images, volume) and their refusals, and the
 * own-memory estimate (mem_bytes) worked out from its formula. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/workload/pixelmerge/pm_workload.h"

/* Parses "workload: {type: pixelmerge<extra>}"; NULL with *err set on a
 * refusal. */
static WlPmParams *parse(const char *extra, GError **err)
{
    char *text = g_strdup_printf("workload: {type: pixelmerge%s}\n", extra);
    CfgNode *root = cfg_load_string(text, "pm.yaml", err);
    assert_non_null(root);
    WlPmParams *p = wl_pixelmerge_ops.parse(cfg_get(root, "workload"), err);
    cfg_free(root);
    g_free(text);
    return p;
}

static WlPmParams *parse_ok(const char *extra)
{
    GError *e = NULL;
    WlPmParams *p = parse(extra, &e);
    if (!p)
        fail_msg("%s: %s", extra, e->message);
    return p;
}

/* The refusal names the value's place: "pm.yaml:1:<col>:". */
static void expect_refused(const char *key, guint64 v)
{
    char *extra = g_strdup_printf(", %s: %" G_GUINT64_FORMAT, key, v);
    GError *e = NULL;
    assert_null(parse(extra, &e));
    assert_non_null(e);
    char *at = g_strdup_printf("pm.yaml:1:%d:",
                               (int)(strlen("workload: {type: pixelmerge, ") +
                                     strlen(key) + 3));
    if (!strstr(e->message, at))
        fail_msg("%s: '%s' lacks '%s'", extra, e->message, at);
    g_free(at);
    g_clear_error(&e);
    g_free(extra);
}

static void test_defaults(void **st)
{
    (void)st;
    WlPmParams *p = parse_ok("");
    assert_int_equal(p->setup.scheme, WL_PM_PAIR);
    assert_int_equal(p->setup.balance, WL_PM_BAL_RS);
    assert_int_equal(p->setup.split, WL_PM_SPLIT_CYCLIC);
    assert_int_equal(p->setup.span_rule, RAST_SPAN_EXACT);
    assert_int_equal(p->setup.procs, 0);
    assert_int_equal(p->setup.resolution, 400);
    assert_true(p->setup.check_image);
    assert_false(p->setup.cull_back);
    assert_int_equal(p->setup.fmt.bytes_per_pixel, 8);
    assert_int_equal(p->setup.fmt.bytes_per_location, 4);
    assert_int_equal(p->setup.fmt.bytes_per_scanline, 2);
    assert_int_equal(p->count_bytes, 4);
    assert_int_equal(p->mem.base, 1000000);
    assert_int_equal(p->mem.polygon, 200);
    assert_int_equal(p->mem.span, 32);
    assert_int_equal(p->mem.location, 8);
    assert_int_equal(p->mem.pixel, 8);
    assert_int_equal(p->mem.index, 4);
    wl_pixelmerge_ops.free_params(p);
}

static void test_words_and_values(void **st)
{
    (void)st;
    WlPmParams *p = parse_ok(
        ", scheme: zbuf_exc, balance: hbp, polygon_split: block,"
        " span_rule: endpoints, processors: 16, resolution: 2,"
        " check_image: false, cull_back: true, bytes_per_pixel: 5,"
        " bytes_per_location: 6, bytes_per_scanline: 0, bytes_per_count: 1,"
        " memory: {base: 11 B, polygon: 12 B, span: 13 B, location: 14 B,"
        " pixel: 15 B, index: 1 kB}");
    assert_int_equal(p->setup.scheme, WL_PM_ZBUF_EXC);
    assert_int_equal(p->setup.balance, WL_PM_BAL_HBP);
    assert_int_equal(p->setup.split, WL_PM_SPLIT_BLOCK);
    assert_int_equal(p->setup.span_rule, RAST_SPAN_ENDPOINTS);
    assert_int_equal(p->setup.procs, 16);
    assert_int_equal(p->setup.resolution, 2);
    assert_false(p->setup.check_image);
    assert_true(p->setup.cull_back);
    assert_int_equal(p->setup.fmt.bytes_per_pixel, 5);
    assert_int_equal(p->setup.fmt.bytes_per_location, 6);
    assert_int_equal(p->setup.fmt.bytes_per_scanline, 0);
    assert_int_equal(p->count_bytes, 1);
    assert_int_equal(p->mem.base, 11);
    assert_int_equal(p->mem.polygon, 12);
    assert_int_equal(p->mem.span, 13);
    assert_int_equal(p->mem.location, 14);
    assert_int_equal(p->mem.pixel, 15);
    assert_int_equal(p->mem.index, 1000);
    wl_pixelmerge_ops.free_params(p);
    p = parse_ok(", scheme: zbuf-exc, balance: strips");
    assert_int_equal(p->setup.scheme, WL_PM_ZBUF_EXC);
    assert_int_equal(p->setup.balance, WL_PM_BAL_STRIPS);
    wl_pixelmerge_ops.free_params(p);
    p = parse_ok(", scheme: aapc, processors: 1");
    assert_int_equal(p->setup.scheme, WL_PM_AAPC);
    assert_int_equal(p->setup.procs, 1);
    wl_pixelmerge_ops.free_params(p);
}

/* Each count key: its lowest and highest value accepted, one past
 * either refused (processors: powers of two only, 1 .. 1024). */
static void test_count_ranges(void **st)
{
    (void)st;
    static const struct {
        const char *key;
        guint64 lo, hi;
    } k[] = {{"processors", 1, 1024},      {"resolution", 2, 4096},
             {"bytes_per_pixel", 1, 256},  {"bytes_per_location", 1, 256},
             {"bytes_per_scanline", 0, 256}, {"bytes_per_count", 1, 16}};
    for (guint i = 0; i < G_N_ELEMENTS(k); i++) {
        for (guint j = 0; j < 2; j++) {
            char *extra = g_strdup_printf(", %s: %" G_GUINT64_FORMAT, k[i].key,
                                          j ? k[i].hi : k[i].lo);
            wl_pixelmerge_ops.free_params(parse_ok(extra));
            g_free(extra);
        }
        if (k[i].lo > 0)
            expect_refused(k[i].key, k[i].lo - 1);
        expect_refused(k[i].key, k[i].hi + 1);
    }
    expect_refused("processors", 6);
    expect_refused("processors", 3);
}

/* Refused with this text at pm.yaml:1:<col>, col where `value` (the
 * last occurrence in extra) stands. */
static void expect_refused_at(const char *extra, const char *value,
                              const char *text)
{
    const char *v = g_strrstr(extra, value);
    assert_non_null(v);
    int col = (int)(strlen("workload: {type: pixelmerge") + (v - extra) + 1);
    GError *e = NULL;
    assert_null(parse(extra, &e));
    assert_non_null(e);
    char *at = g_strdup_printf("pm.yaml:1:%d: %s", col, text);
    if (!strstr(e->message, at))
        fail_msg("%s: '%s' lacks '%s'", extra, e->message, at);
    g_free(at);
    g_clear_error(&e);
}

/* The compositing schemes: their words, any processor count, radices,
 * the options and their defaults; the options refused with Kurç's
 * schemes, radices refused with any other scheme and below 2. */
static void test_compositing_keys(void **st)
{
    (void)st;
    static const char *const words[] = {"binary_swap", "direct_send",
                                        "radix_k", "two_three_swap"};
    for (guint i = 0; i < G_N_ELEMENTS(words); i++) {
        char *extra = g_strdup_printf(", scheme: %s, processors: 12", words[i]);
        WlPmParams *p = parse_ok(extra);
        assert_int_equal(p->setup.scheme, WL_PM_BINARY_SWAP + i);
        assert_int_equal(p->setup.procs, 12);
        assert_int_equal(p->setup.comp.op, WL_PM_OP_Z);
        assert_false(p->setup.comp.rle || p->setup.comp.bounding_rect);
        assert_int_equal(p->setup.comp.n_radices, 0);
        assert_true(p->setup.comp.opacity == 0.5);
        assert_int_equal(p->setup.fmt.bytes_per_run, 4);
        assert_int_equal(p->setup.fmt.bytes_per_rect, 8);
        wl_pixelmerge_ops.free_params(p);
        g_free(extra);
    }
    WlPmParams *p = parse_ok(", scheme: radix_k, radices: [4, 3], rle: true,"
                             " bounding_rect: true, operator: over,"
                             " opacity: 0.25, bytes_per_run: 2,"
                             " bytes_per_rect: 0");
    assert_int_equal(p->setup.comp.n_radices, 2);
    assert_int_equal(p->setup.comp.radices[0] * 10 + p->setup.comp.radices[1],
                     43);
    assert_true(p->setup.comp.rle && p->setup.comp.bounding_rect);
    assert_int_equal(p->setup.comp.op, WL_PM_OP_OVER);
    assert_true(p->setup.comp.opacity == 0.25);
    assert_int_equal(p->setup.fmt.bytes_per_run, 2);
    assert_int_equal(p->setup.fmt.bytes_per_rect, 0);
    wl_pixelmerge_ops.free_params(p);
    expect_refused_at(", scheme: pair, radices: [2]", "[2]",
                      "found 'radices' with scheme 'pair', expected scheme "
                      "radix_k");
    expect_refused_at(", scheme: radix_k, radices: [4, 1]", "1]",
                      "found '1', expected a radix");
    expect_refused_at(", scheme: radix_k, radices: 4", "4",
                      "found 'radices', expected a list of 1 to 32");
    expect_refused_at(", scheme: aapc, rle: true", "true",
                      "found 'rle' with scheme 'aapc', expected a "
                      "compositing scheme");
    expect_refused_at(", scheme: direct_send, operator: under", "under",
                      "found 'under', expected one of: z, over");
    p = parse_ok(", scheme: binary_swap, processors: 3, visibility: [2, 0, 1]");
    assert_int_equal(p->n_order, 3);
    assert_true(p->setup.comp.order == p->order);
    assert_int_equal(p->order[0] * 100 + p->order[1] * 10 + p->order[2], 201);
    wl_pixelmerge_ops.free_params(p);
    expect_refused_at(", scheme: binary_swap, processors: 3, visibility: "
                      "[2, 2, 1]",
                      "[2, 2", "found a visibility order of 3 processors "
                               "with repeats, expected each of the 3");
    expect_refused_at(", scheme: direct_send, visibility: [0, x]", "x]",
                      "found 'x', expected a processor number");
    expect_refused_at(", scheme: pair, processors: 12", "12",
                      "found '12', expected a power of two");
}

/* mem_bytes: N^2 (copies x sizeof(WlPmPixel) + 3) + P (N + 1) 4 + P^2 8
 * (block images: their layers and lattice),
 * copies 3 with the serial check, 2 without; P = 0 counts as 1. */
static void test_mem_bytes(void **st)
{
    (void)st;
    const double px = sizeof(WlPmPixel);
    WlPmParams *p = parse_ok(", processors: 4, resolution: 10");
    GString *what = g_string_new(NULL);
    assert_true(wl_pixelmerge_ops.mem_bytes(p, what) ==
                100 * (3 * px + 3) + 4 * 11 * 4 + 16 * 8);
    assert_string_equal(what->str, "4 processors, 10 x 10 pixels");
    wl_pixelmerge_ops.free_params(p);
    p = parse_ok(", resolution: 7, check_image: false");
    g_string_truncate(what, 0);
    assert_true(wl_pixelmerge_ops.mem_bytes(p, what) ==
                49 * (2 * px + 3) + 1 * 8 * 4 + 1 * 8);
    assert_string_equal(what->str, "0 processors, 7 x 7 pixels");
    wl_pixelmerge_ops.free_params(p);
    /* block images: 2 layers at 8 blocks, and the volume's lattice */
    p = parse_ok(", scheme: direct_send, processors: 8, resolution: 10, "
                 "images: volume, volume: {grid: 20}");
    const double comp = 2 * 48.0, layers = 100 * 2 * (px + 32);
    assert_true(wl_pixelmerge_ops.mem_bytes(p, what) ==
                100 * (3 * px + 3 + comp) + 8 * 11 * 4 + 64 * 8 + layers +
                    21 * 21 * 21 * 8);
    wl_pixelmerge_ops.free_params(p);
    g_string_free(what, TRUE);
}

/* Per-node memory worked out from its parts: base, polygons x polygon,
 * spans x span; ZBUF-EXC a full N^2 z-buffer and an N^2 message of
 * locations; active-pixel schemes the WPA (pixel each) and MSA (index
 * per column) and two messages of active pixels. */
static void test_memory_use(void **st)
{
    (void)st;
    const WlPmMemory mem = {1000, 200, 30, 8, 12, 4};
    WlPmSetup s = {.scheme = WL_PM_ZBUF_EXC, .resolution = 10,
                   .fmt = {8, 5, 2, 0, 0}};
    WlPmMemUse u = wl_pm_memory_use(&mem, &s, 3, 7, 50);
    assert_int_equal(u.base, 1000);
    assert_int_equal(u.polygons, 600);
    assert_int_equal(u.spans, 210);
    assert_int_equal(u.zbuffer, 800);
    assert_int_equal(u.buffers, 500);
    assert_int_equal(u.total, 1000 + 600 + 210 + 800 + 500);
    s.scheme = WL_PM_PAIR;
    u = wl_pm_memory_use(&mem, &s, 3, 7, 50);
    assert_int_equal(u.zbuffer, 50 * 12 + 10 * 4);
    assert_int_equal(u.buffers, 2 * 50 * 8);
    assert_int_equal(u.total, 1000 + 600 + 210 + 640 + 800);
    /* compositing: a full image unless run-length encoded */
    s.scheme = WL_PM_RADIX_K;
    u = wl_pm_memory_use(&mem, &s, 3, 7, 50);
    assert_int_equal(u.zbuffer, 800);
    assert_int_equal(u.buffers, 500);
    s.comp.rle = TRUE;
    u = wl_pm_memory_use(&mem, &s, 3, 7, 50);
    assert_int_equal(u.zbuffer, 50 * 12 + 10 * 4);
    assert_int_equal(u.buffers, 2 * 50 * 8);
}

/* workload.images and workload.volume (pm_images.h, pm_volume.h). */
static void test_block_images(void **st)
{
    (void)st;
    GError *e = NULL;
    WlPmParams *p = parse(", scheme: radix_k, images: volume, volume: "
                          "{field: metaballs, grid: 20, step: 0.01, "
                          "density: 5, width: 0.5, iso: 1.5, balls: 3}",
                          &e);
    assert_non_null(p);
    const WlPmImages *im = &p->setup.images;
    assert_int_equal(im->kind, WL_PM_IMAGES_VOLUME);
    assert_int_equal(im->vol.iso.field, SCENE_FIELD_METABALLS);
    assert_int_equal(im->vol.iso.grid, 20);
    assert_int_equal(im->vol.iso.balls, 3);
    assert_true(im->vol.step == 0.01 && im->vol.density == 5 &&
                im->vol.width == 0.5 && im->vol.iso.iso == 1.5);
    wl_pixelmerge_ops.free_params(p);
    p = parse(", scheme: binary_swap, images: blocks, volume: {density: 3}",
              &e);
    assert_non_null(p);
    assert_true(p->setup.images.kind == WL_PM_IMAGES_BLOCKS &&
                p->setup.images.density == 3);
    wl_pixelmerge_ops.free_params(p);
    p = parse("", &e);
    assert_int_equal(p->setup.images.kind, WL_PM_IMAGES_SCENE);
    wl_pixelmerge_ops.free_params(p);
    static const struct {
        const char *extra, *where;
    } bad[] = {
        {", images: blocks", "pm.yaml:1:38:"}, /* Kurç's pair */
        {", scheme: radix_k, volume: {density: 2}", "pm.yaml:1:55:"},
        {", scheme: radix_k, images: blocks, visibility: [0]",
         "pm.yaml:1:75:"},
        {", scheme: radix_k, images: pixels", "pm.yaml:1:55:"},
        {", scheme: radix_k, images: volume, volume: {field: cube}",
         "pm.yaml:1:79:"},
        {", scheme: radix_k, images: volume, volume: {step: 0}",
         "pm.yaml:1:78:"},
    };
    for (guint i = 0; i < G_N_ELEMENTS(bad); i++) {
        assert_null(parse(bad[i].extra, &e));
        if (!strstr(e->message, bad[i].where))
            fail_msg("%s: '%s' lacks %s", bad[i].extra, e->message,
                     bad[i].where);
        g_clear_error(&e);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_words_and_values),
        cmocka_unit_test(test_count_ranges),
        cmocka_unit_test(test_compositing_keys),
        cmocka_unit_test(test_mem_bytes),
        cmocka_unit_test(test_memory_use),
        cmocka_unit_test(test_block_images),
    };
    return cmocka_run_group_tests_name("pm_parse", tests, NULL, NULL);
}
