/* table.c — text tables and CSV.
 *
 * The reader is a small state machine over the text: fields end at ',',
 * records at LF or CRLF; a quoted field may hold commas, newlines and
 * doubled quotes.  A line starting with '#' where a record would start
 * is a comment and is skipped (provenance headers, provenance.h); the
 * writer quotes a field starting with '#', so no record reads as one.
 * Invariant: every row has exactly cols->len cells (a record with
 * another count is an error naming its line).  A file's table is
 * estimated against the memory limit before it is built.  O(n).
 */
#include "sim/output/table.h"
#include "sim/core/datapath.h"
#include "sim/core/memlimit.h"
#include <glib/gstdio.h>
#include <string.h>
#include <sys/stat.h>

DataTable *dt_new(const GPtrArray *cols)
{
    DataTable *t = g_new0(DataTable, 1);
    t->cols = g_ptr_array_new_with_free_func(g_free);
    for (guint i = 0; i < cols->len; i++)
        g_ptr_array_add(t->cols, g_strdup(g_ptr_array_index(cols, i)));
    t->rows = g_ptr_array_new_with_free_func((GDestroyNotify)g_strfreev);
    return t;
}

DataTable *dt_new_named(const char *const *names)
{
    GPtrArray *cols = g_ptr_array_new();
    for (guint i = 0; names[i]; i++)
        g_ptr_array_add(cols, (gpointer)names[i]);
    DataTable *t = dt_new(cols);
    g_ptr_array_free(cols, TRUE);
    return t;
}

char *dt_col_names(const DataTable *t)
{
    GString *s = g_string_new(NULL);
    for (guint i = 0; i < t->cols->len; i++)
        g_string_append_printf(s, "%s%s", i ? ", " : "",
                               (const char *)g_ptr_array_index(t->cols, i));
    return g_string_free(s, FALSE);
}

void dt_free(DataTable *t)
{
    if (!t)
        return;
    g_ptr_array_free(t->cols, TRUE);
    g_ptr_array_free(t->rows, TRUE);
    if (t->pos)
        g_ptr_array_free(t->pos, TRUE);
    g_free(t->head_pos);
    g_free(t->path);
    g_free(t);
}

DataTable *dt_new_like(const DataTable *src)
{
    DataTable *t = dt_new(src->cols);
    if (src->pos) {
        t->path = g_strdup(src->path);
        t->head_pos = g_memdup2(src->head_pos, src->cols->len * sizeof(DtPos));
        t->pos = g_ptr_array_new_with_free_func(g_free);
    }
    return t;
}

void dt_copy_row(DataTable *dst, const DataTable *src, guint r)
{
    dt_add_row(dst, g_ptr_array_index(src->rows, r));
    const DtPos *at = src->pos ? g_ptr_array_index(src->pos, r) : NULL;
    if (dst->pos && at)
        dst->pos->pdata[dst->pos->len - 1] =
            g_memdup2(at, src->cols->len * sizeof(DtPos));
}

char *dt_where(const DataTable *t, guint r, int c)
{
    if (!t->pos || c < 0 || (guint)c >= t->cols->len ||
        (r != G_MAXUINT && r >= t->pos->len))
        return NULL;
    const DtPos *at = r == G_MAXUINT
                          ? t->head_pos
                          : (const DtPos *)g_ptr_array_index(t->pos, r);
    if (!at)
        return NULL;
    return g_strdup_printf("%s:%d:%d", t->path, at[c].line, at[c].col);
}

void dt_add_row(DataTable *t, char *const *cells)
{
    char **row = g_new0(char *, t->cols->len + 1);
    for (guint i = 0; i < t->cols->len; i++)
        row[i] = g_strdup(cells[i] ? cells[i] : "");
    g_ptr_array_add(t->rows, row);
    if (t->pos)
        g_ptr_array_add(t->pos, NULL); /* a row of no known place */
}

int dt_col(const DataTable *t, const char *name)
{
    for (guint i = 0; i < t->cols->len; i++)
        if (strcmp(g_ptr_array_index(t->cols, i), name) == 0)
            return (int)i;
    return -1;
}

