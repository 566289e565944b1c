/* sf_edit_struct.c — the structure, primitive, colour and execute
 * add/delete edits of sort-first (sf_edit.h, kinds from `create` on;
 * seed 000 §1.1 operations, §3.3.1 volumes that grow and shrink, §3.4
 * "A executed an additional time", §3.4.2 max-set operations).
 *
 * Every element the editor makes gets a fresh tag (the chunks and the
 * max-set match follow elements by tag, sf_db_edit.c and sf_edit.c);
 * a structure whose elements are inserted, deleted or whose primitives
 * change is marked dirty, so its chunks are re-formed after the frame's
 * edits.  Cost of one edit: O(elements of the database) to pick it
 * (the candidates are listed afresh), plus the structure's length.
 */
#include "sim/workload/sortfirst/sf_edit_internal.h"
#include <math.h>

enum { MAX_EXEC_TRIES = 16 };

static guint8 *flag_at(GArray *flags, guint sid)
{
    if (sid >= flags->len)
        g_array_set_size(flags, sid + 1); /* zeroed: cleared array */
    return &g_array_index(flags, guint8, sid);
}

static gboolean deleted(const WlSfEdit *e, guint sid)
{
    return sid < e->deleted->len && g_array_index(e->deleted, guint8, sid);
}

static void dirty(WlSfEdit *e, guint sid)
{
    *flag_at(e->dirty, sid) = 1;
}

void wl_sf_edit_tag_all(WlSfEdit *e)
{
    for (guint s = 0; s < scene_db_struct_count(e->db); s++)
        for (guint i = 0; i < scene_db_len(e->db, s); i++)
            scene_db_set_tag(e->db, s, i, ++e->next_tag);
}

/* Every primitive that draws a polygon, as (structure, position). */
static GArray *prims_of(const SceneDb *db)
{
    GArray *at = g_array_new(FALSE, FALSE, sizeof(guint) * 2);
    for (guint s = 0; s < scene_db_struct_count(db); s++)
        for (guint i = 0; i < scene_db_len(db, s); i++) {
            const SceneElem *el = scene_db_elem(db, s, i);
            if (scene_elem_is_prim(el->kind) && el->nverts >= 3) {
                guint sp[2] = {s, i};
                g_array_append_val(at, sp);
            }
        }
    return at;
}

/* A random entry of a (structure, position) list; FALSE when empty. */
static gboolean pick(WlSfEdit *e, GArray *at, guint *sid, guint *pos)
{
    gboolean any = at->len > 0;
    if (any) {
        const guint *sp = (const guint *)(const void *)at->data +
                          2 * sim_rng_below(e->rng, at->len);
        *sid = sp[0];
        *pos = sp[1];
    }
    g_array_unref(at);
    return any;
}

static double signed_unit(WlSfEdit *e)
{
    return 2 * sim_rng_uniform(e->rng) - 1;
}

/* src's vertices scaled by `scale` about their centroid and moved by up
 * to `shift` times their extent (box diagonal) in a random direction:
 * a new array (g_free). */
static Vec3 *moved(WlSfEdit *e, const SceneElem *src, double scale,
                   double shift)
{
    Vec3 c = vec3(0, 0, 0);
    SceneBox b = scene_box_empty();
    for (guint k = 0; k < src->nverts; k++) {
        c = vec3_add(c, src->verts[k]);
        b = scene_box_add_point(b, src->verts[k]);
    }
    c = vec3_scale(c, 1.0 / src->nverts);
    Vec3 dir = vec3(signed_unit(e), signed_unit(e), signed_unit(e));
    double len = vec3_len(dir);
    dir = len > 0 ? vec3_scale(dir, 1 / len) : vec3(1, 0, 0);
    double by = shift * vec3_len(scene_box_size(b)) * sim_rng_uniform(e->rng);
    Vec3 d = vec3_scale(dir, by);
    Vec3 *v = g_new(Vec3, src->nverts);
    for (guint k = 0; k < src->nverts; k++)
        v[k] = vec3_add(vec3_add(c, vec3_scale(vec3_sub(src->verts[k], c),
                                               scale)),
                        d);
    return v;
}

/* Inserts a copy of primitive (from, at) moved by up to its extent into
 * sid at pos, with a fresh tag. */
static void insert_copy(WlSfEdit *e, guint from, guint at, guint sid,
                        guint pos)
{
    const SceneElem *src = scene_db_elem(e->db, from, at);
    Vec3 *v = moved(e, src, 1, 1);
    SceneElem el = scene_elem_prim(src->kind, v, src->nverts);
    el.tag = ++e->next_tag;
    gboolean ok = scene_db_insert(e->db, sid, pos, &el, NULL);
    g_assert(ok);
    g_free(v);
    dirty(e, sid);
}

static gboolean edit_create(WlSfEdit *e)
{
    char name[48];
    g_snprintf(name, sizeof name, "edit-created-%" G_GUINT64_FORMAT,
               e->applied[WL_SF_ED_CREATE]);
    e->open = scene_db_add_struct(e->db, name);
    *flag_at(e->deleted, e->open) = 0;
    dirty(e, e->open);
    return TRUE;
}

static gboolean edit_add(WlSfEdit *e)
{
    guint s, i;
    if (e->open == WL_SF_NO_STRUCT || !pick(e, prims_of(e->db), &s, &i))
        return FALSE;
    insert_copy(e, s, i, e->open, scene_db_len(e->db, e->open));
    return TRUE;
}

static gboolean edit_close(WlSfEdit *e)
{
    if (e->open == WL_SF_NO_STRUCT)
        return FALSE;
    e->open = WL_SF_NO_STRUCT;
    return TRUE;
}

