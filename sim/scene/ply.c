/* ply.c — PLY (Stanford polygon file) reading and writing.
 *
 * Implements ply.h.  The header becomes a list of elements with typed
 * properties; the body is read element by element through one value
 * reader that is either an ASCII tokenizer (tracking line and column) or
 * a bounds-checked binary cursor (tracking the byte offset), so every
 * error can say where it happened.  Format: Turk 1994.  O(file size).
 */
#include "sim/scene/ply.h"
#include "sim/core/inputs.h"
#include "sim/core/datapath.h"
#include "sim/scene/scene_limits.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

typedef enum { P_I8, P_U8, P_I16, P_U16, P_I32, P_U32, P_F32, P_F64 } PType;

static const char *const type_names[] = {
    "char",  "uchar",  "short",   "ushort",  "int",   "uint",
    "float", "double", "int8",    "uint8",   "int16", "uint16",
    "int32", "uint32", "float32", "float64", NULL};
static const guint type_size[] = {1, 1, 2, 2, 4, 4, 4, 8};

typedef struct {
    char *name;
    gboolean list;
    PType count_type, type;
} PProp;

typedef struct {
    char *name;
    guint64 count;
    GArray *props; /* PProp */
    int line;      /* of its header line */
} PElem;

typedef struct {
    const char *name;
    const guchar *data;
    gsize len, pos;
    ScenePlyFormat fmt;
    int line, col; /* ASCII position of pos */
    gsize tok_pos; /* start of the last token / value */
    int tok_line, tok_col;
    GArray *elems; /* PElem */
    GError **err;
} Ply;

/* ---- errors ----------------------------------------------------------- */

static gboolean fail(Ply *p, const char *found, const char *expected)
{
    if (p->fmt == SCENE_PLY_ASCII || p->line > 0)
        sim_error_located(p->err, p->name, p->tok_line, p->tok_col, found,
                          expected);
    else
        g_set_error(p->err, SIM_ERROR, SIM_ERROR_INPUT,
                    "%s: byte offset %" G_GSIZE_FORMAT
                    ": found %s, expected %s",
                    p->name, p->tok_pos, found, expected);
    return FALSE;
}

/* ---- ASCII tokens (header and ASCII body) ----------------------------- */

static void advance(Ply *p)
{
    if (p->data[p->pos] == '\n') {
        p->line++;
        p->col = 1;
    } else {
        p->col++;
    }
    p->pos++;
}

static void skip_blanks(Ply *p, gboolean newlines)
{
    while (p->pos < p->len &&
           (p->data[p->pos] == ' ' || p->data[p->pos] == '\t' ||
            p->data[p->pos] == '\r' || (newlines && p->data[p->pos] == '\n')))
        advance(p);
}

/* The next token on the line (or across lines if `newlines`) into buf,
 * cut to size - 1 bytes; empty when the line ends.  Returns the token's
 * whole length. */
static gsize token(Ply *p, gboolean newlines, char *buf, gsize size)
{
    skip_blanks(p, newlines);
    p->tok_pos = p->pos;
    p->tok_line = p->line;
    p->tok_col = p->col;
    gsize n = 0;
    while (p->pos < p->len && !g_ascii_isspace(p->data[p->pos])) {
        if (n < size - 1)
            buf[n++] = (char)p->data[p->pos];
        advance(p);
    }
    buf[n] = 0;
    return p->pos - p->tok_pos;
}

static void quoted(const char *tok, char *out, gsize size)
{
    if (*tok)
        g_snprintf(out, size, "'%.40s'", tok);
    else
        g_snprintf(out, size, "end of line");
}

static gboolean fail_tok(Ply *p, const char *tok, const char *expected)
{
    char q[64];
    quoted(tok, q, sizeof q);
    return fail(p, q, expected);
}

static void skip_line(Ply *p)
{
    while (p->pos < p->len && p->data[p->pos] != '\n')
        advance(p);
    if (p->pos < p->len)
        advance(p);
}

static gboolean end_of_line(Ply *p)
{
    char tok[64];
    token(p, FALSE, tok, sizeof tok);
    if (*tok)
        return fail_tok(p, tok, "end of line");
    skip_line(p);
    return TRUE;
}

/* ---- header ------------------------------------------------------------ */

