/* sf_edit.c — edits of the hierarchy under sort-first and the max-set
 * match that carries bookkeeping across them (sf_edit.h; seed 000 §1.1,
 * §3.4.2-§3.4.3).
 */
#include "sim/workload/sortfirst/sf_edit_internal.h"
#include "sim/workload/sortfirst/sf_db_edit.h"
#include <math.h>
#include <string.h>

const char *const wl_sf_edit_names[] = {
    "matrix",      "execute",     "unpost",      "post",
    "create",      "add",         "close",       "prim_create",
    "prim_change", "prim_delete", "color",       "execute_add",
    "execute_delete", "delete",   NULL};
G_STATIC_ASSERT(G_N_ELEMENTS(wl_sf_edit_names) == WL_SF_ED_N + 1);

enum { MAX_EXEC_TRIES = 16 };

gboolean wl_sf_edit_any(const WlSfEditSpec *spec)
{
    for (int k = 0; k < WL_SF_ED_N; k++)
        if (spec->per_frame[k])
            return TRUE;
    return FALSE;
}

WlSfEdit *wl_sf_edit_new(const SceneDb *db, WlSfDb *sf,
                         const WlSfEditSpec *spec, SimRng *rng)
{
    WlSfEdit *e = g_new0(WlSfEdit, 1);
    e->db = scene_db_copy(db);
    e->sf = sf;
    e->spec = *spec;
    e->rng = rng;
    e->serial = g_array_new(FALSE, FALSE, sizeof(guint));
    e->unposted = g_array_new(FALSE, FALSE, sizeof(guint));
    e->open = WL_SF_NO_STRUCT;
    e->deleted = g_array_new(FALSE, TRUE, sizeof(guint8));
    e->dirty = g_array_new(FALSE, TRUE, sizeof(guint8));
    wl_sf_edit_tag_all(e);
    for (guint i = 0; i < scene_db_posted_count(db); i++, e->next_serial++)
        g_array_append_val(e->serial, e->next_serial);
    return e;
}

void wl_sf_edit_free(WlSfEdit *e)
{
    if (!e)
        return;
    scene_db_free(e->db);
    g_array_unref(e->serial);
    g_array_unref(e->unposted);
    g_array_unref(e->deleted);
    g_array_unref(e->dirty);
    g_free(e);
}

const SceneDb *wl_sf_edit_db(const WlSfEdit *e)
{
    return e->db;
}

const uint64_t *wl_sf_edit_applied(const WlSfEdit *e)
{
    return e->applied;
}

/* ---- the edits ------------------------------------------------------ */

GArray *wl_sf_edit_elements_of(const SceneDb *db, SceneElemKind kind)
{
    GArray *at = g_array_new(FALSE, FALSE, sizeof(guint) * 2);
    for (guint s = 0; s < scene_db_struct_count(db); s++)
        for (guint i = 0; i < scene_db_len(db, s); i++)
            if (scene_db_elem(db, s, i)->kind == kind) {
                guint sp[2] = {s, i};
                g_array_append_val(at, sp);
            }
    return at;
}

static gboolean edit_matrix(WlSfEdit *e)
{
    GArray *at = wl_sf_edit_elements_of(e->db, SCENE_EL_MATRIX);
    gboolean any = at->len > 0;
    if (any) {
        guint *sp = (guint *)(void *)at->data +
                    2 * sim_rng_below(e->rng, at->len);
        SceneElem m = *scene_db_elem(e->db, sp[0], sp[1]);
        double a = e->spec.angle_deg * G_PI / 180;
        m.matrix = mat4_mul(m.matrix, mat4_rotate(vec3(0, 1, 0), a));
        gboolean ok = scene_db_modify(e->db, sp[0], sp[1], &m, NULL);
        g_assert(ok);
    }
    g_array_unref(at);
    return any;
}

/* Points execute (sid, pos) at another structure of its child's height,
 * trying them from a random one on; FALSE if each closes a cycle. */