/* After a primitive of its structure, so it shares their matrix. */
static gboolean edit_prim_create(WlSfEdit *e)
{
    guint s, i;
    if (!pick(e, prims_of(e->db), &s, &i))
        return FALSE;
    insert_copy(e, s, i, s, i + 1);
    return TRUE;
}

static gboolean edit_prim_change(WlSfEdit *e)
{
    guint s, i;
    if (!pick(e, prims_of(e->db), &s, &i))
        return FALSE;
    SceneElem el = *scene_db_elem(e->db, s, i);
    Vec3 *v = moved(e, &el, exp2(signed_unit(e)), 0.5);
    el.verts = v; /* the db copies it; tag kept */
    gboolean ok = scene_db_modify(e->db, s, i, &el, NULL);
    g_assert(ok);
    g_free(v);
    dirty(e, s);
    return TRUE;
}

static gboolean edit_prim_delete(WlSfEdit *e)
{
    guint s, i;
    if (!pick(e, prims_of(e->db), &s, &i))
        return FALSE;
    scene_db_delete(e->db, s, i);
    dirty(e, s);
    return TRUE;
}

static gboolean edit_color(WlSfEdit *e)
{
    guint s, i;
    if (!pick(e, wl_sf_edit_elements_of(e->db, SCENE_EL_COLOR), &s, &i))
        return FALSE;
    SceneElem el = *scene_db_elem(e->db, s, i);
    el.color = vec3(sim_rng_uniform(e->rng), sim_rng_uniform(e->rng),
                    sim_rng_uniform(e->rng));
    gboolean ok = scene_db_modify(e->db, s, i, &el, NULL);
    g_assert(ok);
    return TRUE;
}

/* A random structure not deleted, or WL_SF_NO_STRUCT. */
static guint live_struct(WlSfEdit *e)
{
    guint n = scene_db_struct_count(e->db);
    guint from = (guint)sim_rng_below(e->rng, n);
    for (guint k = 0; k < n; k++)
        if (!deleted(e, (from + k) % n))
            return (from + k) % n;
    return WL_SF_NO_STRUCT;
}

/* Appended (the parent's primitives keep their positions). */
static gboolean edit_exec_add(WlSfEdit *e)
{
    for (guint t = 0; t < MAX_EXEC_TRIES; t++) {
        guint parent = live_struct(e), child = live_struct(e);
        if (parent == WL_SF_NO_STRUCT)
            return FALSE;
        if (child == parent)
            continue;
        SceneElem x = scene_elem_execute(child);
        x.tag = ++e->next_tag;
        if (scene_db_append(e->db, parent, &x, NULL))
            return TRUE; /* else it closed a cycle: another pair */
    }
    return FALSE;
}

static gboolean edit_exec_delete(WlSfEdit *e)
{
    guint s, i;
    if (!pick(e, wl_sf_edit_elements_of(e->db, SCENE_EL_EXECUTE), &s, &i))
        return FALSE;
    scene_db_delete(e->db, s, i);
    dirty(e, s);
    return TRUE;
}

/* Forgets sid in the list of unposted structures. */
static void forget_unposted(WlSfEdit *e, guint sid)
{
    for (guint k = e->unposted->len; k-- > 0;)
        if (g_array_index(e->unposted, guint, k) == sid)
            g_array_remove_index(e->unposted, k);
}

/* A random structure neither posted nor executed (§3.4.2: deletion
 * "only affects the min-set ... you should only delete non-instanced
 * structures"). */
static gboolean edit_delete(WlSfEdit *e)
{
    guint n = scene_db_struct_count(e->db);
    guint8 *executed = g_new0(guint8, n);
    GArray *xs = wl_sf_edit_elements_of(e->db, SCENE_EL_EXECUTE);
    for (guint k = 0; k < xs->len; k++) {
        const guint *sp = (const guint *)(const void *)xs->data + 2 * k;
        executed[scene_db_elem(e->db, sp[0], sp[1])->child] = 1;
    }
    g_array_unref(xs);
    guint from = (guint)sim_rng_below(e->rng, n), sid = WL_SF_NO_STRUCT;
    for (guint k = 0; k < n && sid == WL_SF_NO_STRUCT; k++) {
        guint s = (from + k) % n;
        if (!executed[s] && !deleted(e, s) && !scene_db_is_posted(e->db, s))
            sid = s;
    }
    g_free(executed);
    if (sid == WL_SF_NO_STRUCT)
        return FALSE;
    forget_unposted(e, sid);
    for (guint i = scene_db_len(e->db, sid); i-- > 0;)
        scene_db_delete(e->db, sid, i);
    if (e->open == sid)
        e->open = WL_SF_NO_STRUCT;
    *flag_at(e->deleted, sid) = 1;
    dirty(e, sid);
    return TRUE;
}

gboolean wl_sf_edit_struct_one(WlSfEdit *e, int kind)
{
    switch (kind) {
    case WL_SF_ED_CREATE:
        return edit_create(e);
    case WL_SF_ED_ADD:
        return edit_add(e);
    case WL_SF_ED_CLOSE:
        return edit_close(e);
    case WL_SF_ED_PRIM_CREATE:
        return edit_prim_create(e);
    case WL_SF_ED_PRIM_CHANGE:
        return edit_prim_change(e);
    case WL_SF_ED_PRIM_DELETE:
        return edit_prim_delete(e);
    case WL_SF_ED_COLOR:
        return edit_color(e);
    case WL_SF_ED_EXEC_ADD:
        return edit_exec_add(e);
    case WL_SF_ED_EXEC_DELETE:
        return edit_exec_delete(e);
    default:
        g_assert(kind == WL_SF_ED_DELETE);
        return edit_delete(e);
    }
}