const char *dt_cell(const DataTable *t, guint row, int col)
{
    g_assert(row < t->rows->len && col >= 0 && (guint)col < t->cols->len);
    return ((char **)g_ptr_array_index(t->rows, row))[col];
}

void dt_csv_field(GString *out, const char *s)
{
    if (!s)
        return;
    if (*s != '#' && !strpbrk(s, ",\"\n\r")) {
        g_string_append(out, s);
        return;
    }
    g_string_append_c(out, '"');
    for (const char *p = s; *p; p++) {
        if (*p == '"')
            g_string_append_c(out, '"');
        g_string_append_c(out, *p);
    }
    g_string_append_c(out, '"');
}

static void write_record(GString *out, char *const *cells, guint n)
{
    for (guint i = 0; i < n; i++) {
        if (i)
            g_string_append_c(out, ',');
        dt_csv_field(out, cells[i]);
    }
    g_string_append_c(out, '\n');
}

void dt_write_csv(const DataTable *t, GString *out)
{
    write_record(out, (char *const *)t->cols->pdata, t->cols->len);
    for (guint r = 0; r < t->rows->len; r++)
        write_record(out, g_ptr_array_index(t->rows, r), t->cols->len);
}

/* ---- reader ---------------------------------------------------------- */

typedef struct {
    const char *s;
    size_t pos;
    int line, col;
    const char *name;
} CsvReader;

static void advance(CsvReader *r)
{
    if (r->s[r->pos] == '\n') {
        r->line++;
        r->col = 0;
    }
    r->pos++;
    r->col++;
}

static gboolean quoted_field(CsvReader *r, GString *f, GError **err)
{
    int line = r->line, col = r->col;
    advance(r);
    for (;;) {
        char c = r->s[r->pos];
        if (!c) {
            sim_error_located(err, r->name, line, col,
                              "a quoted field without its closing quote",
                              "'\"' before the end of the file");
            return FALSE;
        }
        advance(r);
        if (c != '"') {
            g_string_append_c(f, c);
        } else if (r->s[r->pos] == '"') {
            g_string_append_c(f, '"');
            advance(r);
        } else {
            return TRUE;
        }
    }
}

/* Reads one record into a new strv, and where each field starts into
 * *at (a new array); NULL with *err on a bad field. */
static GPtrArray *read_record(CsvReader *r, GArray **at, GError **err)
{
    GPtrArray *cells = g_ptr_array_new_with_free_func(g_free);
    *at = g_array_new(FALSE, FALSE, sizeof(DtPos));
    for (;;) {
        DtPos here = {r->line, r->col};
        g_array_append_val(*at, here);
        GString *f = g_string_new(NULL);
        if (r->s[r->pos] == '"' && !quoted_field(r, f, err)) {
            g_string_free(f, TRUE);
            g_ptr_array_free(cells, TRUE);
            g_array_free(*at, TRUE);
            *at = NULL;
            return NULL;
        }
        while (r->s[r->pos] && !strchr(",\r\n", r->s[r->pos])) {
            g_string_append_c(f, r->s[r->pos]);
            advance(r);
        }
        g_ptr_array_add(cells, g_string_free(f, FALSE));
        if (r->s[r->pos] != ',')
            break;
        advance(r);
    }
    if (r->s[r->pos] == '\r')
        advance(r);
    if (r->s[r->pos] == '\n')
        advance(r);
    return cells;
}

static gboolean add_record(DataTable *t, GPtrArray *cells, GArray *at,
                           CsvReader *r, GError **err)
{
    int line = g_array_index(at, DtPos, 0).line;
    if (cells->len != t->cols->len) {
        char *f = g_strdup_printf("%u fields", cells->len);
        char *e = g_strdup_printf("%u, as in the header", t->cols->len);
        sim_error_located(err, r->name, line, 1, f, e);
        g_free(f);
        g_free(e);
        return FALSE;
    }
    g_ptr_array_add(cells, NULL);
    g_ptr_array_add(t->rows, g_ptr_array_free(cells, FALSE));
    g_ptr_array_add(t->pos, g_array_free(at, FALSE));
    return TRUE;
}