static gboolean parse_type(Ply *p, PType *t)
{
    char tok[64];
    token(p, FALSE, tok, sizeof tok);
    for (int i = 0; type_names[i]; i++)
        if (!strcmp(tok, type_names[i])) {
            *t = (PType)(i % 8);
            return TRUE;
        }
    return fail_tok(p, tok,
                    "a type (char uchar short ushort int uint "
                    "float double or int8 ... float64)");
}

static gboolean parse_property(Ply *p)
{
    char tok[64];
    if (p->elems->len == 0)
        return fail(p, "'property'", "an 'element' line before it");
    PElem *e = &g_array_index(p->elems, PElem, p->elems->len - 1);
    PProp pr = {NULL, FALSE, P_U8, P_U8};
    skip_blanks(p, FALSE);
    if (p->pos + 4 <= p->len && !memcmp(p->data + p->pos, "list", 4) &&
        p->pos + 4 < p->len && g_ascii_isspace(p->data[p->pos + 4])) {
        token(p, FALSE, tok, sizeof tok);
        pr.list = TRUE;
        if (!parse_type(p, &pr.count_type))
            return FALSE;
        if (pr.count_type >= P_F32)
            return fail_tok(p, type_names[pr.count_type],
                            "an integer list-count type");
    }
    if (!parse_type(p, &pr.type))
        return FALSE;
    token(p, FALSE, tok, sizeof tok);
    if (!*tok)
        return fail_tok(p, tok, "a property name");
    pr.name = g_strdup(tok);
    g_array_append_val(e->props, pr);
    return end_of_line(p);
}

static gboolean parse_count(Ply *p, const char *tok, guint64 *out)
{
    char *end;
    errno = 0;
    *out = g_ascii_strtoull(tok, &end, 10);
    if (!*tok || *end || errno || !g_ascii_isdigit(tok[0]))
        return fail_tok(p, tok, "an element count");
    return TRUE;
}

static gboolean parse_element(Ply *p)
{
    char name[64], tok[64];
    token(p, FALSE, name, sizeof name);
    if (!*name)
        return fail_tok(p, name, "an element name");
    token(p, FALSE, tok, sizeof tok);
    PElem e = {NULL, 0, NULL, p->tok_line};
    if (!parse_count(p, tok, &e.count))
        return FALSE;
    /* Every item takes at least one byte (binary) or two (ASCII). */
    if (e.count > p->len)
        return fail_tok(p, tok, "a count the file size can hold");
    e.name = g_strdup(name);
    e.props = g_array_new(FALSE, FALSE, sizeof(PProp));
    g_array_append_val(p->elems, e);
    return end_of_line(p);
}

static gboolean parse_format(Ply *p)
{
    char tok[64];
    token(p, FALSE, tok, sizeof tok);
    if (!strcmp(tok, "ascii"))
        p->fmt = SCENE_PLY_ASCII;
    else if (!strcmp(tok, "binary_little_endian"))
        p->fmt = SCENE_PLY_BINARY_LE;
    else if (!strcmp(tok, "binary_big_endian"))
        p->fmt = SCENE_PLY_BINARY_BE;
    else
        return fail_tok(p, tok,
                        "ascii, binary_little_endian or "
                        "binary_big_endian");
    token(p, FALSE, tok, sizeof tok);
    if (strcmp(tok, "1.0"))
        return fail_tok(p, tok, "version 1.0");
    return end_of_line(p);
}

static gboolean parse_header(Ply *p)
{
    char tok[64];
    gboolean have_format = FALSE;
    token(p, FALSE, tok, sizeof tok);
    if (strcmp(tok, "ply"))
        return fail_tok(p, tok, "'ply' (the PLY magic line)");
    if (!end_of_line(p))
        return FALSE;
    for (;;) {
        token(p, FALSE, tok, sizeof tok);
        if (p->pos >= p->len && !*tok)
            return fail(p, "end of file", "'end_header'");
        if (!strcmp(tok, "format")) {
            if (!parse_format(p))
                return FALSE;
            have_format = TRUE;
        } else if (!strcmp(tok, "comment") || !strcmp(tok, "obj_info") ||
                   !*tok) {
            skip_line(p);
        } else if (!strcmp(tok, "element")) {
            if (!parse_element(p))
                return FALSE;
        } else if (!strcmp(tok, "property")) {
            if (!parse_property(p))
                return FALSE;
        } else if (!strcmp(tok, "end_header")) {
            break;
        } else {
            return fail_tok(p, tok,
                            "format, comment, obj_info, element, "
                            "property or end_header");
        }
    }
    if (!have_format)
        return fail_tok(p, tok, "a 'format' line before end_header");
    /* end_header's line ends with exactly one newline (CR LF allowed). */
    skip_blanks(p, FALSE);
    if (p->pos < p->len && p->data[p->pos] == '\n')
        advance(p);
    return TRUE;
}

