/* obj.c — Wavefront OBJ reading and writing.
 *
 * Implements obj.h.  A single pass over the text, one line at a time,
 * with a tokenizer that tracks columns (1-based, in bytes) so each error
 * names the offending token.  Relative indices resolve against the
 * counts seen so far, as the format specifies (Wavefront, "Object Files
 * (.obj)", Advanced Visualizer manual, appendix B1).  O(file size).
 */
#include "sim/scene/obj.h"
#include "sim/core/inputs.h"
#include "sim/core/datapath.h"
#include "sim/scene/scene_limits.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *name;
    int line;
    const char *line_start;
    const char *p, *end; /* cursor within the current line */
    SceneMesh *m;
    GArray *normals; /* Vec3 from vn */
    guint n_texcoords;
    guint tag;
    gboolean all_normals, any_face;
    GError **err;
} ObjParser;

static int col_of(const ObjParser *o, const char *at)
{
    return (int)(at - o->line_start) + 1;
}

static gboolean fail_at(ObjParser *o, const char *at, const char *found,
                        const char *expected)
{
    sim_error_located(o->err, o->name, o->line, col_of(o, at), found, expected);
    return FALSE;
}

/* Fails naming the token at `at` (up to whitespace, quoted). */
static gboolean fail_token(ObjParser *o, const char *at, const char *expected)
{
    const char *e = at;
    while (e < o->end && *e != ' ' && *e != '\t' && *e != '\r')
        e++;
    if (e == at)
        return fail_at(o, at, "end of line", expected);
    char *tok = g_strdup_printf("'%.*s'", (int)MIN(e - at, 40), at);
    fail_at(o, at, tok, expected);
    g_free(tok);
    return FALSE;
}

static void skip_space(ObjParser *o)
{
    while (o->p < o->end && (*o->p == ' ' || *o->p == '\t' || *o->p == '\r'))
        o->p++;
}

static gboolean at_end(ObjParser *o)
{
    skip_space(o);
    return o->p >= o->end || *o->p == '#';
}

/* One number token; a token too long for any number (64 bytes or more)
 * is refused whole rather than read in pieces. */
static gboolean read_double(ObjParser *o, double *out)
{
    skip_space(o);
    const char *start = o->p;
    while (o->p < o->end && *o->p != ' ' && *o->p != '\t' && *o->p != '\r')
        o->p++;
    gsize n = (gsize)(o->p - start);
    char buf[64], *endp;
    if (n == 0 || n >= sizeof buf)
        return fail_token(o, start, "a finite number");
    memcpy(buf, start, n);
    buf[n] = 0;
    *out = g_ascii_strtod(buf, &endp);
    if (*endp || !isfinite(*out))
        return fail_token(o, start, "a finite number");
    return TRUE;
}

/* Grows a to len elements, each new one a copy of *val. */
static void pad(GArray *a, guint len, const void *val)
{
    while (a->len < len)
        g_array_append_vals(a, val, 1);
}

static const SceneColor white = {1, 1, 1};
static const Vec3 zero3 = {0, 0, 0};

/* Fails at `at` unless ok: the value printed %g, the limit expected. */
static gboolean check_value(ObjParser *o, const char *at, gboolean ok,
                            const char *what, double v, const char *expected)
{
    if (ok)
        return TRUE;
    char *found = g_strdup_printf("%s %g", what, v);
    fail_at(o, at, found, expected);
    g_free(found);
    return FALSE;
}

static gboolean check_coords(ObjParser *o, const char *const *at,
                             const double *x, double w)
{
    char expected[96];
    g_snprintf(expected, sizeof expected,
               "a coordinate within +-%g (docs/config.md, Limits)",
               SCENE_COORD_MAX);
    for (int i = 0; i < 3; i++)
        if (!check_value(o, at[i], scene_coord_ok(x[i] / w),
                         w == 1.0 ? "a coordinate" : "a coordinate over w",
                         x[i] / w, expected))
            return FALSE;
    return TRUE;
}

static gboolean check_colors(ObjParser *o, const char *const *at,
                             const double *c)
{
    for (int i = 0; i < 3; i++)
        if (!check_value(o, at[i], scene_color_ok(c[i]), "a colour", c[i],
                         "a colour component in [0, 1]"))
            return FALSE;
    return TRUE;
}