static gboolean retarget(WlSfEdit *e, const guint *height, guint sid,
                         guint pos)
{
    SceneElem x = *scene_db_elem(e->db, sid, pos);
    guint n = scene_db_struct_count(e->db), from = sim_rng_below(e->rng, n);
    guint old = x.child;
    for (guint k = 0; k < n; k++) {
        guint b = (from + k) % n;
        if (b == old || height[b] != height[old] ||
            (b < e->deleted->len && g_array_index(e->deleted, guint8, b)))
            continue;
        x.child = b;
        if (scene_db_modify(e->db, sid, pos, &x, NULL))
            return TRUE; /* else it closed a cycle: next */
    }
    return FALSE;
}

static gboolean edit_execute(WlSfEdit *e)
{
    GArray *at = wl_sf_edit_elements_of(e->db, SCENE_EL_EXECUTE);
    guint n = scene_db_struct_count(e->db);
    guint *height = g_new(guint, n + 1);
    for (guint s = 0; s < n; s++)
        height[s] = scene_db_height(e->db, s);
    gboolean done = FALSE;
    for (guint t = 0; !done && at->len && t < MAX_EXEC_TRIES; t++) {
        guint *sp = (guint *)(void *)at->data +
                    2 * sim_rng_below(e->rng, at->len);
        done = retarget(e, height, sp[0], sp[1]);
    }
    g_free(height);
    g_array_unref(at);
    return done;
}

static void unpost_at(WlSfEdit *e, guint i)
{
    guint sid = scene_db_posted_at(e->db, i);
    gboolean ok = scene_db_unpost(e->db, sid);
    g_assert(ok);
    g_array_remove_index(e->serial, i);
    g_array_append_val(e->unposted, sid);
}

static gboolean edit_unpost(WlSfEdit *e)
{
    guint n = scene_db_posted_count(e->db);
    if (!n)
        return FALSE;
    unpost_at(e, (guint)sim_rng_below(e->rng, n));
    return TRUE;
}

/* The last unposted structure, else a random one not posted. */
static gboolean edit_post(WlSfEdit *e)
{
    guint n = scene_db_struct_count(e->db), sid = n;
    if (e->unposted->len) {
        sid = g_array_index(e->unposted, guint, e->unposted->len - 1);
        g_array_set_size(e->unposted, e->unposted->len - 1);
    } else if (scene_db_posted_count(e->db) < n) {
        guint from = (guint)sim_rng_below(e->rng, n);
        for (guint k = 0; k < n && sid == n; k++) {
            guint b = (from + k) % n;
            if (!scene_db_is_posted(e->db, b) &&
                !(b < e->deleted->len && g_array_index(e->deleted, guint8, b)))
                sid = b;
        }
    }
    if (sid == n)
        return FALSE;
    scene_db_post(e->db, sid);
    g_array_append_val(e->serial, e->next_serial);
    e->next_serial++;
    return TRUE;
}

static gboolean edit_one(WlSfEdit *e, int kind)
{
    switch (kind) {
    case WL_SF_ED_MATRIX:
        return edit_matrix(e);
    case WL_SF_ED_EXECUTE:
        return edit_execute(e);
    case WL_SF_ED_UNPOST:
        return edit_unpost(e);
    case WL_SF_ED_POST:
        return edit_post(e);
    default:
        return wl_sf_edit_struct_one(e, kind);
    }
}

/* ---- matching the max-set trees -------------------------------------- */

/* Children of each node in execute order (CSR) and each node's ordinal
 * among its parent's children. */
typedef struct {
    guint *start, *kids, *ord;
} Kids;

static void kids_build(const GArray *nodes, Kids *k)
{
    guint n = nodes->len;
    k->start = g_new0(guint, n + 2);
    k->kids = g_new0(guint, n + 1);
    k->ord = g_new0(guint, n + 1);
    for (guint i = 0; i < n; i++) {
        gint p = g_array_index(nodes, SceneMaxNode, i).parent;
        if (p >= 0)
            k->ord[i] = k->start[p + 1]++;
    }
    for (guint i = 0; i < n; i++)
        k->start[i + 1] += k->start[i];
    for (guint i = 0; i < n; i++) {
        gint p = g_array_index(nodes, SceneMaxNode, i).parent;
        if (p >= 0)
            k->kids[k->start[p] + k->ord[i]] = i;
    }
}