/* ---- values ------------------------------------------------------------ */

static gboolean ascii_value(Ply *p, PType t, double *out)
{
    char tok[64], *end;
    gsize len = token(p, TRUE, tok, sizeof tok);
    if (!*tok)
        return fail(p, "end of file", "a number");
    *out = g_ascii_strtod(tok, &end);
    if (len >= sizeof tok || *end || !isfinite(*out)) /* or read cut */
        return fail_tok(p, tok, "a finite number");
    if (t < P_F32 && *out != floor(*out))
        return fail_tok(p, tok, "an integer");
    return TRUE;
}

static guint64 load_bytes(const guchar *b, guint n, gboolean big)
{
    guint64 v = 0;
    for (guint i = 0; i < n; i++)
        v |= (guint64)b[big ? n - 1 - i : i] << (8 * i);
    return v;
}

static double decode(guint64 v, PType t)
{
    switch (t) {
    case P_I8:
        return (gint8)v;
    case P_U8:
        return (guint8)v;
    case P_I16:
        return (gint16)v;
    case P_U16:
        return (guint16)v;
    case P_I32:
        return (gint32)v;
    case P_U32:
        return (guint32)v;
    case P_F32: {
        guint32 u = (guint32)v;
        float f;
        memcpy(&f, &u, 4);
        return f;
    }
    default: {
        double d;
        memcpy(&d, &v, 8);
        return d;
    }
    }
}

static gboolean binary_value(Ply *p, PType t, double *out)
{
    guint n = type_size[t];
    p->tok_pos = p->pos;
    if (p->len - p->pos < n) {
        char exp[64];
        g_snprintf(exp, sizeof exp, "%u more bytes (a %s)", n, type_names[t]);
        return fail(p, "end of file", exp);
    }
    *out = decode(
        load_bytes(p->data + p->pos, n, p->fmt == SCENE_PLY_BINARY_BE), t);
    p->pos += n;
    if (!isfinite(*out))
        return fail(p, "a non-finite number", "a finite number");
    return TRUE;
}

static gboolean value(Ply *p, PType t, double *out)
{
    return p->fmt == SCENE_PLY_ASCII ? ascii_value(p, t, out)
                                     : binary_value(p, t, out);
}

/* ---- body -------------------------------------------------------------- */

typedef struct {
    int x, y, z, nx, ny, nz, r, g, b; /* property indices, -1 if absent */
    int list;                         /* face: the index list */
} Roles;

static int find_prop(const PElem *e, const char *name)
{
    for (guint i = 0; i < e->props->len; i++)
        if (!strcmp(g_array_index(e->props, PProp, i).name, name))
            return (int)i;
    return -1;
}

static Roles roles_of(const PElem *e)
{
    Roles r = {find_prop(e, "x"),    find_prop(e, "y"),
               find_prop(e, "z"),    find_prop(e, "nx"),
               find_prop(e, "ny"),   find_prop(e, "nz"),
               find_prop(e, "red"),  find_prop(e, "green"),
               find_prop(e, "blue"), find_prop(e, "vertex_indices")};
    if (r.list < 0)
        r.list = find_prop(e, "vertex_index");
    return r;
}

static float colour_of(const PElem *e, int i, double v)
{
    PType t = g_array_index(e->props, PProp, i).type;
    return (float)(t < P_F32 ? v / 255.0 : v);
}

/* Reads one list; stores up to 64 Ki entries in idx when idx != NULL. */
static gboolean read_list(Ply *p, const PProp *pr, GArray *idx)
{
    double c, v;
    if (!value(p, pr->count_type, &c))
        return FALSE;
    if (c < 0 || c > (double)(p->len - p->pos) + 1)
        return fail(p, "an impossible list count", "a count the file holds");
    for (guint64 k = 0; k < (guint64)c; k++) {
        if (!value(p, pr->type, &v))
            return FALSE;
        if (idx) {
            uint32_t u = v < 0 || v > G_MAXUINT32 ? G_MAXUINT32 : (uint32_t)v;
            g_array_append_val(idx, u);
        }
    }
    return TRUE;
}

/* Range check of property i's value v just read (docs/config.md,
 * Limits): positions and normals within +-SCENE_COORD_MAX, colours in
 * [0, 1] once scaled. */
