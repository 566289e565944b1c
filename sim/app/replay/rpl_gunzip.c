/* rpl_gunzip.c — every member of a gzip file (rpl_gunzip.h).
 *
 * The wrapped GZlibDecompressor answers G_CONVERTER_FINISHED at the end of
 * each member; this converter turns that into G_CONVERTER_CONVERTED unless
 * the input is also at its end, and resets the inner decompressor before
 * the next byte.  Between members with no input left it asks for more
 * (G_IO_ERROR_PARTIAL_INPUT), as GConverter's contract says.
 */
#include "sim/app/replay/rpl_gunzip.h"

typedef struct {
    GObject parent;
    GConverter *inner;
    gboolean between; /* a member ended; the next byte starts another */
} RplGunzip;

typedef struct {
    GObjectClass parent_class;
} RplGunzipClass;

static void rpl_gunzip_iface_init(GConverterIface *iface);

G_DEFINE_TYPE_WITH_CODE(RplGunzip, rpl_gunzip, G_TYPE_OBJECT,
                        G_IMPLEMENT_INTERFACE(G_TYPE_CONVERTER,
                                              rpl_gunzip_iface_init))

static GConverterResult convert(GConverter *c, const void *in, gsize in_size,
                                void *out, gsize out_size,
                                GConverterFlags flags, gsize *read,
                                gsize *written, GError **err)
{
    RplGunzip *g = (RplGunzip *)c;
    if (g->between && in_size == 0) {
        *read = *written = 0;
        if (flags & G_CONVERTER_INPUT_AT_END)
            return G_CONVERTER_FINISHED;
        g_set_error_literal(err, G_IO_ERROR, G_IO_ERROR_PARTIAL_INPUT,
                            "need more input");
        return G_CONVERTER_ERROR;
    }
    if (g->between) {
        g_converter_reset(g->inner);
        g->between = FALSE;
    }
    GConverterResult r = g_converter_convert(g->inner, in, in_size, out,
                                             out_size, flags, read, written,
                                             err);
    if (r != G_CONVERTER_FINISHED)
        return r;
    g->between = TRUE;
    return *read == in_size && (flags & G_CONVERTER_INPUT_AT_END)
               ? G_CONVERTER_FINISHED
               : G_CONVERTER_CONVERTED;
}

static void reset(GConverter *c)
{
    RplGunzip *g = (RplGunzip *)c;
    g_converter_reset(g->inner);
    g->between = FALSE;
}

static void rpl_gunzip_iface_init(GConverterIface *iface)
{
    iface->convert = convert;
    iface->reset = reset;
}

static void finalize(GObject *o)
{
    g_object_unref(((RplGunzip *)o)->inner);
    G_OBJECT_CLASS(rpl_gunzip_parent_class)->finalize(o);
}

static void rpl_gunzip_class_init(RplGunzipClass *k)
{
    G_OBJECT_CLASS(k)->finalize = finalize;
}

static void rpl_gunzip_init(RplGunzip *g)
{
    g->inner = G_CONVERTER(
        g_zlib_decompressor_new(G_ZLIB_COMPRESSOR_FORMAT_GZIP));
}

GConverter *rpl_gunzip_new(void)
{
    return G_CONVERTER(g_object_new(rpl_gunzip_get_type(), NULL));
}
