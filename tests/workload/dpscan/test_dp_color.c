/* test_dp_color.c — seed 004's 8-bit colour table (dp_color.c), every
 * entry against its formula: index 0 black, 1..29 a grey ramp
 * i x 255 / 29, 30 + 15 c + s colour c at shade (s + 1) / 15 rounded,
 * 255 white; an image maps each index through the table; palettes from
 * a config as [r, g, b] in 0..1 or "#rrggbb", anything else refused at
 * its location.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "sim/workload/dpscan/dp_color.h"

static void test_table(void **state)
{
    (void)state;
    float pal[WL_DP_COLORS][3];
    for (int c = 0; c < WL_DP_COLORS; c++)
        for (int k = 0; k < 3; k++)
            pal[c][k] = (float)((c * 3 + k) % 11) / 10.0f;
    WlDpColorTable t;
    memset(&t, 0xab, sizeof t);
    wl_dp_color_table(pal, &t);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(t.rgb[0][k], 0);
        assert_int_equal(t.rgb[255][k], 255);
    }
    for (int i = 1; i < 30; i++)
        for (int k = 0; k < 3; k++)
            assert_int_equal(t.rgb[i][k], i * 255 / 29);
    assert_int_equal(t.rgb[29][0], 255);
    for (int c = 0; c < WL_DP_COLORS; c++)
        for (int s = 0; s < 15; s++)
            for (int k = 0; k < 3; k++) {
                /* in float, rounded half up, as the table is built */
                float v = pal[c][k] * (float)(s + 1) / 15.0f;
                int want = (int)(v * 255.0f + 0.5f);
                int got = t.rgb[30 + 15 * c + s][k];
                if (got != want || abs(got - (int)lround(v * 255.0)) > 1)
                    fail_msg("colour %d shade %d channel %d: %d, expected %d",
                             c, s, k, got, want);
            }
    /* an image: each pixel its index's entry */
    const uint8_t idx[6] = {0, 1, 30, 44, 254, 255};
    RastImage *img = wl_dp_color_image(idx, 3, 2, &t);
    assert_int_equal(img->width, 3);
    assert_int_equal(img->height, 2);
    for (int p = 0; p < 6; p++)
        assert_memory_equal(img->rgb + 3 * p, t.rgb[idx[p]], 3);
    rast_image_free(img);
}

/* The default palette entry by entry: every dpscan image without a
 * `palette:` uses it, so a change to it must be deliberate (like a
 * golden result). */
static void test_default_palette(void **state)
{
    (void)state;
    const float want[WL_DP_COLORS][3] = {
        {0.90f, 0.10f, 0.10f}, {0.10f, 0.60f, 0.10f}, {0.15f, 0.35f, 0.95f},
        {0.95f, 0.85f, 0.10f}, {0.95f, 0.50f, 0.05f}, {0.60f, 0.20f, 0.80f},
        {0.10f, 0.80f, 0.80f}, {0.95f, 0.40f, 0.70f}, {0.55f, 0.35f, 0.15f},
        {0.60f, 0.90f, 0.30f}, {0.50f, 0.50f, 0.50f}, {0.95f, 0.95f, 0.95f},
        {0.00f, 0.40f, 0.40f}, {0.50f, 0.00f, 0.20f}, {0.65f, 0.80f, 0.95f},
    };
    float pal[WL_DP_COLORS][3];
    memset(pal, 0, sizeof pal);
    wl_dp_palette_default(pal);
    assert_memory_equal(pal, want, sizeof want);
}

/* A palette of 15 entries: entry `bad` replaced by `what`. */
static void refused(const char *what, int bad, const char *message)
{
    GString *y = g_string_new("p: [");
    for (int i = 0; i < WL_DP_COLORS; i++)
        g_string_append_printf(y, "%s%s", i ? ", " : "",
                               i == bad ? what : "[0.5, 0, 1]");
    g_string_append(y, "]\n");
    GError *err = NULL;
    CfgNode *root = cfg_load_string(y->str, "pal.yaml", &err);
    assert_non_null(root);
    float pal[WL_DP_COLORS][3];
    gboolean ok = wl_dp_palette_from_cfg(cfg_get(root, "p"), pal, &err);
    if (!message) {
        if (!ok)
            fail_msg("%s refused: %s", what, err->message);
        assert_true(pal[0][0] == 0.5f && pal[0][1] == 0 && pal[0][2] == 1);
    } else {
        assert_false(ok);
        if (!strstr(err->message, message))
            fail_msg("%s: message '%s' lacks '%s'", what, err->message,
                     message);
        g_error_free(err);
    }
    cfg_free(root);
    g_string_free(y, TRUE);
}

static void test_palette_from_cfg(void **state)
{
    (void)state;
    refused("[0, 0, 0]", 3, NULL);
    refused("[1, 1, 1]", 3, NULL);
    refused("\"#a0B1c2\"", 3, NULL);
    const char *bad = "found a bad colour, expected [r, g, b] in 0..1";
    refused("[1.01, 0, 0]", 3, bad);
    refused("[0, -0.01, 0]", 3, bad);
    refused("[0, 0]", 3, bad);
    refused("[0, 0, 0, 0]", 3, bad);
    refused("[0, 0, x]", 3, bad);
    refused("\"#a0b1c\"", 3, bad);
    refused("\"#a0b1c2f\"", 3, bad);
    refused("\"#a0b1g2\"", 3, bad);
    refused("\"a0b1c2a\"", 3, bad);
    refused("\"# 0b1c2\"", 3, bad);
    refused("\"#a0b1c \"", 3, bad);
    refused("red", 14, bad);
    /* the error is located at the bad entry: column of entry 0 */
    GError *err = NULL;
    CfgNode *root = cfg_load_string("p: [[2, 0, 0]]\n", "pal.yaml", &err);
    float pal[WL_DP_COLORS][3];
    assert_false(wl_dp_palette_from_cfg(cfg_get(root, "p"), pal, &err));
    assert_string_equal(err->message,
                        "pal.yaml:1:4: found 1 colours, expected 15 colours, "
                        "each [r, g, b] in 0..1 or \"#rrggbb\"");
    g_clear_error(&err);
    cfg_free(root);
    root = cfg_load_string("p: {a: 1}\n", "pal.yaml", &err);
    assert_false(wl_dp_palette_from_cfg(cfg_get(root, "p"), pal, &err));
    assert_string_equal(err->message,
                        "pal.yaml:1:4: found not a list, expected 15 colours, "
                        "each [r, g, b] in 0..1 or \"#rrggbb\"");
    g_clear_error(&err);
    cfg_free(root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_default_palette),
        cmocka_unit_test(test_palette_from_cfg),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