static gboolean check_range(Ply *p, const PElem *e, const Roles *r, int i,
                            double v)
{
    char found[64], expected[96];
    if (i == r->x || i == r->y || i == r->z || i == r->nx || i == r->ny ||
        i == r->nz) {
        if (scene_coord_ok(v))
            return TRUE;
        g_snprintf(found, sizeof found, "a coordinate %g", v);
        g_snprintf(expected, sizeof expected,
                   "a coordinate within +-%g (docs/config.md, Limits)",
                   SCENE_COORD_MAX);
        return fail(p, found, expected);
    }
    if ((i == r->r || i == r->g || i == r->b) &&
        !scene_color_ok(colour_of(e, i, v))) {
        g_snprintf(found, sizeof found, "a colour %g", v);
        return fail(p, found, "a colour in [0, 1] (float) or 0..255 (integer)");
    }
    return TRUE;
}

static gboolean read_vertex(Ply *p, const PElem *e, const Roles *r,
                            SceneMesh *m)
{
    double val[64] = {0};
    for (guint i = 0; i < e->props->len; i++) {
        const PProp *pr = &g_array_index(e->props, PProp, i);
        double v;
        if (pr->list ? !read_list(p, pr, NULL)
                     : !value(p, pr->type, &v) || !check_range(p, e, r, i, v))
            return FALSE;
        if (!pr->list && i < 64)
            val[i] = v;
    }
    scene_mesh_add_vertex(m, vec3(val[r->x], val[r->y], val[r->z]));
    if (r->nx >= 0) {
        Vec3 n = vec3(val[r->nx], val[r->ny], val[r->nz]);
        g_array_append_val(m->normals, n);
    }
    if (r->r >= 0) {
        SceneColor c = {colour_of(e, r->r, val[r->r]),
                        colour_of(e, r->g, val[r->g]),
                        colour_of(e, r->b, val[r->b])};
        g_array_append_val(m->colors, c);
    }
    return TRUE;
}

static gboolean check_face(Ply *p, GArray *idx, guint nverts, gsize at,
                           int line, int col)
{
    p->tok_pos = at;
    p->tok_line = line;
    p->tok_col = col;
    if (idx->len < 3)
        return fail(p, "a face of fewer than 3 vertices",
                    "at least 3 vertex indices");
    for (guint k = 0; k < idx->len; k++)
        if (g_array_index(idx, uint32_t, k) >= nverts) {
            char exp[64];
            g_snprintf(exp, sizeof exp, "vertex indices in 0..%u",
                       nverts ? nverts - 1 : 0);
            return fail(p, "a vertex index out of range", exp);
        }
    return TRUE;
}

static gboolean read_face(Ply *p, const PElem *e, const Roles *r, SceneMesh *m,
                          GArray *idx)
{
    double val[64] = {0};
    if (p->fmt == SCENE_PLY_ASCII)
        skip_blanks(p, TRUE);
    gsize at = p->pos;
    int line = p->line, col = p->col;
    g_array_set_size(idx, 0);
    for (guint i = 0; i < e->props->len; i++) {
        const PProp *pr = &g_array_index(e->props, PProp, i);
        double v;
        if (pr->list) {
            if (!read_list(p, pr, (int)i == r->list ? idx : NULL))
                return FALSE;
        } else if (!value(p, pr->type, &v) || !check_range(p, e, r, i, v)) {
            return FALSE;
        } else if (i < 64) {
            val[i] = v;
        }
    }
    if (!check_face(p, idx, m->pos->len, at, line, col))
        return FALSE;
    SceneColor c = {1, 1, 1};
    if (r->r >= 0)
        c = (SceneColor){colour_of(e, r->r, val[r->r]),
                         colour_of(e, r->g, val[r->g]),
                         colour_of(e, r->b, val[r->b])};
    scene_mesh_add_poly(m, (uint32_t *)idx->data, idx->len, c, 0);
    return TRUE;
}

/* Whether the three property indices are all present or all absent. */
static gboolean all_or_none(int a, int b, int c)
{
    return (a >= 0) == (b >= 0) && (b >= 0) == (c >= 0);
}