static gboolean parse_v(ObjParser *o)
{
    double x[6]; /* at most 6 numbers: the 7th is refused before it is read */
    const char *at[6];
    int n = 0;
    while (!at_end(o)) {
        if (n == 6)
            return fail_token(o, o->p, "end of line after 3, 4 or 6 numbers");
        at[n] = o->p;
        if (!read_double(o, &x[n++]))
            return FALSE;
    }
    if (n < 3 || n == 5)
        return fail_token(o, o->p, "a vertex of 3, 4 or 6 numbers");
    double w = n == 4 ? x[3] : 1.0;
    if (w == 0)
        return fail_at(o, at[3], "w = 0", "a non-zero w");
    if (!check_coords(o, at, x, w) || (n == 6 && !check_colors(o, at + 3, x + 3)))
        return FALSE;
    scene_mesh_add_vertex(o->m, vec3(x[0] / w, x[1] / w, x[2] / w));
    if (n == 6) {
        SceneColor c = {(float)x[3], (float)x[4], (float)x[5]};
        pad(o->m->colors, o->m->pos->len - 1, &white);
        g_array_append_val(o->m->colors, c);
    }
    return TRUE;
}

static gboolean parse_vn(ObjParser *o)
{
    double x[3];
    const char *at[3];
    for (int i = 0; i < 3; i++)
        if (at_end(o))
            return fail_token(o, o->p, "3 numbers");
        else if (at[i] = o->p, !read_double(o, &x[i]))
            return FALSE;
    if (!at_end(o))
        return fail_token(o, o->p, "end of line");
    if (!check_coords(o, at, x, 1.0))
        return FALSE;
    Vec3 n = vec3_norm(vec3(x[0], x[1], x[2]));
    g_array_append_val(o->normals, n);
    return TRUE;
}

/* One index (may be negative) resolved against `count`; *out 0-based. */
static gboolean read_index(ObjParser *o, guint count, const char *what,
                           guint *out)
{
    const char *start = o->p;
    gboolean neg = o->p < o->end && *o->p == '-';
    if (neg)
        o->p++;
    guint64 v = 0;
    const char *digits = o->p;
    while (o->p < o->end && g_ascii_isdigit(*o->p) && v < G_MAXUINT32)
        v = v * 10 + (guint64)(*o->p++ - '0');
    if (o->p == digits || v == 0)
        return fail_token(o, start, "a non-zero integer index");
    gint64 idx = neg ? (gint64)count - (gint64)v : (gint64)v - 1;
    if (idx < 0 || idx >= (gint64)count) {
        char *exp = count ? g_strdup_printf("a %s index in 1..%u or -1..-%u",
                                            what, count, count)
                          : g_strdup_printf("no %s index (none defined "
                                            "above)",
                                            what);
        fail_token(o, start, exp);
        g_free(exp);
        return FALSE;
    }
    *out = (guint)idx;
    return TRUE;
}

/* v, v/vt, v//vn or v/vt/vn; *vn = G_MAXUINT when absent. */
static gboolean read_corner(ObjParser *o, guint *v, guint *vn)
{
    const char *start = o->p;
    guint vt;
    *vn = G_MAXUINT;
    if (!read_index(o, o->m->pos->len, "vertex", v))
        return FALSE;
    if (o->p < o->end && *o->p == '/') {
        o->p++;
        if (o->p < o->end && *o->p != '/' &&
            !read_index(o, o->n_texcoords, "texture", &vt))
            return FALSE;
        if (o->p < o->end && *o->p == '/') {
            o->p++;
            if (!read_index(o, o->normals->len, "normal", vn))
                return FALSE;
        }
    }
    if (o->p < o->end && *o->p != ' ' && *o->p != '\t' && *o->p != '\r' &&
        *o->p != '#')
        return fail_token(o, start, "a corner v, v/vt, v//vn or v/vt/vn");
    return TRUE;
}

static gboolean parse_f(ObjParser *o)
{
    GArray *idx = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    const char *start = o->line_start;
    gboolean ok = TRUE;
    while (ok && !at_end(o)) {
        guint v, vn;
        ok = read_corner(o, &v, &vn);
        if (!ok)
            break;
        g_array_append_val(idx, v);
        if (vn == G_MAXUINT) {
            o->all_normals = FALSE;
        } else {
            pad(o->m->normals, o->m->pos->len, &zero3);
            g_array_index(o->m->normals, Vec3, v) =
                g_array_index(o->normals, Vec3, vn);
        }
    }
    if (ok && idx->len < 3)
        ok = fail_at(o, start,
                     idx->len ? "a face of fewer than 3 corners"
                              : "an empty face",
                     "at least 3 corners");
    if (ok) {
        scene_mesh_add_poly(o->m, (uint32_t *)idx->data, idx->len,
                            scene_color(1, 1, 1), o->tag);
        o->any_face = TRUE;
    }
    g_array_free(idx, TRUE);
    return ok;
}

