/* rpl_lines.c — buffered line reader and atomic writer for traces
 * (rpl_lines.h).
 *
 * Reading: a 64 KiB input buffer refilled from a GInputStream (wrapped in
 * a GConverterInputStream for .gz) and one line buffer of RPL_LINE_MAX
 * bytes: memory is constant whatever the file's length.  Cost: O(bytes).
 */
#include "sim/app/replay/rpl_lines.h"
#include "sim/core/inputs.h"
#include "sim/app/replay/rpl_gunzip.h"
#include "sim/core/error.h"
#include <errno.h>
#include <gio/gio.h>
#include <glib/gstdio.h>
#include <string.h>
#include <sys/stat.h>

#define RPL_BUF 65536

struct RplLines {
    char *path;
    GInputStream *in;
    char buf[RPL_BUF];
    gsize len, pos;
    gboolean eof;
    char line[RPL_LINE_MAX + 1];
    char *word[RPL_TOKENS_MAX];
    int col[RPL_TOKENS_MAX];
    int n;
    guint number;
};

static gboolean is_gz(const char *path)
{
    return g_str_has_suffix(path, ".gz");
}

static GError *io_error(const char *path, GError *e)
{
    GError *r = g_error_new(SIM_ERROR, SIM_ERROR_IO, "%s: %s", path,
                            e ? e->message : "cannot read");
    g_clear_error(&e);
    return r;
}

/* A trace or map file must be a regular file: opening a FIFO would wait
 * for a writer (pgsim run refuses them the same way, datapath.c). */
static gboolean regular(const char *path, GError **err)
{
    GStatBuf st;
    if (g_stat(path, &st) != 0 || S_ISREG(st.st_mode))
        return TRUE; /* a missing file: g_file_read() says why */
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s:0:0: found %s, expected a regular file", path,
                S_ISDIR(st.st_mode)    ? "a directory"
                : S_ISFIFO(st.st_mode) ? "a pipe"
                                       : "a special file");
    return FALSE;
}

RplLines *rpl_lines_open(const char *path, GError **err)
{
    if (!regular(path, err))
        return NULL;
    sim_inputs_note_file("trace", path);
    GFile *f = g_file_new_for_path(path);
    GError *e = NULL;
    GInputStream *in = G_INPUT_STREAM(g_file_read(f, NULL, &e));
    g_object_unref(f);
    if (!in) {
        g_propagate_error(err, io_error(path, e));
        return NULL;
    }
    if (is_gz(path)) {
        GConverter *z = rpl_gunzip_new(); /* every member, not the first */
        GInputStream *c = g_converter_input_stream_new(in, z);
        g_object_unref(z);
        g_object_unref(in);
        in = c;
    }
    RplLines *l = g_new0(RplLines, 1);
    l->path = g_strdup(path);
    l->in = in;
    return l;
}

void rpl_lines_free(RplLines *l)
{
    if (!l)
        return;
    g_object_unref(l->in);
    g_free(l->path);
    g_free(l);
}

/* Refills the input buffer; FALSE with *err on a read error. */
static gboolean refill(RplLines *l, GError **err)
{
    GError *e = NULL;
    gssize n = g_input_stream_read(l->in, l->buf, RPL_BUF, NULL, &e);
    if (n < 0) {
        g_propagate_error(err, io_error(l->path, e));
        return FALSE;
    }
    l->len = (gsize)n;
    l->pos = 0;
    l->eof = n == 0;
    return TRUE;
}

/* Copies the next raw line into l->line; 1 read, 0 end, -1 error. */
static int raw_line(RplLines *l, GError **err)
{
    gsize k = 0;
    gboolean any = FALSE;
    for (;;) {
        if (l->pos == l->len && (l->eof || !refill(l, err) || l->eof))
            return err && *err ? -1 : (any ? (l->line[k] = 0, 1) : 0);
        char ch = l->buf[l->pos++];
        any = TRUE;
        if (ch == '\n')
            break;
        if (ch == 0) { /* would end the line's text early, silently */
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "%s:%u:%zu: found a NUL byte, expected text",
                        l->path, l->number + 1, k + 1);
            return -1;
        }
        if (k == RPL_LINE_MAX) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                        "%s:%u:1: found a line longer than %d characters, "
                        "expected one action per line",
                        l->path, l->number + 1, RPL_LINE_MAX);
            return -1;
        }
        l->line[k++] = ch;
    }
    l->line[k] = 0;
    return 1;
}

/* Splits l->line into words in place; FALSE if there are too many. */
static gboolean split(RplLines *l, GError **err)
{
    char *s = l->line, *hash = strchr(s, '#');
    if (hash)
        *hash = 0;
    l->n = 0;
    for (char *p = s; *p;) {
        while (*p == ' ' || *p == '\t' || *p == '\r')
            *p++ = 0;
        if (!*p)
            break;
        if (l->n == RPL_TOKENS_MAX) {
            g_propagate_error(err, rpl_lines_error(l, l->n - 1,
                                                   "at most 64 words a line"));
            return FALSE;
        }
        l->col[l->n] = (int)(p - s) + 1;
        l->word[l->n++] = p;
        while (*p && *p != ' ' && *p != '\t' && *p != '\r')
            p++;
    }
    return TRUE;
}