static gboolean check_roles(Ply *p, const PElem *e, const Roles *r,
                            gboolean face, gboolean seen_vertex)
{
    const char *what = NULL;
    if (!face && (r->x < 0 || r->y < 0 || r->z < 0))
        what = "vertex properties x, y and z";
    else if (!face && !all_or_none(r->nx, r->ny, r->nz))
        what = "all of nx, ny, nz or none";
    else if (!all_or_none(r->r, r->g, r->b))
        what = "all of red, green, blue or none";
    else if (face &&
             (r->list < 0 || !g_array_index(e->props, PProp, r->list).list))
        what = "a face list property vertex_indices";
    else if (face && !seen_vertex)
        what = "the vertex element before the face element";
    else if (MAX(MAX(r->x, MAX(r->y, r->z)), MAX(MAX(r->nx, MAX(r->ny, r->nz)),
                                                 MAX(r->r, MAX(r->g, r->b)))) >=
             64)
        what = "x, y, z, normals and colours among the first 64 properties";
    if (!what)
        return TRUE;
    char found[96];
    g_snprintf(found, sizeof found, "element '%.40s' without them", e->name);
    sim_error_located(p->err, p->name, e->line, 1, found, what);
    return FALSE;
}

static gboolean read_body(Ply *p, SceneMesh *m)
{
    gboolean seen_vertex = FALSE, ok = TRUE;
    GArray *idx = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    for (guint ei = 0; ok && ei < p->elems->len; ei++) {
        const PElem *e = &g_array_index(p->elems, PElem, ei);
        gboolean is_v = !strcmp(e->name, "vertex");
        gboolean is_f = !strcmp(e->name, "face");
        Roles r = roles_of(e);
        if ((is_v || is_f) && !check_roles(p, e, &r, is_f, seen_vertex))
            ok = FALSE;
        for (guint64 k = 0; ok && k < e->count; k++) {
            if (is_v)
                ok = read_vertex(p, e, &r, m);
            else if (is_f)
                ok = read_face(p, e, &r, m, idx);
            else
                for (guint i = 0; ok && i < e->props->len; i++) {
                    const PProp *pr = &g_array_index(e->props, PProp, i);
                    double v;
                    ok = pr->list ? read_list(p, pr, NULL)
                                  : value(p, pr->type, &v);
                }
        }
        seen_vertex |= is_v;
    }
    g_array_free(idx, TRUE);
    return ok;
}

/* Nothing may follow the last element but white space (ASCII). */
static gboolean check_tail(Ply *p)
{
    if (p->fmt == SCENE_PLY_ASCII)
        skip_blanks(p, TRUE);
    if (p->pos >= p->len)
        return TRUE;
    p->tok_pos = p->pos;
    p->tok_line = p->line;
    p->tok_col = p->col;
    char found[64];
    g_snprintf(found, sizeof found, "%" G_GSIZE_FORMAT " bytes more",
               p->len - p->pos);
    return fail(p, found, "the end of the file after the last element");
}

static void free_elems(GArray *elems)
{
    for (guint i = 0; i < elems->len; i++) {
        PElem *e = &g_array_index(elems, PElem, i);
        for (guint k = 0; k < e->props->len; k++)
            g_free(g_array_index(e->props, PProp, k).name);
        g_array_free(e->props, TRUE);
        g_free(e->name);
    }
    g_array_free(elems, TRUE);
}

SceneMesh *scene_ply_parse(const guchar *data, gsize len, const char *name,
                           GError **err)
{
    Ply p = {name,
             data,
             len,
             0,
             SCENE_PLY_ASCII,
             1,
             1,
             0,
             1,
             1,
             g_array_new(FALSE, FALSE, sizeof(PElem)),
             err};
    SceneMesh *m = scene_mesh_new();
    gboolean ok = parse_header(&p);
    if (ok && p.fmt != SCENE_PLY_ASCII)
        p.line = 0; /* binary body: errors by byte offset */
    ok = ok && read_body(&p, m) && check_tail(&p);
    free_elems(p.elems);
    if (!ok) {
        scene_mesh_free(m);
        return NULL;
    }
    return m;
}

SceneMesh *scene_ply_load(const char *path, GError **err)
{
    char *data;
    gsize len;
    if (!sim_file_read(path, &data, &len, err))
        return NULL;
    sim_inputs_note_bytes("mesh", path, data, len);
    SceneMesh *m = scene_ply_parse((const guchar *)data, len, path, err);
    g_free(data);
    return m;
}

/* ---- writing ----------------------------------------------------------- */

