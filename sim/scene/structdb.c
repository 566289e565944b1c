/* structdb.c — the hierarchical structure database (see structdb.h).
 *
 * Structures live in a GPtrArray indexed by id; each keeps its elements in
 * a GArray of SceneElem whose vertex arrays it owns.  Invariants: the
 * execute graph is acyclic (checked on every execute added); every
 * execute names an existing structure; posted ids are distinct.
 * Bounding boxes are cached per structure, stamped with the database's
 * edit generation, so any edit invalidates every cache in O(1).
 * Sources: seed 001 (Ellsworth, Good, Tebbs 1990) §1.2, §3, §4; seed 000
 * (Mueller 1997) §3.3-3.4 for the min-set / max-set views and chunks.
 */
#include "sim/scene/structdb.h"
#include <string.h>

typedef struct {
    char *name;
    GArray *elems; /* SceneElem */
    int64_t end_delta;
    gboolean primitive;
    gboolean posted; /* in db->posted (O(1) post and is_posted) */
    SceneBox bbox;
    uint64_t bbox_gen; /* 0: never computed */
} SceneStruct;

struct SceneDb {
    GPtrArray *structs;  /* SceneStruct * */
    GHashTable *by_name; /* name -> id + 1 */
    GArray *posted;      /* guint */
    uint64_t gen;        /* bumped by every edit */
};

static const char *const kind_names[SCENE_EL_NKINDS] = {
    "triangle", "polygon", "tristrip",   "polygon2d",    "line",
    "sphere",   "color",   "matrix",     "execute",      "line_color",
    "sphere_color",
};

/* ---- elements ------------------------------------------------------- */

static SceneElem elem_blank(SceneElemKind k)
{
    SceneElem e;
    memset(&e, 0, sizeof e);
    e.kind = k;
    e.matrix = mat4_identity();
    return e;
}

SceneElem scene_elem_prim(SceneElemKind kind, const Vec3 *verts, guint nverts)
{
    g_assert(scene_elem_is_prim(kind));
    SceneElem e = elem_blank(kind);
    e.verts = (Vec3 *)verts;
    e.nverts = nverts;
    e.delta = kind == SCENE_EL_POLYGON2D ? 1 : 0;
    return e;
}

SceneElem scene_elem_kind_color(SceneElemKind kind, Vec3 rgb)
{
    g_assert(scene_elem_is_color(kind));
    SceneElem e = elem_blank(kind);
    e.color = rgb;
    return e;
}

gboolean scene_elem_is_color(SceneElemKind k)
{
    return k == SCENE_EL_COLOR || k == SCENE_EL_LINE_COLOR ||
           k == SCENE_EL_SPHERE_COLOR;
}

SceneElemKind scene_elem_color_of(SceneElemKind k)
{
    return k == SCENE_EL_LINE     ? SCENE_EL_LINE_COLOR
           : k == SCENE_EL_SPHERE ? SCENE_EL_SPHERE_COLOR
                                  : SCENE_EL_COLOR;
}

SceneElem scene_elem_color(Vec3 rgb)
{
    SceneElem e = elem_blank(SCENE_EL_COLOR);
    e.color = rgb;
    return e;
}

SceneElem scene_elem_matrix(Mat4 m, SceneMatMode mode)
{
    SceneElem e = elem_blank(SCENE_EL_MATRIX);
    e.matrix = m;
    e.mode = mode;
    return e;
}

SceneElem scene_elem_execute(guint child)
{
    SceneElem e = elem_blank(SCENE_EL_EXECUTE);
    e.child = child;
    return e;
}

gboolean scene_elem_is_prim(SceneElemKind k)
{
    return k <= SCENE_EL_SPHERE;
}

gboolean scene_elem_is_attr(SceneElemKind k)
{
    return scene_elem_is_color(k) || k == SCENE_EL_MATRIX;
}

const char *scene_elem_kind_name(SceneElemKind k)
{
    g_assert(k < SCENE_EL_NKINDS);
    return kind_names[k];
}

static SceneElem elem_dup(const SceneElem *e)
{
    SceneElem c = *e;
    c.verts = e->nverts ? g_memdup2(e->verts, e->nverts * sizeof(Vec3)) : NULL;
    return c;
}

/* ---- structures ----------------------------------------------------- */

