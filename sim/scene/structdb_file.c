/* structdb_file.c — reading and writing the structure database file
 * format (structdb_file.h).
 */
#include "sim/scene/structdb_file.h"
#include "sim/core/inputs.h"
#include "sim/core/memlimit.h"
#include "sim/scene/scene_limits.h"
#include <math.h>
#include <string.h>

/* ---- reading --------------------------------------------------------------
 */

static gboolean bad(GError **err, const CfgNode *at, const char *expected)
{
    char *found = cfg_describe(at);
    cfg_error(err, at, found, expected);
    g_free(found);
    return FALSE;
}

static gboolean number(const CfgNode *n, double *out, GError **err)
{
    const char *s = cfg_scalar(n);
    char *end = NULL;
    if (s && *s) {
        *out = g_ascii_strtod(s, &end);
        if (end && *end == '\0' && isfinite(*out))
            return TRUE;
    }
    return bad(err, n, "a finite number");
}

/* A sequence of exactly `want` numbers. */
static gboolean numbers(const CfgNode *n, int want, double *out, GError **err)
{
    guint len = cfg_seq_len(n);
    if (cfg_kind(n) != CFG_SEQ || len != (guint)want) {
        char *exp = g_strdup_printf("a sequence of %d numbers", want);
        bad(err, n, exp);
        g_free(exp);
        return FALSE;
    }
    for (guint i = 0; i < len; i++)
        if (!number(cfg_seq_at(n, i), &out[i], err))
            return FALSE;
    return TRUE;
}

/* Vertices [[x, y, z], ...]: exactly `exact` when it is not 0 (3 for a
 * triangle, 2 for a line or a sphere's centre and surface point), else
 * at least 3. */
static Vec3 *vertices(const CfgNode *n, guint exact, guint *count,
                      GError **err)
{
    guint len = cfg_seq_len(n);
    if (cfg_kind(n) != CFG_SEQ || len < (exact ? exact : 3) ||
        (exact && len != exact)) {
        bad(err, n,
            exact == 3   ? "three vertices [[x, y, z], [x, y, z], [x, y, z]]"
            : exact == 2 ? "two vertices [[x, y, z], [x, y, z]] (a line's "
                           "ends; a sphere's centre and a surface point)"
                         : "a sequence of at least three [x, y, z] vertices");
        return NULL;
    }
    Vec3 *v = g_new(Vec3, len);
    for (guint i = 0; i < len; i++) {
        double xyz[3];
        if (!numbers(cfg_seq_at(n, i), 3, xyz, err)) {
            g_free(v);
            return NULL;
        }
        for (int k = 0; k < 3; k++)
            if (!scene_coord_ok(xyz[k])) {
                bad(err, cfg_seq_at(cfg_seq_at(n, i), (guint)k),
                    "a coordinate within +-1e15");
                g_free(v);
                return NULL;
            }
        v[i] = vec3(xyz[0], xyz[1], xyz[2]);
    }
    *count = len;
    return v;
}

static const char *const kind_keys[] = {
    "triangle", "polygon", "tristrip", "polygon2d",  "line",         "sphere",
    "color",    "matrix",  "execute",  "line_color", "sphere_color", NULL};
static const char *const modes[] = {"replace", "concat", NULL};

#define ELEM_KEYS                                                              \
    "one of triangle, polygon, tristrip, polygon2d, line, sphere, color, "     \
    "matrix, execute, line_color, sphere_color"

/* The element kind of map n: its one kind key (others: tag, mode). */
static gboolean elem_kind(const CfgNode *n, SceneElemKind *kind,
                          const CfgNode **val, GError **err)
{
    int found = -1;
    if (cfg_kind(n) != CFG_MAP)
        return bad(err, n, "an element map {" ELEM_KEYS ": ...}");
    for (int k = 0; kind_keys[k]; k++) {
        if (!cfg_has(n, kind_keys[k]))
            continue;
        if (found >= 0)
            return bad(err, cfg_get(n, kind_keys[k]),
                       "one element kind per list entry");
        found = k;
        *val = cfg_get(n, kind_keys[k]);
    }
    if (found < 0)
        return bad(err, n, "an element with a key " ELEM_KEYS);
    *kind = (SceneElemKind)found;
    return TRUE;
}

