/* dp_color.h — the colour table of seed 004's library (§5).
 *
 * "The shading algorithm in the library supports 15 shades of up to 15
 * colors.  The color model is designed for eight color planes or the
 * PseudoColor video class.  The library expects indices 30 through 255
 * of the color table to provide the correct shading for 15 colors.
 * There is a utility routine that will generate the correct color table
 * from 15 user defined colors."  Index 30 + 15 c + s (s = 0 darkest ..
 * 14 full) holds colour c at brightness (s + 1) / 15; indices 0-29 are
 * left to the window system (here: 0 black, the background, and a grey
 * ramp), 255 is white.  O(256).
 */
#ifndef PGSIM_WORKLOAD_DPSCAN_DP_COLOR_H
#define PGSIM_WORKLOAD_DPSCAN_DP_COLOR_H

#include "sim/core/cfg.h"
#include "sim/raster/image.h"
#include "sim/workload/dpscan/dp_poly.h"

typedef struct {
    uint8_t rgb[256][3];
} WlDpColorTable;

/* The 15 default colours (a qualitative palette), RGB in [0, 1]. */
void wl_dp_palette_default(float pal[WL_DP_COLORS][3]);
/* Reads `palette: [[r, g, b] or "#rrggbb", ...]` of exactly 15 colours;
 * FALSE with a located *err. */
gboolean wl_dp_palette_from_cfg(const CfgNode *seq,
                                float pal[WL_DP_COLORS][3], GError **err);
/* The utility of §5: the 256-entry table from 15 colours. */
void wl_dp_color_table(const float pal[WL_DP_COLORS][3], WlDpColorTable *t);
/* The image array as RGB through the table; a new image, free with
 * rast_image_free(). */
RastImage *wl_dp_color_image(const uint8_t *index, int width, int height,
                             const WlDpColorTable *t);

#endif