static void struct_free(gpointer p)
{
    SceneStruct *s = p;
    for (guint i = 0; i < s->elems->len; i++)
        g_free(g_array_index(s->elems, SceneElem, i).verts);
    g_array_unref(s->elems);
    g_free(s->name);
    g_free(s);
}

static SceneStruct *get(const SceneDb *db, guint sid)
{
    g_assert(sid < db->structs->len);
    return g_ptr_array_index(db->structs, sid);
}

SceneDb *scene_db_new(void)
{
    SceneDb *db = g_new0(SceneDb, 1);
    db->structs = g_ptr_array_new_with_free_func(struct_free);
    db->by_name = g_hash_table_new(g_str_hash, g_str_equal);
    db->posted = g_array_new(FALSE, FALSE, sizeof(guint));
    db->gen = 1;
    return db;
}

void scene_db_free(SceneDb *db)
{
    if (!db)
        return;
    g_hash_table_unref(db->by_name);
    g_ptr_array_unref(db->structs);
    g_array_unref(db->posted);
    g_free(db);
}

SceneDb *scene_db_copy(const SceneDb *db)
{
    SceneDb *c = scene_db_new();
    for (guint i = 0; i < db->structs->len; i++) {
        const SceneStruct *s = get(db, i);
        guint id = scene_db_add_struct(c, s->name);
        SceneStruct *d = get(c, id);
        d->end_delta = s->end_delta;
        d->primitive = s->primitive;
        for (guint j = 0; j < s->elems->len; j++) {
            SceneElem e = elem_dup(&g_array_index(s->elems, SceneElem, j));
            g_array_append_val(d->elems, e);
        }
    }
    for (guint i = 0; i < db->posted->len; i++)
        scene_db_post(c, g_array_index(db->posted, guint, i));
    return c;
}

guint scene_db_add_struct(SceneDb *db, const char *name)
{
    g_assert(name);
    SceneStruct *s = g_new0(SceneStruct, 1);
    s->name = g_strdup(name);
    s->elems = g_array_new(FALSE, FALSE, sizeof(SceneElem));
    guint id = db->structs->len;
    g_ptr_array_add(db->structs, s);
    if (!g_hash_table_contains(db->by_name, s->name))
        g_hash_table_insert(db->by_name, s->name, GUINT_TO_POINTER(id + 1));
    return id;
}

guint scene_db_struct_count(const SceneDb *db)
{
    return db->structs->len;
}

const char *scene_db_struct_name(const SceneDb *db, guint sid)
{
    return get(db, sid)->name;
}

gboolean scene_db_find(const SceneDb *db, const char *name, guint *sid)
{
    gpointer v = g_hash_table_lookup(db->by_name, name);
    if (!v)
        return FALSE;
    *sid = GPOINTER_TO_UINT(v) - 1;
    return TRUE;
}

guint scene_db_len(const SceneDb *db, guint sid)
{
    return get(db, sid)->elems->len;
}

const SceneElem *scene_db_elem(const SceneDb *db, guint sid, guint pos)
{
    SceneStruct *s = get(db, sid);
    g_assert(pos < s->elems->len);
    return &g_array_index(s->elems, SceneElem, pos);
}

int64_t scene_db_end_delta(const SceneDb *db, guint sid)
{
    return get(db, sid)->end_delta;
}

void scene_db_set_end_delta(SceneDb *db, guint sid, int64_t d)
{
    get(db, sid)->end_delta = d;
}

void scene_db_set_delta(SceneDb *db, guint sid, guint pos, int64_t d)
{
    SceneStruct *s = get(db, sid);
    g_assert(pos < s->elems->len);
    g_array_index(s->elems, SceneElem, pos).delta = d;
}

void scene_db_set_tag(SceneDb *db, guint sid, guint pos, uint64_t tag)
{
    SceneStruct *s = get(db, sid);
    g_assert(pos < s->elems->len);
    g_array_index(s->elems, SceneElem, pos).tag = tag;
}

void scene_db_set_primitive(SceneDb *db, guint sid, gboolean on)
{
    get(db, sid)->primitive = on;
}

gboolean scene_db_is_primitive(const SceneDb *db, guint sid)
{
    return get(db, sid)->primitive;
}

/* ---- cycle check ------------------------------------------------------ */

typedef struct {
    guint sid, next; /* a structure on the search path, its next element */
} DfsFrame;