/* Skips comment lines (a '#' where a record starts). */
static void skip_comments(CsvReader *r)
{
    while (r->s[r->pos] == '#') {
        while (r->s[r->pos] && r->s[r->pos] != '\n')
            advance(r);
        if (r->s[r->pos])
            advance(r);
    }
}

DataTable *dt_parse_csv(const char *text, const char *name, GError **err)
{
    CsvReader r = {text, 0, 1, 1, name};
    GArray *at = NULL;
    skip_comments(&r);
    GPtrArray *head = read_record(&r, &at, err);
    if (!head)
        return NULL;
    DataTable *t = dt_new(head);
    g_ptr_array_free(head, TRUE);
    t->path = g_strdup(name);
    t->head_pos = (DtPos *)g_array_free(at, FALSE);
    t->pos = g_ptr_array_new_with_free_func(g_free);
    for (skip_comments(&r); r.s[r.pos]; skip_comments(&r)) {
        GPtrArray *cells = read_record(&r, &at, err);
        gboolean ok = cells != NULL;
        if (ok && cells->len == 1 && !*(char *)cells->pdata[0]) {
            g_ptr_array_free(cells, TRUE); /* blank line */
            g_array_free(at, TRUE);
        } else if (!ok || !add_record(t, cells, at, &r, err)) {
            if (cells && ok) {
                g_ptr_array_free(cells, TRUE);
                g_array_free(at, TRUE);
            }
            dt_free(t);
            return NULL;
        }
    }
    return t;
}

/* A CSV is UTF-8 text without NUL bytes: anything else (a binary file)
 * is a located error that does not echo the bytes. */
static gboolean check_text(const char *text, gsize len, const char *name,
                           GError **err)
{
    const char *end = NULL;
    if (memchr(text, '\0', len) == NULL && g_utf8_validate(text, len, &end))
        return TRUE;
    const char *bad = end ? end : memchr(text, '\0', len);
    int line = 1, col = 1;
    for (const char *p = text; p < bad; p++, col++)
        if (*p == '\n')
            line++, col = 0;
    char found[48];
    g_snprintf(found, sizeof found, "the byte 0x%02x",
               (unsigned)(guchar)*bad);
    sim_error_located(err, name, line, col, found, "UTF-8 text (a CSV file)");
    return FALSE;
}

/* The table of a CSV text within the memory limit (memlimit.h): the
 * text, and per cell its copy, pointer, place and allocation (assumption:
 * 32 bytes of allocator overhead a cell).  O(n). */
static gboolean csv_fits(const char *text, gsize len, const char *path,
                         GError **err)
{
    double cells = 1;
    for (gsize i = 0; i < len; i++)
        cells += text[i] == ',' || text[i] == '\n';
    double bytes = 2.0 * (double)len +
                   cells * (sizeof(char *) + sizeof(DtPos) + 32);
    char *where = g_strdup_printf("%s:1:1", path);
    char *what = g_strdup_printf("a CSV file of %.0f cells", cells);
    gboolean ok = sim_mem_check(bytes, where, what, err);
    g_free(what);
    g_free(where);
    return ok;
}

DataTable *dt_read_csv(const char *path, GError **err)
{
    char *text = NULL;
    gsize len = 0;
    GStatBuf st;
    if (g_stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
        char *where = g_strdup_printf("%s:1:1", path);
        gboolean ok = sim_mem_check((double)st.st_size, where,
                                    "a CSV file's text", err);
        g_free(where);
        if (!ok)
            return NULL;
    }
    if (!sim_file_read(path, &text, &len, err))
        return NULL;
    DataTable *t = check_text(text, len, path, err) &&
                           csv_fits(text, len, path, err)
                       ? dt_parse_csv(text, path, err)
                       : NULL;
    g_free(text);
    return t;
}
