/* image.c — RGB images; PNG (libpng simplified API) and PPM I/O.
 *
 * Writes encode in memory and hand the bytes to sim_file_write()
 * (g_file_set_contents_full: temporary file, fsync, rename; mode 0666
 * less the umask), so a failure leaves the target untouched.
 * O(W H) per operation.
 */
#include "sim/raster/image.h"
#include "sim/core/datapath.h"
#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

RastImage *rast_image_new(int width, int height)
{
    g_assert(width > 0 && height > 0);
    RastImage *img = g_new0(RastImage, 1);
    img->width = width;
    img->height = height;
    img->rgb = g_new0(uint8_t, (size_t)3 * width * height);
    return img;
}

void rast_image_free(RastImage *img)
{
    if (!img)
        return;
    g_free(img->rgb);
    g_free(img);
}

void rast_image_set(RastImage *img, int x, int y, uint32_t rgba)
{
    g_assert(x >= 0 && x < img->width && y >= 0 && y < img->height);
    uint8_t *p = img->rgb + 3 * ((size_t)y * img->width + x);
    p[0] = rgba & 0xff;
    p[1] = (rgba >> 8) & 0xff;
    p[2] = (rgba >> 16) & 0xff;
}

uint32_t rast_image_get(const RastImage *img, int x, int y)
{
    g_assert(x >= 0 && x < img->width && y >= 0 && y < img->height);
    const uint8_t *p = img->rgb + 3 * ((size_t)y * img->width + x);
    return p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | 0xff000000u;
}

void rast_image_fill(RastImage *img, RastColor c)
{
    uint8_t r = rast_channel(c.r), g = rast_channel(c.g), b = rast_channel(c.b);
    size_t n = (size_t)img->width * img->height;
    for (size_t i = 0; i < n; i++) {
        img->rgb[3 * i] = r;
        img->rgb[3 * i + 1] = g;
        img->rgb[3 * i + 2] = b;
    }
}

void rast_image_from_zbuffer(RastImage *img, const RastZBuffer *zb,
                             RastColor bg)
{
    g_assert(img->width == zb->width && img->height == zb->height);
    rast_image_fill(img, bg);
    for (int y = 0; y < zb->height; y++)
        for (int x = 0; x < zb->width; x++) {
            size_t i = (size_t)y * zb->width + x;
            if (zb->prim[i] != RAST_NO_PRIM)
                rast_image_set(img, x, y, zb->rgba[i]);
        }
}

void rast_image_from_active(RastImage *img, const RastActive *a, RastColor bg)
{
    g_assert(img->width == rast_active_width(a));
    g_assert(img->height == rast_active_height(a));
    rast_image_fill(img, bg);
    for (int y = 0; y < img->height; y++) {
        size_t n;
        const RastActivePixel *row = rast_active_row(a, y, &n);
        for (size_t i = 0; i < n; i++)
            rast_image_set(img, row[i].x, y, row[i].rgba);
    }
}

gboolean rast_image_equal(const RastImage *a, const RastImage *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->rgb, b->rgb, (size_t)3 * a->width * a->height) == 0;
}

uint64_t rast_image_diff(const RastImage *a, const RastImage *b)
{
    g_assert(a->width == b->width && a->height == b->height);
    size_t n = (size_t)a->width * a->height;
    uint64_t k = 0;
    for (size_t i = 0; i < n; i++)
        k += memcmp(a->rgb + 3 * i, b->rgb + 3 * i, 3) != 0;
    return k;
}

static gboolean io_error(GError **err, const char *path, const char *what)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", path, what);
    return FALSE;
}

static gboolean encode_png(const RastImage *img, const char *path,
                           GError **err)
{
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    pi.width = (png_uint_32)img->width;
    pi.height = (png_uint_32)img->height;
    pi.format = PNG_FORMAT_RGB;
    png_alloc_size_t size = 0;
    gboolean ok = FALSE;
    if (png_image_write_to_memory(&pi, NULL, &size, 0, img->rgb, 0, NULL)) {
        void *buf = g_malloc(size);
        ok = png_image_write_to_memory(&pi, buf, &size, 0, img->rgb, 0,
                                       NULL) &&
             sim_file_write(path, buf, size, err);
        g_free(buf);
    } else {
        io_error(err, path, pi.message);
    }
    png_image_free(&pi);
    return ok;
}

gboolean rast_image_write_png(const RastImage *img, const char *path,
                              GError **err)
{
    return encode_png(img, path, err);
}

gboolean rast_image_write_ppm(const RastImage *img, const char *path,
                              GError **err)
{
    size_t n = (size_t)3 * img->width * img->height;
    GString *s = g_string_sized_new(n + 32);
    g_string_printf(s, "P6\n%d %d\n255\n", img->width, img->height);
    g_string_append_len(s, (const char *)img->rgb, (gssize)n);
    gboolean ok = sim_file_write(path, s->str, s->len, err);
    g_string_free(s, TRUE);
    return ok;
}

gboolean rast_image_write(const RastImage *img, const char *path, GError **err)
{
    if (g_str_has_suffix(path, ".ppm"))
        return rast_image_write_ppm(img, path, err);
    return rast_image_write_png(img, path, err);
}

static RastImage *bad_ppm(GError **err, const char *path, const char *what)
{
    sim_error_located(err, path, 1, 1, what, "a binary PPM (P6, maxval 255)");
    return NULL;
}

RastImage *rast_image_read_ppm(const char *path, GError **err)
{
    gchar *data;
    gsize len;
    if (!sim_file_read(path, &data, &len, err))
        return NULL;
    int w = 0, h = 0, max = 0, off = 0;
    if (sscanf(data, "P6 %d %d %d%n", &w, &h, &max, &off) != 3 || w <= 0 ||
        h <= 0 || max != 255 || w > RAST_MAX_SIDE || h > RAST_MAX_SIDE) {
        g_free(data);
        return bad_ppm(err, path, "a malformed header");
    }
    size_t need = (size_t)3 * w * h;
    if ((size_t)off + 1 + need != len) {
        g_free(data);
        return bad_ppm(err, path, "a pixel array of the wrong size");
    }
    RastImage *img = rast_image_new(w, h);
    memcpy(img->rgb, data + off + 1, need);
    g_free(data);
    return img;
}

RastImage *rast_image_read_png(const char *path, GError **err)
{
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&pi, path)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", path, pi.message);
        png_image_free(&pi);
        return NULL;
    }
    pi.format = PNG_FORMAT_RGB;
    if (pi.width == 0 || pi.height == 0 || pi.width > RAST_MAX_SIDE ||
        pi.height > RAST_MAX_SIDE) {
        png_image_free(&pi);
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: bad size", path);
        return NULL;
    }
    RastImage *img = rast_image_new((int)pi.width, (int)pi.height);
    if (!png_image_finish_read(&pi, NULL, img->rgb, 0, NULL)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", path, pi.message);
        png_image_free(&pi);
        rast_image_free(img);
        return NULL;
    }
    return img;
}