/* Depth-first search from `from` for `target` along executes, on an
 * explicit stack (a chain may be deeper than the C stack allows); on
 * success `path` holds the chain from `from` to `target`. */
static gboolean reaches(const SceneDb *db, guint from, guint target,
                        GArray *path, guint8 *seen)
{
    GArray *st = g_array_new(FALSE, FALSE, sizeof(DfsFrame));
    DfsFrame f0 = {from, 0};
    gboolean found = from == target;
    seen[from] = 1;
    g_array_append_val(st, f0);
    while (!found && st->len) {
        DfsFrame *f = &g_array_index(st, DfsFrame, st->len - 1);
        const SceneStruct *s = get(db, f->sid);
        while (f->next < s->elems->len &&
               g_array_index(s->elems, SceneElem, f->next).kind !=
                   SCENE_EL_EXECUTE)
            f->next++;
        if (f->next == s->elems->len) {
            g_array_set_size(st, st->len - 1);
            continue;
        }
        DfsFrame c = {g_array_index(s->elems, SceneElem, f->next++).child, 0};
        found = c.sid == target;
        if (found || !seen[c.sid]) {
            seen[c.sid] = 1;
            g_array_append_val(st, c);
        }
    }
    for (guint i = 0; found && i < st->len; i++)
        g_array_append_val(path, g_array_index(st, DfsFrame, i).sid);
    g_array_unref(st);
    return found;
}

static gboolean check_execute(const SceneDb *db, guint sid, const SceneElem *e,
                              GError **err)
{
    if (e->kind != SCENE_EL_EXECUTE)
        return TRUE;
    if (e->child >= db->structs->len) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "found execute of unknown structure %u in '%s', "
                    "expected an existing structure",
                    e->child, get(db, sid)->name);
        return FALSE;
    }
    GArray *path = g_array_new(FALSE, FALSE, sizeof(guint));
    guint8 *seen = g_new0(guint8, db->structs->len);
    gboolean cyc = reaches(db, e->child, sid, path, seen);
    if (cyc) {
        GString *s = g_string_new(get(db, sid)->name);
        for (guint i = 0; i < path->len; i++)
            g_string_append_printf(
                s, " -> %s", get(db, g_array_index(path, guint, i))->name);
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "found execute of '%s' in '%s' closing the cycle %s, "
                    "expected an acyclic structure network",
                    get(db, e->child)->name, get(db, sid)->name, s->str);
        g_string_free(s, TRUE);
    }
    g_free(seen);
    g_array_unref(path);
    return !cyc;
}

/* ---- edits ------------------------------------------------------------ */

gboolean scene_db_append(SceneDb *db, guint sid, const SceneElem *e,
                         GError **err)
{
    return scene_db_insert(db, sid, get(db, sid)->elems->len, e, err);
}

gboolean scene_db_insert(SceneDb *db, guint sid, guint pos, const SceneElem *e,
                         GError **err)
{
    SceneStruct *s = get(db, sid);
    g_assert(pos <= s->elems->len);
    g_assert(e->kind < SCENE_EL_NKINDS);
    if (!check_execute(db, sid, e, err))
        return FALSE;
    SceneElem c = elem_dup(e);
    g_array_insert_val(s->elems, pos, c);
    db->gen++;
    return TRUE;
}

gboolean scene_db_modify(SceneDb *db, guint sid, guint pos, const SceneElem *e,
                         GError **err)
{
    SceneStruct *s = get(db, sid);
    g_assert(pos < s->elems->len);
    SceneElem *old = &g_array_index(s->elems, SceneElem, pos);
    if (old->kind != e->kind) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "found modify of a %s element into a %s in '%s', "
                    "expected an element of the same kind",
                    kind_names[old->kind], kind_names[e->kind], s->name);
        return FALSE;
    }
    if (!check_execute(db, sid, e, err))
        return FALSE;
    SceneElem c = elem_dup(e); /* first: e may alias *old */
    g_free(old->verts);
    *old = c;
    db->gen++;
    return TRUE;
}

void scene_db_delete(SceneDb *db, guint sid, guint pos)
{
    SceneStruct *s = get(db, sid);
    g_assert(pos < s->elems->len);
    g_free(g_array_index(s->elems, SceneElem, pos).verts);
    g_array_remove_index(s->elems, pos);
    db->gen++;
}

/* ---- posting ---------------------------------------------------------- */