static void kids_clear(Kids *k)
{
    g_free(k->start);
    g_free(k->kids);
    g_free(k->ord);
}

/* The old root of posting `serial`, or -1. */
static gint old_root(const GArray *nodes, const GArray *serial, guint want)
{
    guint r = 0;
    for (guint i = 0; i < nodes->len; i++) {
        if (g_array_index(nodes, SceneMaxNode, i).parent >= 0)
            continue;
        if (g_array_index(serial, guint, r++) == want)
            return (gint)i;
    }
    return -1;
}

/* The tag of the execute element that made each node (0 for a root):
 * a node's k-th child comes from its structure's k-th execute. */
static uint64_t *exec_tags(const SceneDb *db, const GArray *nodes)
{
    Kids k;
    kids_build(nodes, &k);
    uint64_t *tag = g_new0(uint64_t, nodes->len + 1);
    for (guint p = 0; p < nodes->len; p++) {
        guint sid = g_array_index(nodes, SceneMaxNode, p).sid, c = k.start[p];
        for (guint i = 0; i < scene_db_len(db, sid) && c < k.start[p + 1];
             i++) {
            const SceneElem *el = scene_db_elem(db, sid, i);
            if (el->kind == SCENE_EL_EXECUTE)
                tag[k.kids[c++]] = el->tag;
        }
    }
    kids_clear(&k);
    return tag;
}

/* The child of old node po made by the execute tagged `tag`, or -1. */
static gint old_child(const Kids *ko, const uint64_t *old_tag, guint po,
                      uint64_t tag)
{
    for (guint s = ko->start[po]; s < ko->start[po + 1]; s++)
        if (old_tag[ko->kids[s]] == tag)
            return (gint)ko->kids[s];
    return -1;
}

typedef struct {
    const GArray *nodes, *serial; /* max-set tree, postings of its roots */
    const uint64_t *tag;          /* exec_tags() */
} Tree;

/* match[n]: the old node new node n continues, or -1. */
static gint *match_nodes(const Tree *old, const Tree *now)
{
    Kids ko;
    kids_build(old->nodes, &ko);
    gint *match = g_new(gint, now->nodes->len + 1);
    guint root = 0;
    for (guint i = 0; i < now->nodes->len; i++) {
        const SceneMaxNode *n = &g_array_index(now->nodes, SceneMaxNode, i);
        gint o = -1;
        if (n->parent < 0)
            o = old_root(old->nodes, old->serial,
                         g_array_index(now->serial, guint, root++));
        else if (match[n->parent] >= 0)
            o = old_child(&ko, old->tag, (guint)match[n->parent],
                          now->tag[i]);
        if (o >= 0 && g_array_index(old->nodes, SceneMaxNode, o).sid != n->sid)
            o = -1;
        match[i] = o;
    }
    kids_clear(&ko);
    return match;
}

/* Each node's rank among the nodes of its structure (its instance
 * offset within each chunk of that structure). */
static guint *ranks(const GArray *nodes, guint n_structs)
{
    guint *seen = g_new0(guint, n_structs + 1);
    guint *rank = g_new0(guint, nodes->len + 1);
    for (guint i = 0; i < nodes->len; i++)
        rank[i] = seen[g_array_index(nodes, SceneMaxNode, i).sid]++;
    g_free(seen);
    return rank;
}

/* The chunks before the frame's edits. */
typedef struct {
    guint *first;       /* per old chunk: its first instance */
    guint n_structs;    /* structures then */
    const gint *old_of; /* per new chunk: the old one it continues, or -1
                           (NULL: the chunks were kept) */
} OldChunks;