static gboolean prim_elem(const CfgNode *v, SceneElemKind kind, SceneElem *e,
                          GError **err)
{
    guint count = 0;
    guint exact = kind == SCENE_EL_TRIANGLE ? 3
                  : kind == SCENE_EL_LINE || kind == SCENE_EL_SPHERE ? 2
                                                                      : 0;
    Vec3 *verts = vertices(v, exact, &count, err);
    if (!verts)
        return FALSE;
    *e = scene_elem_prim(kind, verts, count);
    e->verts = verts; /* freed by the caller after the append copies it */
    return TRUE;
}

static gboolean matrix_elem(const CfgNode *n, const CfgNode *v, SceneElem *e,
                            GError **err)
{
    double m[16];
    int mode = SCENE_MAT_REPLACE;
    if (!numbers(v, 16, m, err) ||
        !cfg_get_enum(n, "mode", FALSE, modes, &mode, err))
        return FALSE;
    for (int k = 0; k < 16; k++)
        if (fabs(m[k]) > SCENE_COORD_MAX)
            return bad(err, cfg_seq_at(v, (guint)k),
                       "a matrix entry within +-1e15");
    Mat4 mat;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            mat.m[r][c] = m[r * 4 + c];
    *e = scene_elem_matrix(mat, (SceneMatMode)mode);
    return TRUE;
}

static gboolean other_elem(const SceneDb *db, const CfgNode *v,
                           SceneElemKind kind, SceneElem *e, GError **err)
{
    if (scene_elem_is_color(kind)) {
        double c[3];
        if (!numbers(v, 3, c, err))
            return FALSE;
        *e = scene_elem_kind_color(kind, vec3(c[0], c[1], c[2]));
        return TRUE;
    }
    guint child;
    const char *name = cfg_scalar(v);
    if (!name || !scene_db_find(db, name, &child))
        return bad(err, v, "the name of a structure in this file");
    *e = scene_elem_execute(child);
    return TRUE;
}

/* Appends element n to structure sid. */
static gboolean add_elem(SceneDb *db, guint sid, const CfgNode *n,
                         GError **err)
{
    SceneElemKind kind;
    const CfgNode *v = NULL;
    SceneElem e;
    int64_t tag = 0;
    if (!elem_kind(n, &kind, &v, err) ||
        !cfg_get_int(n, "tag", FALSE, 0, INT64_MAX, &tag, err))
        return FALSE;
    gboolean ok = scene_elem_is_prim(kind) ? prim_elem(v, kind, &e, err)
                  : kind == SCENE_EL_MATRIX ? matrix_elem(n, v, &e, err)
                                            : other_elem(db, v, kind, &e, err);
    if (!ok)
        return FALSE;
    if (!cfg_check_unused(n, err)) {
        if (scene_elem_is_prim(kind))
            g_free(e.verts);
        return FALSE;
    }
    e.tag = (uint64_t)tag;
    ok = scene_db_append(db, sid, &e, err);
    if (scene_elem_is_prim(kind))
        g_free(e.verts);
    if (!ok)
        g_prefix_error(err, "%s:%d:%d: ", cfg_file(v), cfg_line(v),
                       cfg_col(v));
    return ok;
}

/* First pass: every structure's name (unique), so executes may refer
 * forwards. */
static gboolean add_names(SceneDb *db, const CfgNode *list, GError **err)
{
    if (cfg_kind(list) != CFG_SEQ)
        return bad(err, list, "a sequence of structures {name, elements}");
    for (guint i = 0; i < cfg_seq_len(list); i++) {
        const CfgNode *s = cfg_seq_at(list, i);
        const char *name = NULL;
        guint dup;
        if (cfg_kind(s) != CFG_MAP)
            return bad(err, s, "a structure map {name, elements}");
        if (!cfg_get_str(s, "name", TRUE, &name, err))
            return FALSE;
        if (scene_db_find(db, name, &dup))
            return bad(err, cfg_get(s, "name"), "a name not used before");
        scene_db_add_struct(db, name);
    }
    return TRUE;
}

