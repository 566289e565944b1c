/* table.h — a table of text cells with named columns, read from and
 * written as CSV (RFC 4180: quoted fields, doubled quotes, CRLF or LF).
 *
 * Used for sweep results and by `pgsim plot`.  Cells are strings; an empty
 * string is a missing value.  Column lookup is O(columns).
 */
#ifndef PGSIM_OUTPUT_TABLE_H
#define PGSIM_OUTPUT_TABLE_H

#include "sim/core/error.h"

/* Where a cell starts in the file it was read from (1-based). */
typedef struct {
    int line, col;
} DtPos;

typedef struct {
    GPtrArray *cols; /* char * */
    GPtrArray *rows; /* char ** (cols->len strings each) */
    /* Read from a file (dt_parse_csv): its name, the header's cells'
     * places and per row a DtPos[cols->len] (parallel to rows); NULL in a
     * table built in memory. */
    char *path;
    DtPos *head_pos;
    GPtrArray *pos;
} DataTable;

/* Returns a new table with the given columns (copied); free with
 * dt_free(). */
DataTable *dt_new(const GPtrArray *cols);
/* The same from a NULL-terminated list of column names. */
DataTable *dt_new_named(const char *const *names);
void dt_free(DataTable *t);
/* Appends a row of cols->len strings (copied). */
void dt_add_row(DataTable *t, char *const *cells);
/* A new empty table with src's columns and, when src was read from a
 * file, its path and header places; dt_copy_row() appends src's row r
 * with its places (a filtered table keeps its errors located). */
DataTable *dt_new_like(const DataTable *src);
void dt_copy_row(DataTable *dst, const DataTable *src, guint r);
/* "path:line:col" of cell (r, c), or of column c's header when r is
 * G_MAXUINT (g_free); NULL when t was not read from a file. */
char *dt_where(const DataTable *t, guint r, int c);
/* The column names joined with ", " for messages (g_free). */
char *dt_col_names(const DataTable *t);
/* Column index, or -1. */
int dt_col(const DataTable *t, const char *name);
const char *dt_cell(const DataTable *t, guint row, int col);

/* Reads a CSV file whose first line that is not a comment ('#' at the
 * start of a line, skipped anywhere a record may start) is the header;
 * NULL with *err
 * ("file:line:column: found ..., expected ...") on a bad file. */
DataTable *dt_read_csv(const char *path, GError **err);
DataTable *dt_parse_csv(const char *text, const char *name, GError **err);
void dt_write_csv(const DataTable *t, GString *out);
/* Appends one CSV field, quoted when needed (NULL: an empty field; a
 * field starting with '#' is quoted, so it never reads as a comment). */
void dt_csv_field(GString *out, const char *s);

#endif