static gint posted_index(const SceneDb *db, guint sid)
{
    for (guint i = 0; i < db->posted->len; i++)
        if (g_array_index(db->posted, guint, i) == sid)
            return (gint)i;
    return -1;
}

void scene_db_post(SceneDb *db, guint sid)
{
    SceneStruct *s = get(db, sid);
    if (!s->posted)
        g_array_append_val(db->posted, sid);
    s->posted = TRUE;
}

gboolean scene_db_unpost(SceneDb *db, guint sid)
{
    gint i = scene_db_is_posted(db, sid) ? posted_index(db, sid) : -1;
    if (i < 0)
        return FALSE;
    g_array_remove_index(db->posted, (guint)i);
    get(db, sid)->posted = FALSE;
    return TRUE;
}

gboolean scene_db_is_posted(const SceneDb *db, guint sid)
{
    return sid < db->structs->len && get(db, sid)->posted;
}

guint scene_db_posted_count(const SceneDb *db)
{
    return db->posted->len;
}

guint scene_db_posted_at(const SceneDb *db, guint i)
{
    g_assert(i < db->posted->len);
    return g_array_index(db->posted, guint, i);
}

/* ---- traversal -------------------------------------------------------- */

/* The local matrix after a matrix element: REPLACE sets, CONCAT appends. */
static Mat4 local_after(Mat4 local, const SceneElem *e)
{
    return e->mode == SCENE_MAT_REPLACE ? e->matrix
                                        : mat4_mul(local, e->matrix);
}

typedef struct {
    const SceneDb *db;
    ScenePrimFn fn;
    void *ud;
    int64_t priority;
    guint instance; /* next max-set node number */
} Walk;

/* The inherited colour of each primitive type (fill, line, sphere). */
typedef struct {
    Vec3 c[3];
} Colours;

static guint colour_slot(SceneElemKind colour_kind)
{
    return colour_kind == SCENE_EL_LINE_COLOR     ? 1
           : colour_kind == SCENE_EL_SPHERE_COLOR ? 2
                                                  : 0;
}

static void walk(Walk *w, guint sid, Mat4 g, Colours col, guint depth)
{
    const SceneStruct *s = get(w->db, sid);
    Mat4 local = mat4_identity(), comp = g;
    guint inst = w->instance++;
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        w->priority += e->delta;
        if (scene_elem_is_color(e->kind)) {
            col.c[colour_slot(e->kind)] = e->color;
        } else if (e->kind == SCENE_EL_MATRIX) {
            local = local_after(local, e);
            comp = mat4_mul(g, local);
        } else if (e->kind == SCENE_EL_EXECUTE) {
            walk(w, e->child, comp, col, depth + 1);
        } else if (w->fn) {
            Vec3 c = col.c[colour_slot(scene_elem_color_of(e->kind))];
            ScenePrimInst pi = {sid, i, e, comp, c, w->priority, depth, inst};
            w->fn(&pi, w->ud);
        }
    }
    w->priority += s->end_delta;
}

void scene_db_traverse_from(const SceneDb *db, guint sid, Mat4 g, Vec3 color,
                            int64_t *priority, ScenePrimFn fn, void *ud)
{
    Walk w = {db, fn, ud, *priority, 0};
    walk(&w, sid, g, (Colours){{color, color, color}}, 1);
    *priority = w.priority;
}

void scene_db_traverse(const SceneDb *db, ScenePrimFn fn, void *ud)
{
    Walk w = {db, fn, ud, 0, 0};
    for (guint i = 0; i < db->posted->len; i++)
        walk(&w, g_array_index(db->posted, guint, i), mat4_identity(),
             (Colours){{vec3(1, 1, 1), vec3(1, 1, 1), vec3(1, 1, 1)}}, 1);
}