/* Old instance number of every new instance (-1: new); counts nodes. */
static gint64 *instance_map(const WlSfDb *sf, const GArray *old,
                            const OldChunks *oc, const gint *match,
                            WlSfEditFrame *f)
{
    guint *rank = ranks(old, oc->n_structs);
    guint8 *kept = g_new0(guint8, old->len + 1);
    gint64 *map = g_new(gint64, wl_sf_n_insts(sf) + 1);
    for (guint i = 0; i < wl_sf_n_insts(sf); i++) {
        const WlSfInst *in = wl_sf_inst(sf, i);
        gint o = match[in->node];
        gint c = oc->old_of ? oc->old_of[in->chunk] : (gint)in->chunk;
        map[i] = o < 0 || c < 0 ? -1 : (gint64)(oc->first[c] + rank[o]);
    }
    for (guint n = 0; n < sf->nodes->len; n++) {
        f->nodes_created += match[n] < 0;
        if (match[n] >= 0)
            kept[match[n]] = 1;
    }
    for (guint o = 0; o < old->len; o++)
        f->nodes_collected += !kept[o];
    g_free(kept);
    g_free(rank);
    return map;
}

/* TRUE when a structure was made or dirtied this frame. */
static gboolean any_dirty(const WlSfEdit *e)
{
    if (scene_db_struct_count(e->db) != e->sf->n_structs)
        return TRUE;
    for (guint s = 0; s < e->dirty->len; s++)
        if (g_array_index(e->dirty, guint8, s))
            return TRUE;
    return FALSE;
}

/* Re-forms the chunks of dirty structures and carries the book's chunk
 * state over; NULL when no structure is dirty. */
static gint *rechunk(WlSfEdit *e, WlSfBook *b, const GArray *tags,
                     WlSfEditFrame *f)
{
    if (!any_dirty(e))
        return NULL;
    guint n_old = wl_sf_n_chunks(e->sf);
    g_array_set_size(e->dirty, scene_db_struct_count(e->db));
    WlSfRechunk rc = {0};
    gint *old_of = wl_sf_db_rechunk(e->sf, e->db, tags,
                                    (const guint8 *)(const void *)e->dirty->data,
                                    &rc);
    f->chunks_created = rc.created;
    f->chunks_dropped = rc.dropped;
    f->chunks_changed = rc.changed;
    wl_sf_book_remap_chunks(b, old_of, n_old);
    memset(e->dirty->data, 0, e->dirty->len);
    return old_of;
}

gint64 *wl_sf_edit_frame(WlSfEdit *e, WlSfBook *b, WlSfEditFrame *f,
                         WlSfRemapWork *w)
{
    gint64 *map = NULL;
    memset(f, 0, sizeof *f);
    GArray *old_serial = g_array_copy(e->serial);
    uint64_t *old_tag = exec_tags(e->db, e->sf->nodes);
    GArray *tags = wl_sf_db_prim_tags(e->sf, e->db);
    for (int k = 0; k < WL_SF_ED_N; k++)
        for (uint64_t i = 0; i < e->spec.per_frame[k]; i++)
            if (edit_one(e, k)) {
                e->applied[k]++;
                f->commands++;
            }
    if (f->commands) {
        GArray *old = g_array_ref(e->sf->nodes);
        guint nc = wl_sf_n_chunks(e->sf), n_old = wl_sf_n_insts(e->sf);
        OldChunks oc = {g_new(guint, nc + 1), e->sf->n_structs, NULL};
        for (guint c = 0; c < nc; c++)
            oc.first[c] = wl_sf_chunk(e->sf, c)->inst_first;
        gint *old_of = rechunk(e, b, tags, f);
        oc.old_of = old_of;
        gboolean ok = wl_sf_db_reinstance(e->sf, e->db, NULL);
        g_assert(ok); /* edits keep one matrix per structure's primitives */
        uint64_t *tag = exec_tags(e->db, e->sf->nodes);
        Tree was = {old, old_serial, old_tag}, now = {e->sf->nodes, e->serial,
                                                      tag};
        gint *match = match_nodes(&was, &now);
        map = instance_map(e->sf, old, &oc, match, f);
        wl_sf_book_remap(b, map, n_old, w);
        g_free(match);
        g_free(tag);
        g_free(old_of);
        g_free(oc.first);
        g_array_unref(old);
    }
    g_array_unref(tags);
    g_free(old_tag);
    g_array_unref(old_serial);
    return map;
}