static gboolean parse_line(ObjParser *o)
{
    if (at_end(o))
        return TRUE;
    const char *kw = o->p;
    while (o->p < o->end && *o->p != ' ' && *o->p != '\t' && *o->p != '\r')
        o->p++;
    gsize n = (gsize)(o->p - kw);
    if (n == 1 && kw[0] == 'v')
        return parse_v(o);
    if (n == 2 && !strncmp(kw, "vn", 2))
        return parse_vn(o);
    if (n == 2 && !strncmp(kw, "vt", 2)) {
        o->n_texcoords++;
        return TRUE;
    }
    if (n == 1 && kw[0] == 'f')
        return parse_f(o);
    if (n == 1 && (kw[0] == 'o' || kw[0] == 'g') && o->any_face)
        o->tag++;
    return TRUE; /* l, p, s, usemtl, mtllib, unknown: skipped */
}

static void finish_arrays(ObjParser *o)
{
    SceneMesh *m = o->m;
    if (m->colors->len)
        pad(m->colors, m->pos->len, &white);
    if (!o->all_normals || !o->any_face)
        g_array_set_size(m->normals, 0);
    else
        pad(m->normals, m->pos->len, &zero3);
}

SceneMesh *scene_obj_parse(const char *text, gsize len, const char *name,
                           GError **err)
{
    ObjParser o = {name,
                   0,
                   text,
                   text,
                   text,
                   scene_mesh_new(),
                   g_array_new(FALSE, FALSE, sizeof(Vec3)),
                   0,
                   0,
                   TRUE,
                   FALSE,
                   err};
    const char *end = text + len;
    gboolean ok = TRUE;
    for (const char *s = text; ok && s < end;) {
        const char *nl = memchr(s, '\n', (size_t)(end - s));
        o.line++;
        o.line_start = o.p = s;
        o.end = nl ? nl : end;
        if (memchr(s, '\0', (size_t)(o.end - s)))
            ok = fail_at(&o, memchr(s, '\0', (size_t)(o.end - s)), "a NUL byte",
                         "text");
        else
            ok = parse_line(&o);
        s = nl ? nl + 1 : end;
    }
    g_array_free(o.normals, TRUE);
    if (!ok) {
        scene_mesh_free(o.m);
        return NULL;
    }
    finish_arrays(&o);
    return o.m;
}

SceneMesh *scene_obj_load(const char *path, GError **err)
{
    char *text;
    gsize len;
    if (!sim_file_read(path, &text, &len, err))
        return NULL;
    sim_inputs_note_bytes("mesh", path, text, len);
    SceneMesh *m = scene_obj_parse(text, len, path, err);
    g_free(text);
    return m;
}

static void put_num(GString *s, double x)
{
    char buf[G_ASCII_DTOSTR_BUF_SIZE];
    g_string_append_c(s, ' ');
    g_string_append(s, g_ascii_formatd(buf, sizeof buf, "%.17g", x));
}

char *scene_obj_to_string(const SceneMesh *m)
{
    GString *s = g_string_new("# pgsim OBJ\n");
    gboolean nrm = m->normals->len > 0, col = m->colors->len > 0;
    for (guint i = 0; i < m->pos->len; i++) {
        Vec3 p = scene_mesh_vertex(m, i);
        g_string_append_c(s, 'v');
        put_num(s, p.x);
        put_num(s, p.y);
        put_num(s, p.z);
        if (col) {
            SceneColor c = g_array_index(m->colors, SceneColor, i);
            put_num(s, c.r);
            put_num(s, c.g);
            put_num(s, c.b);
        }
        g_string_append_c(s, '\n');
    }
    for (guint i = 0; nrm && i < m->normals->len; i++) {
        Vec3 n = g_array_index(m->normals, Vec3, i);
        g_string_append(s, "vn");
        put_num(s, n.x);
        put_num(s, n.y);
        put_num(s, n.z);
        g_string_append_c(s, '\n');
    }
    for (guint i = 0; i < scene_mesh_n_polys(m); i++) {
        const uint32_t *v = scene_mesh_poly(m, i);
        g_string_append_c(s, 'f');
        for (guint k = 0; k < scene_mesh_poly_len(m, i); k++)
            if (nrm)
                g_string_append_printf(s, " %u//%u", v[k] + 1, v[k] + 1);
            else
                g_string_append_printf(s, " %u", v[k] + 1);
        g_string_append_c(s, '\n');
    }
    return g_string_free(s, FALSE);
}

gboolean scene_obj_save(const SceneMesh *m, const char *path, GError **err)
{
    char *text = scene_obj_to_string(m);
    GError *e = NULL;
    gboolean ok = g_file_set_contents(path, text, -1, &e);
    g_free(text);
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: %s", path, e->message);
        g_error_free(e);
    }
    return ok;
}