static void put(GByteArray *b, ScenePlyFormat f, guint64 v, guint n)
{
    guchar buf[8];
    for (guint i = 0; i < n; i++)
        buf[f == SCENE_PLY_BINARY_BE ? n - 1 - i : i] = (guchar)(v >> (8 * i));
    g_byte_array_append(b, buf, n);
}

static void put_double(GByteArray *b, ScenePlyFormat f, double d)
{
    if (f == SCENE_PLY_ASCII) {
        char buf[G_ASCII_DTOSTR_BUF_SIZE + 1] = " ";
        g_ascii_formatd(buf + 1, sizeof buf - 1, "%.17g", d);
        g_byte_array_append(b, (guchar *)buf, strlen(buf));
        return;
    }
    guint64 v;
    memcpy(&v, &d, 8);
    put(b, f, v, 8);
}

static void put_uint(GByteArray *b, ScenePlyFormat f, guint64 v, guint n)
{
    if (f == SCENE_PLY_ASCII) {
        char buf[32];
        g_snprintf(buf, sizeof buf, " %" G_GUINT64_FORMAT, v);
        g_byte_array_append(b, (guchar *)buf, strlen(buf));
        return;
    }
    put(b, f, v, n);
}

static void put_eol(GByteArray *b, ScenePlyFormat f)
{
    if (f == SCENE_PLY_ASCII)
        g_byte_array_append(b, (const guchar *)"\n", 1);
}

static guint8 to_byte(float c)
{
    return (guint8)lrint(CLAMP(c, 0.0f, 1.0f) * 255.0f);
}

static void put_rgb(GByteArray *b, ScenePlyFormat f, SceneColor c)
{
    put_uint(b, f, to_byte(c.r), 1);
    put_uint(b, f, to_byte(c.g), 1);
    put_uint(b, f, to_byte(c.b), 1);
}

static void put_header(GByteArray *b, const SceneMesh *m, ScenePlyFormat f)
{
    static const char *const fmt[] = {"ascii", "binary_little_endian",
                                      "binary_big_endian"};
    GString *h = g_string_new("ply\n");
    g_string_append_printf(h, "format %s 1.0\ncomment written by pgsim\n",
                           fmt[f]);
    g_string_append_printf(h, "element vertex %u\n", m->pos->len);
    g_string_append(h, "property double x\nproperty double y\n"
                       "property double z\n");
    if (m->normals->len)
        g_string_append(h, "property double nx\nproperty double ny\n"
                           "property double nz\n");
    if (m->colors->len)
        g_string_append(h, "property uchar red\nproperty uchar green\n"
                           "property uchar blue\n");
    g_string_append_printf(h, "element face %u\n", scene_mesh_n_polys(m));
    g_string_append(h, "property list uint uint vertex_indices\n"
                       "property uchar red\nproperty uchar green\n"
                       "property uchar blue\nend_header\n");
    g_byte_array_append(b, (guchar *)h->str, h->len);
    g_string_free(h, TRUE);
}

guchar *scene_ply_encode(const SceneMesh *m, ScenePlyFormat f, gsize *len)
{
    GByteArray *b = g_byte_array_new();
    put_header(b, m, f);
    for (guint i = 0; i < m->pos->len; i++) {
        Vec3 p = scene_mesh_vertex(m, i);
        put_double(b, f, p.x);
        put_double(b, f, p.y);
        put_double(b, f, p.z);
        if (m->normals->len) {
            Vec3 n = g_array_index(m->normals, Vec3, i);
            put_double(b, f, n.x);
            put_double(b, f, n.y);
            put_double(b, f, n.z);
        }
        if (m->colors->len)
            put_rgb(b, f, g_array_index(m->colors, SceneColor, i));
        put_eol(b, f);
    }
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        guint n = scene_mesh_poly_len(m, i);
        const uint32_t *v = scene_mesh_poly(m, i);
        put_uint(b, f, n, 4);
        for (guint k = 0; k < n; k++)
            put_uint(b, f, v[k], 4);
        put_rgb(b, f, g_array_index(m->poly_color, SceneColor, i));
        put_eol(b, f);
    }
    *len = b->len;
    return g_byte_array_free(b, FALSE);
}

gboolean scene_ply_save(const SceneMesh *m, const char *path, ScenePlyFormat f,
                        GError **err)
{
    gsize len;
    guchar *data = scene_ply_encode(m, f, &len);
    GError *e = NULL;
    gboolean ok = g_file_set_contents(path, (char *)data, (gssize)len, &e);
    g_free(data);
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", path, e->message);
        g_error_free(e);
    }
    return ok;
}
