/* rpl_lines.h — reading and writing trace text, plain or gzip.
 *
 * A file whose name ends in ".gz" is (de)compressed on the fly by GLib's
 * GZlibCompressor/GZlibDecompressor (GIO, a Debian package), read through
 * every gzip member (rpl_gunzip.h: `cat a.gz b.gz` reads as a then b);
 * any other name is plain text.  The reader hands out one line at a time from a
 * fixed buffer (a line longer than RPL_LINE_MAX is a located error), so
 * memory does not grow with the file.  Tokens are blank-separated words;
 * the reader remembers each word's column for located errors of the
 * form `file:line:column: found X, expected Y`.
 *
 * The writer writes into "<path>.tmp" and renames it over <path> when
 * closed successfully, so a failed recording leaves no half-written file.
 */
#ifndef PGSIM_APP_REPLAY_RPL_LINES_H
#define PGSIM_APP_REPLAY_RPL_LINES_H

#include <glib.h>
#include <stdint.h>

#define RPL_LINE_MAX 4096
#define RPL_TOKENS_MAX 64

typedef struct RplLines RplLines;

/* Opens a trace for reading; NULL with *err (I/O) on failure. */
RplLines *rpl_lines_open(const char *path, GError **err);
void rpl_lines_free(RplLines *l);
/* Reads the next line that is not blank or a comment (# ...) and splits
 * it into words.  Returns the number of words (> 0), 0 at the end of the
 * file, -1 with *err on an I/O error or an over-long line. */
int rpl_lines_next(RplLines *l, GError **err);
/* The i-th word of the current line (borrowed until the next call). */
const char *rpl_lines_word(const RplLines *l, int i);
int rpl_lines_count(const RplLines *l);
/* The column (1-based) where word i starts. */
int rpl_lines_col(const RplLines *l, int i);
guint rpl_lines_number(const RplLines *l);
const char *rpl_lines_path(const RplLines *l);

/* A located input error at word i (i == count: the end of the line):
 * "path:line:col: found 'W', expected <what>". */
GError *rpl_lines_error(const RplLines *l, int i, const char *expected);
/* Word i as an unsigned integer no larger than max (else *err located). */
gboolean rpl_lines_u64(const RplLines *l, int i, uint64_t max, uint64_t *out,
                       const char *what, GError **err);

typedef struct RplWriter RplWriter;

/* Opens path for writing (compressed if it ends in .gz). */
RplWriter *rpl_writer_open(const char *path, GError **err);
/* Appends text; write errors are reported by rpl_writer_close(). */
void rpl_writer_puts(RplWriter *w, const char *s);
void rpl_writer_printf(RplWriter *w, const char *fmt, ...) G_GNUC_PRINTF(2, 3);
/* Flushes, closes and renames the file into place; FALSE with *err if
 * any write failed (then nothing is left at path).  Frees w. */
gboolean rpl_writer_close(RplWriter *w, GError **err);
/* Drops everything written (no file is left).  Frees w. */
void rpl_writer_abort(RplWriter *w);

#endif