static void flatten_prim(const ScenePrimInst *pi, void *ud)
{
    SceneMesh *m = ud;
    const SceneElem *e = pi->el;
    uint32_t base = scene_mesh_n_vertices(m);
    if (e->nverts < 3)
        return; /* no area: nothing to draw */
    for (guint k = 0; k < e->nverts; k++) {
        Vec4 h = mat4_apply_point(pi->matrix, e->verts[k]);
        scene_mesh_add_vertex(m, vec3(h.x, h.y, h.z));
    }
    SceneColor c = {(float)pi->color.x, (float)pi->color.y, (float)pi->color.z};
    if (e->kind != SCENE_EL_TRISTRIP) {
        uint32_t *idx = g_new(uint32_t, e->nverts);
        for (guint k = 0; k < e->nverts; k++)
            idx[k] = base + k;
        scene_mesh_add_poly(m, idx, e->nverts, c, pi->sid);
        g_free(idx);
        return;
    }
    for (guint k = 0; k + 2 < e->nverts; k++) {
        uint32_t a = base + k, b = base + k + 1, d = base + k + 2;
        if (k % 2)
            scene_mesh_add_tri(m, b, a, d, c, pi->sid);
        else
            scene_mesh_add_tri(m, a, b, d, c, pi->sid);
    }
}

SceneMesh *scene_db_flatten(const SceneDb *db)
{
    SceneMesh *m = scene_mesh_new();
    scene_db_traverse(db, flatten_prim, m);
    return m;
}

/* ---- max-set and min-set views ---------------------------------------- */

static void maxset_walk(const SceneDb *db, GArray *out, guint sid, gint parent,
                        guint depth, Mat4 g)
{
    SceneMaxNode n = {sid, parent, depth, g};
    gint me = (gint)out->len;
    g_array_append_val(out, n);
    const SceneStruct *s = get(db, sid);
    Mat4 local = mat4_identity(), comp = g;
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        if (e->kind == SCENE_EL_MATRIX) {
            local = local_after(local, e);
            comp = mat4_mul(g, local);
        } else if (e->kind == SCENE_EL_EXECUTE) {
            maxset_walk(db, out, e->child, me, depth + 1, comp);
        }
    }
}

GArray *scene_db_maxset(const SceneDb *db)
{
    GArray *out = g_array_new(FALSE, FALSE, sizeof(SceneMaxNode));
    for (guint i = 0; i < db->posted->len; i++)
        maxset_walk(db, out, g_array_index(db->posted, guint, i), -1, 1,
                    mat4_identity());
    return out;
}

GArray *scene_db_children(const SceneDb *db, guint sid)
{
    const SceneStruct *s = get(db, sid);
    GArray *out = g_array_new(FALSE, FALSE, sizeof(guint));
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        if (e->kind != SCENE_EL_EXECUTE)
            continue;
        gboolean dup = FALSE;
        for (guint j = 0; j < out->len && !dup; j++)
            dup = g_array_index(out, guint, j) == e->child;
        if (!dup)
            g_array_append_val(out, e->child);
    }
    return out;
}

guint scene_db_execute_count(const SceneDb *db, guint sid, guint child)
{
    const SceneStruct *s = get(db, sid);
    guint n = 0;
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        n += e->kind == SCENE_EL_EXECUTE && e->child == child;
    }
    return n;
}

void scene_db_shape(const SceneDb *db, SceneDbShape *out)
{
    guint n = db->structs->len;
    guint *indeg = g_new0(guint, n), *depth = g_new0(guint, n);
    double *inst = g_new0(double, n);
    GArray *queue = g_array_new(FALSE, FALSE, sizeof(guint));
    memset(out, 0, sizeof *out);
    for (guint sid = 0; sid < n; sid++) {
        const SceneStruct *s = get(db, sid);
        for (guint i = 0; i < s->elems->len; i++) {
            const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
            indeg[e->child] += e->kind == SCENE_EL_EXECUTE;
        }
    }
    for (guint sid = 0; sid < n; sid++) {
        inst[sid] = indeg[sid] == 0 || get(db, sid)->posted;
        depth[sid] = 1;
        if (indeg[sid] == 0)
            g_array_append_val(queue, sid);
    }
    for (guint q = 0; q < queue->len; q++) { /* Kahn's topological order */
        guint sid = g_array_index(queue, guint, q);
        const SceneStruct *s = get(db, sid);
        out->instances += inst[sid];
        out->elements += inst[sid] * s->elems->len;
        if (depth[sid] > out->depth)
            out->depth = depth[sid], out->deepest = sid;
        for (guint i = 0; i < s->elems->len; i++) {
            const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
            if (e->kind != SCENE_EL_EXECUTE)
                continue;
            inst[e->child] += inst[sid];
            depth[e->child] = MAX(depth[e->child], depth[sid] + 1);
            if (--indeg[e->child] == 0)
                g_array_append_val(queue, e->child);
        }
    }
    g_array_unref(queue);
    g_free(indeg);
    g_free(depth);
    g_free(inst);
}

