/* dp_color.c — the 8-bit colour table of seed 004's library (dp_color.h).
 * O(256) to build, O(pixels) to convert.
 */
#include "sim/workload/dpscan/dp_color.h"
#include <stdlib.h>
#include <string.h>

static const float default_pal[WL_DP_COLORS][3] = {
    {0.90f, 0.10f, 0.10f}, {0.10f, 0.60f, 0.10f}, {0.15f, 0.35f, 0.95f},
    {0.95f, 0.85f, 0.10f}, {0.95f, 0.50f, 0.05f}, {0.60f, 0.20f, 0.80f},
    {0.10f, 0.80f, 0.80f}, {0.95f, 0.40f, 0.70f}, {0.55f, 0.35f, 0.15f},
    {0.60f, 0.90f, 0.30f}, {0.50f, 0.50f, 0.50f}, {0.95f, 0.95f, 0.95f},
    {0.00f, 0.40f, 0.40f}, {0.50f, 0.00f, 0.20f}, {0.65f, 0.80f, 0.95f},
};

void wl_dp_palette_default(float pal[WL_DP_COLORS][3])
{
    memcpy(pal, default_pal, sizeof default_pal);
}

static gboolean hex_color(const char *s, float out[3])
{
    if (!s || s[0] != '#' || strlen(s) != 7)
        return FALSE;
    for (int k = 0; k < 3; k++) {
        char part[3] = {s[1 + 2 * k], s[2 + 2 * k], 0};
        char *end = NULL;
        long v = strtol(part, &end, 16);
        if (*end || !g_ascii_isxdigit(part[0]) || !g_ascii_isxdigit(part[1]))
            return FALSE;
        out[k] = (float)v / 255.0f;
    }
    return TRUE;
}

static gboolean triple(const CfgNode *n, float out[3])
{
    if (cfg_kind(n) != CFG_SEQ || cfg_seq_len(n) != 3)
        return FALSE;
    for (guint k = 0; k < 3; k++) {
        const char *s = cfg_scalar(cfg_seq_at(n, k));
        char *end = NULL;
        double v = s ? g_ascii_strtod(s, &end) : -1;
        if (!s || *end || v < 0 || v > 1)
            return FALSE;
        out[k] = (float)v;
    }
    return TRUE;
}

gboolean wl_dp_palette_from_cfg(const CfgNode *seq,
                                float pal[WL_DP_COLORS][3], GError **err)
{
    if (cfg_kind(seq) != CFG_SEQ || cfg_seq_len(seq) != WL_DP_COLORS) {
        char *found = cfg_kind(seq) == CFG_SEQ
                          ? g_strdup_printf("%u colours", cfg_seq_len(seq))
                          : g_strdup("not a list");
        cfg_error(err, seq, found,
                  "15 colours, each [r, g, b] in 0..1 or \"#rrggbb\"");
        g_free(found);
        return FALSE;
    }
    for (guint i = 0; i < WL_DP_COLORS; i++) {
        const CfgNode *c = cfg_seq_at(seq, i);
        if (!hex_color(cfg_scalar(c), pal[i]) && !triple(c, pal[i])) {
            cfg_error(err, c, "a bad colour", "[r, g, b] in 0..1 or \"#rrggbb\"");
            return FALSE;
        }
    }
    return TRUE;
}

void wl_dp_color_table(const float pal[WL_DP_COLORS][3], WlDpColorTable *t)
{
    memset(t, 0, sizeof *t);
    for (int i = 1; i < WL_DP_TABLE_BASE; i++)
        for (int k = 0; k < 3; k++)
            t->rgb[i][k] = (uint8_t)(i * 255 / (WL_DP_TABLE_BASE - 1));
    for (int c = 0; c < WL_DP_COLORS; c++)
        for (int s = 0; s < WL_DP_SHADES; s++)
            for (int k = 0; k < 3; k++) {
                float v = pal[c][k] * (float)(s + 1) / WL_DP_SHADES;
                t->rgb[WL_DP_TABLE_BASE + c * WL_DP_SHADES + s][k] =
                    (uint8_t)(v * 255.0f + 0.5f);
            }
    t->rgb[255][0] = t->rgb[255][1] = t->rgb[255][2] = 255;
}

RastImage *wl_dp_color_image(const uint8_t *index, int width, int height,
                             const WlDpColorTable *t)
{
    RastImage *img = rast_image_new(width, height);
    for (int64_t k = 0; k < (int64_t)width * height; k++)
        memcpy(img->rgb + 3 * k, t->rgb[index[k]], 3);
    return img;
}