static gboolean add_elements(SceneDb *db, const CfgNode *list, GError **err)
{
    for (guint i = 0; i < cfg_seq_len(list); i++) {
        const CfgNode *s = cfg_seq_at(list, i);
        const CfgNode *els = NULL;
        gboolean prim = FALSE;
        if (!cfg_get_bool(s, "primitive", FALSE, &prim, err))
            return FALSE;
        scene_db_set_primitive(db, i, prim);
        els = cfg_get(s, "elements");
        if (!els)
            continue;
        if (cfg_kind(els) != CFG_SEQ)
            return bad(err, els, "a sequence of elements");
        for (guint k = 0; k < cfg_seq_len(els); k++)
            if (!add_elem(db, i, cfg_seq_at(els, k), err))
                return FALSE;
    }
    return TRUE;
}

static gboolean add_posted(SceneDb *db, const CfgNode *root, GError **err)
{
    const CfgNode *p = cfg_get(root, "posted");
    if (!p)
        return TRUE;
    if (cfg_kind(p) != CFG_SEQ)
        return bad(err, p, "a sequence of structure names");
    for (guint i = 0; i < cfg_seq_len(p); i++) {
        guint sid;
        const char *name = cfg_scalar(cfg_seq_at(p, i));
        if (!name || !scene_db_find(db, name, &sid))
            return bad(err, cfg_seq_at(p, i),
                       "the name of a structure in this file");
        scene_db_post(db, sid);
    }
    return TRUE;
}

/* The network can be walked and held: execute chains at most
 * SCENE_DB_DEPTH_MAX deep (the traversals recurse per level), shared
 * executes expanded within the memory limit, and posted structures'
 * boxes finite and within +-1e15 once their matrices are applied.  All
 * found before anything expands the network. */
static gboolean check_shape(const SceneDb *db, const CfgNode *root,
                            const CfgNode *list, GError **err)
{
    SceneDbShape sh;
    scene_db_shape(db, &sh);
    if (sh.depth > SCENE_DB_DEPTH_MAX) {
        char *found = g_strdup_printf("structure '%s' %u levels down an "
                                      "execute chain",
                                      scene_db_struct_name(db, sh.deepest),
                                      sh.depth);
        cfg_error(err, cfg_seq_at(list, sh.deepest), found,
                  "at most 256 levels of executes");
        g_free(found);
        return FALSE;
    }
    const CfgNode *at = cfg_has(root, "posted") ? cfg_get(root, "posted") : list;
    char *where = g_strdup_printf("%s:%d:%d", cfg_file(at), cfg_line(at),
                                  cfg_col(at));
    char *what = g_strdup_printf("a network of %.3g structure instances and "
                                 "%.3g element instances (executes expanded)",
                                 sh.instances, sh.elements);
    gboolean ok = sim_mem_check(sh.elements * SCENE_POLY_BYTES, where, what,
                                err);
    g_free(where);
    g_free(what);
    for (guint i = 0; ok && i < scene_db_posted_count(db); i++) {
        SceneBox b = scene_db_struct_bbox(db, scene_db_posted_at(db, i));
        if (!scene_box_is_empty(b) &&
            !(scene_coord_ok(b.min.x) && scene_coord_ok(b.min.y) &&
              scene_coord_ok(b.min.z) && scene_coord_ok(b.max.x) &&
              scene_coord_ok(b.max.y) && scene_coord_ok(b.max.z)))
            ok = bad(err, cfg_seq_at(at, i),
                     "a posted structure whose matrices keep its "
                     "coordinates within +-1e15");
    }
    return ok;
}

SceneDb *scene_db_from_cfg(const CfgNode *root, GError **err)
{
    int64_t version = 0;
    if (cfg_kind(root) != CFG_MAP) {
        bad(err, root, "a map {structure_database: 1, structures, posted}");
        return NULL;
    }
    if (!cfg_get_int(root, "structure_database", TRUE, INT64_MIN, INT64_MAX,
                     &version, err))
        return NULL;
    if (version != 1) {
        bad(err, cfg_get(root, "structure_database"),
            "structure_database: 1 (the format's only version)");
        return NULL;
    }
    const CfgNode *list = cfg_get(root, "structures");
    if (!list) {
        bad(err, root, "a key 'structures'");
        return NULL;
    }
    SceneDb *db = scene_db_new();
    if (add_names(db, list, err) && add_elements(db, list, err) &&
        add_posted(db, root, err) && cfg_check_unused(root, err) &&
        check_shape(db, root, list, err))
        return db;
    scene_db_free(db);
    return NULL;
}

SceneDb *scene_db_load(const char *path, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return NULL;
    sim_inputs_note_file("database", path);
    SceneDb *db = scene_db_from_cfg(root, err);
    cfg_free(root);
    return db;
}