int rpl_lines_next(RplLines *l, GError **err)
{
    for (;;) {
        int r = raw_line(l, err);
        if (r <= 0)
            return r;
        l->number++;
        if (!split(l, err))
            return -1;
        if (l->n > 0)
            return l->n;
    }
}

const char *rpl_lines_word(const RplLines *l, int i)
{
    return i < l->n ? l->word[i] : "";
}

int rpl_lines_count(const RplLines *l)
{
    return l->n;
}

int rpl_lines_col(const RplLines *l, int i)
{
    return i < l->n ? l->col[i] : 1;
}

guint rpl_lines_number(const RplLines *l)
{
    return l->number;
}

const char *rpl_lines_path(const RplLines *l)
{
    return l->path;
}

GError *rpl_lines_error(const RplLines *l, int i, const char *expected)
{
    if (i >= l->n) {
        int col = l->n ? l->col[l->n - 1] + (int)strlen(l->word[l->n - 1])
                       : 1;
        return g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                           "%s:%u:%d: found the end of the line, expected %s",
                           l->path, l->number, col, expected);
    }
    return g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                       "%s:%u:%d: found '%s', expected %s", l->path, l->number,
                       l->col[i], l->word[i], expected);
}

gboolean rpl_lines_u64(const RplLines *l, int i, uint64_t max, uint64_t *out,
                       const char *what, GError **err)
{
    guint64 v;
    if (i < l->n &&
        g_ascii_string_to_unsigned(l->word[i], 10, 0, max, &v, NULL)) {
        *out = v;
        return TRUE;
    }
    g_propagate_error(err, rpl_lines_error(l, i, what));
    return FALSE;
}

/* ---- writer ---- */

struct RplWriter {
    char *path, *tmp;
    GOutputStream *out;
    GString *buf;
    GError *error; /* the first write error */
};

RplWriter *rpl_writer_open(const char *path, GError **err)
{
    char *tmp = g_strconcat(path, ".tmp", NULL);
    GFile *f = g_file_new_for_path(tmp);
    GError *e = NULL;
    GOutputStream *out = G_OUTPUT_STREAM(
        g_file_replace(f, NULL, FALSE, G_FILE_CREATE_NONE, NULL, &e));
    g_object_unref(f);
    if (!out) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", path, e->message);
        g_error_free(e);
        g_free(tmp);
        return NULL;
    }
    if (is_gz(path)) {
        GZlibCompressor *z =
            g_zlib_compressor_new(G_ZLIB_COMPRESSOR_FORMAT_GZIP, -1);
        GOutputStream *c = g_converter_output_stream_new(out, G_CONVERTER(z));
        g_object_unref(z);
        g_object_unref(out);
        out = c;
    }
    RplWriter *w = g_new0(RplWriter, 1);
    w->path = g_strdup(path);
    w->tmp = tmp;
    w->out = out;
    w->buf = g_string_sized_new(RPL_BUF);
    return w;
}

static void flush(RplWriter *w)
{
    if (!w->error && w->buf->len)
        g_output_stream_write_all(w->out, w->buf->str, w->buf->len, NULL, NULL,
                                  &w->error);
    g_string_truncate(w->buf, 0);
}

void rpl_writer_puts(RplWriter *w, const char *s)
{
    g_string_append(w->buf, s);
    if (w->buf->len >= RPL_BUF)
        flush(w);
}

void rpl_writer_printf(RplWriter *w, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    g_string_append_vprintf(w->buf, fmt, ap);
    va_end(ap);
    if (w->buf->len >= RPL_BUF)
        flush(w);
}

static void writer_free(RplWriter *w)
{
    g_object_unref(w->out);
    g_string_free(w->buf, TRUE);
    g_free(w->path);
    g_free(w->tmp);
    g_free(w);
}

gboolean rpl_writer_close(RplWriter *w, GError **err)
{
    flush(w);
    if (!w->error)
        g_output_stream_close(w->out, NULL, &w->error);
    if (!w->error && g_rename(w->tmp, w->path) != 0)
        w->error = g_error_new(G_IO_ERROR, G_IO_ERROR_FAILED, "%s",
                               g_strerror(errno));
    gboolean ok = !w->error;
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", w->path,
                    w->error->message);
        g_error_free(w->error);
        g_unlink(w->tmp);
    }
    writer_free(w);
    return ok;
}

void rpl_writer_abort(RplWriter *w)
{
    g_output_stream_close(w->out, NULL, NULL);
    g_unlink(w->tmp);
    if (w->error)
        g_error_free(w->error);
    writer_free(w);
}