guint scene_db_height(const SceneDb *db, guint sid)
{
    const SceneStruct *s = get(db, sid);
    guint h = 0;
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        if (e->kind == SCENE_EL_EXECUTE) {
            guint c = scene_db_height(db, e->child);
            h = c > h ? c : h;
        }
    }
    return h + 1;
}

/* ---- bounding boxes --------------------------------------------------- */

static Vec3 apply3(Mat4 m, Vec3 p)
{
    Vec4 q = mat4_apply_point(m, p);
    double w = q.w != 0 ? q.w : 1.0;
    return vec3(q.x / w, q.y / w, q.z / w);
}

static void add_prim(SceneBox *b, const SceneElem *e, Mat4 local)
{
    if (e->kind == SCENE_EL_SPHERE && e->nverts >= 2) {
        double r = vec3_len(vec3_sub(e->verts[1], e->verts[0]));
        for (int k = 0; k < 8; k++) /* the box of the sphere, corners */
            *b = scene_box_add_point(
                *b, apply3(local, vec3_add(e->verts[0],
                                           vec3(k & 1 ? r : -r,
                                                k & 2 ? r : -r,
                                                k & 4 ? r : -r))));
        return;
    }
    for (guint v = 0; v < e->nverts; v++)
        *b = scene_box_add_point(*b, apply3(local, e->verts[v]));
}

SceneBox scene_db_struct_bbox(const SceneDb *db, guint sid)
{
    SceneStruct *s = get(db, sid);
    if (s->bbox_gen == db->gen)
        return s->bbox;
    SceneBox b = scene_box_empty();
    Mat4 local = mat4_identity();
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        if (e->kind == SCENE_EL_MATRIX)
            local = local_after(local, e);
        else if (e->kind == SCENE_EL_EXECUTE)
            b = scene_box_union(
                b,
                scene_box_transform(scene_db_struct_bbox(db, e->child), local));
        else if (scene_elem_is_prim(e->kind))
            add_prim(&b, e, local);
    }
    s->bbox = b;
    s->bbox_gen = db->gen;
    return b;
}

GArray *scene_db_chunk_bboxes(const SceneDb *db, guint sid, guint n)
{
    g_assert(n > 0);
    const SceneStruct *s = get(db, sid);
    GArray *out = g_array_new(FALSE, FALSE, sizeof(SceneBox));
    SceneBox b = scene_box_empty();
    Mat4 local = mat4_identity();
    guint in_chunk = 0;
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        if (e->kind == SCENE_EL_MATRIX)
            local = local_after(local, e);
        if (!scene_elem_is_prim(e->kind))
            continue;
        add_prim(&b, e, local);
        if (++in_chunk == n) {
            g_array_append_val(out, b);
            b = scene_box_empty();
            in_chunk = 0;
        }
    }
    if (in_chunk)
        g_array_append_val(out, b);
    return out;
}

/* ---- statistics ------------------------------------------------------- */

static void stats_walk(const SceneDb *db, guint sid, guint depth,
                       SceneDbStats *st, guint8 *seen)
{
    const SceneStruct *s = get(db, sid);
    st->instances++;
    st->depth = depth > st->depth ? depth : st->depth;
    if (!seen[sid]) {
        seen[sid] = 1;
        st->structures++;
        for (guint i = 0; i < s->elems->len; i++)
            st->min_primitives +=
                scene_elem_is_prim(g_array_index(s->elems, SceneElem, i).kind);
    }
    for (guint i = 0; i < s->elems->len; i++) {
        const SceneElem *e = &g_array_index(s->elems, SceneElem, i);
        if (scene_elem_is_prim(e->kind))
            st->primitives++;
        else if (scene_elem_is_attr(e->kind))
            st->attributes++;
        else {
            st->executes++;
            stats_walk(db, e->child, depth + 1, st, seen);
        }
    }
}

void scene_db_stats(const SceneDb *db, SceneDbStats *st)
{
    memset(st, 0, sizeof *st);
    guint8 *seen = g_new0(guint8, db->structs->len + 1);
    for (guint i = 0; i < db->posted->len; i++)
        stats_walk(db, g_array_index(db->posted, guint, i), 1, st, seen);
    g_free(seen);
}
