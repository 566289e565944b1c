/* image.h — RGB images, PNG and PPM output.
 *
 * A RastImage is 8-bit RGB, row-major, top row first.  Images are filled
 * from a full z-buffer or from active pixels (empty pixels get the
 * background), compared, and written as PNG (libpng's simplified API) or
 * binary PPM (P6).  Writes are atomic: the data goes to a temporary file
 * in the destination directory, which is then renamed over the target, so
 * a reader never sees a half-written image.  O(W H) each.
 */
#ifndef PGSIM_RASTER_IMAGE_H
#define PGSIM_RASTER_IMAGE_H

#include "sim/raster/scanzbuf.h"
#include "sim/raster/zbuffer.h"
#include "sim/core/error.h"

typedef struct {
    int width, height;
    uint8_t *rgb; /* 3 * width * height bytes */
} RastImage;

/* Returns a new black image; free with rast_image_free(). */
RastImage *rast_image_new(int width, int height);
void rast_image_free(RastImage *img);
void rast_image_fill(RastImage *img, RastColor c);
void rast_image_set(RastImage *img, int x, int y, uint32_t rgba);
/* Pixel (x, y) as 0xAABBGGRR with alpha 0xff. */
uint32_t rast_image_get(const RastImage *img, int x, int y);

/* Background, then every covered pixel of the z-buffer / active set. */
void rast_image_from_zbuffer(RastImage *img, const RastZBuffer *zb,
                             RastColor bg);
void rast_image_from_active(RastImage *img, const RastActive *a, RastColor bg);

gboolean rast_image_equal(const RastImage *a, const RastImage *b);
/* Number of pixels that differ (sizes must match). */
uint64_t rast_image_diff(const RastImage *a, const RastImage *b);

/* Writers: SIM_ERROR_IO on failure (the target is left untouched). */
gboolean rast_image_write_png(const RastImage *img, const char *path,
                              GError **err);
gboolean rast_image_write_ppm(const RastImage *img, const char *path,
                              GError **err);
/* PPM when the name ends in ".ppm", PNG otherwise. */
gboolean rast_image_write(const RastImage *img, const char *path, GError **err);
/* Reads a binary PPM (P6, maxval 255) written by rast_image_write_ppm();
 * NULL with SIM_ERROR_INPUT/IO on anything else. */
RastImage *rast_image_read_ppm(const char *path, GError **err);
/* Reads any PNG libpng understands, converted to 8-bit RGB. */
RastImage *rast_image_read_png(const char *path, GError **err);

#endif