/* ---- writing --------------------------------------------------------------
 */

static void put_num(GString *s, double v)
{
    char buf[G_ASCII_DTOSTR_BUF_SIZE];
    g_string_append(s, g_ascii_formatd(buf, sizeof buf, "%.17g", v));
}

static void put_vec(GString *s, Vec3 v)
{
    g_string_append_c(s, '[');
    put_num(s, v.x);
    g_string_append(s, ", ");
    put_num(s, v.y);
    g_string_append(s, ", ");
    put_num(s, v.z);
    g_string_append_c(s, ']');
}

static void put_prim(GString *s, const SceneElem *e)
{
    g_string_append_printf(s, "{%s: [", kind_keys[e->kind]);
    for (guint i = 0; i < e->nverts; i++) {
        if (i)
            g_string_append(s, ", ");
        put_vec(s, e->verts[i]);
    }
    g_string_append_c(s, ']');
}

static void put_matrix(GString *s, const SceneElem *e)
{
    g_string_append(s, "{matrix: [");
    for (int k = 0; k < 16; k++) {
        if (k)
            g_string_append(s, ", ");
        put_num(s, e->matrix.m[k / 4][k % 4]);
    }
    g_string_append_printf(s, "], mode: %s", modes[e->mode]);
}

/* A YAML scalar for a name: double-quoted, with " and \ escaped and
 * every control byte written as \xHH (a raw line break inside double
 * quotes would fold to a space when read back). */
static void put_name(GString *s, const char *name)
{
    g_string_append_c(s, '"');
    for (const unsigned char *c = (const unsigned char *)name; *c; c++) {
        if (*c < 0x20 || *c == 0x7f)
            g_string_append_printf(s, "\\x%02x", *c);
        else if (*c == '"' || *c == '\\')
            g_string_append_printf(s, "\\%c", *c);
        else
            g_string_append_c(s, (char)*c);
    }
    g_string_append_c(s, '"');
}

static void put_elem(GString *s, const SceneDb *db, const SceneElem *e)
{
    g_string_append(s, "      - ");
    if (scene_elem_is_prim(e->kind))
        put_prim(s, e);
    else if (e->kind == SCENE_EL_MATRIX)
        put_matrix(s, e);
    else if (scene_elem_is_color(e->kind)) {
        g_string_append_printf(s, "{%s: ", kind_keys[e->kind]);
        put_vec(s, e->color);
    } else {
        g_string_append(s, "{execute: ");
        put_name(s, scene_db_struct_name(db, e->child));
    }
    if (e->tag)
        g_string_append_printf(s, ", tag: %" G_GUINT64_FORMAT,
                               (guint64)e->tag);
    g_string_append(s, "}\n");
}

GString *scene_db_to_yaml(const SceneDb *db)
{
    GString *s = g_string_new("structure_database: 1\nstructures:");
    g_string_append(s, scene_db_struct_count(db) ? "\n" : " []\n");
    for (guint sid = 0; sid < scene_db_struct_count(db); sid++) {
        g_string_append(s, "  - name: ");
        put_name(s, scene_db_struct_name(db, sid));
        g_string_append_c(s, '\n');
        if (scene_db_is_primitive(db, sid))
            g_string_append(s, "    primitive: true\n");
        g_string_append(s, "    elements:");
        g_string_append(s, scene_db_len(db, sid) ? "\n" : " []\n");
        for (guint k = 0; k < scene_db_len(db, sid); k++)
            put_elem(s, db, scene_db_elem(db, sid, k));
    }
    g_string_append(s, "posted: [");
    for (guint i = 0; i < scene_db_posted_count(db); i++) {
        if (i)
            g_string_append(s, ", ");
        put_name(s, scene_db_struct_name(db, scene_db_posted_at(db, i)));
    }
    g_string_append(s, "]\n");
    return s;
}

gboolean scene_db_save(const SceneDb *db, const char *path, GError **err)
{
    GString *s = scene_db_to_yaml(db);
    GError *e = NULL;
    gboolean ok = g_file_set_contents(path, s->str, (gssize)s->len, &e);
    if (!ok) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found an unwritable path (%s), expected a "
                    "writable file",
                    path, e->message);
        g_error_free(e);
    }
    g_string_free(s, TRUE);
    return ok;
}
