/* sf_db_edit.c — chunks re-formed after edits, and the book's chunk
 * state carried over (sf_db_edit.h; seed 000 §3.3.1).
 */
#include "sim/workload/sortfirst/sf_db_edit.h"
#include "sim/workload/sortfirst/sf_bv.h"
#include <string.h>

GArray *wl_sf_db_prim_tags(const WlSfDb *d, const SceneDb *db)
{
    GArray *tags = g_array_sized_new(FALSE, FALSE, sizeof(uint64_t),
                                     d->prims->len);
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        for (guint k = 0; k < ch->n_prims; k++) {
            guint pos = g_array_index(d->prims, guint, ch->prim_first + k);
            uint64_t t = scene_db_elem(db, ch->sid, pos)->tag;
            g_array_append_val(tags, t);
        }
    }
    return tags;
}

/* A chunk being re-formed: its structure, primitive positions, the old
 * chunk it continues (-1: new) and its master. */
typedef struct {
    guint sid, master;
    gint old;
    GArray *pos; /* guint */
} Part;

static Vec3 centroid_of(const SceneElem *e)
{
    Vec3 s = vec3(0, 0, 0);
    for (guint k = 0; k < e->nverts; k++)
        s = vec3_add(s, e->verts[k]);
    return vec3_scale(s, 1.0 / e->nverts);
}

static gboolean chunked(const SceneElem *e)
{
    return scene_elem_is_prim(e->kind) && wl_sf_elem_polys(e) > 0;
}

static SceneBox part_box(const SceneDb *db, const Part *pt)
{
    SceneBox b = scene_box_empty();
    for (guint k = 0; k < pt->pos->len; k++) {
        const SceneElem *e =
            scene_db_elem(db, pt->sid, g_array_index(pt->pos, guint, k));
        for (guint v = 0; v < e->nverts; v++)
            b = scene_box_add_point(b, e->verts[v]);
    }
    return b;
}

typedef struct {
    WlSfDb *d;
    const SceneDb *db;
    const guint8 *dirty;
    GHashTable *where; /* tag -> position + 1, dirty structures' prims */
    uint64_t *keys;    /* the table's keys */
    GArray *parts;     /* Part */
} Re;

static void index_dirty(Re *re)
{
    guint n = 0;
    for (guint s = 0; s < scene_db_struct_count(re->db); s++)
        if (re->dirty[s])
            n += scene_db_len(re->db, s);
    re->keys = g_new(uint64_t, n + 1);
    re->where = g_hash_table_new(g_int64_hash, g_int64_equal);
    guint k = 0;
    for (guint s = 0; s < scene_db_struct_count(re->db); s++)
        for (guint i = 0; re->dirty[s] && i < scene_db_len(re->db, s); i++) {
            const SceneElem *e = scene_db_elem(re->db, s, i);
            if (!chunked(e))
                continue;
            re->keys[k] = e->tag;
            g_hash_table_insert(re->where, &re->keys[k++],
                                GUINT_TO_POINTER(i + 1));
        }
}

/* The old chunks: clean ones as they are, dirty ones with the
 * primitives still there; empty ones dropped. */
static void keep_old(Re *re, const GArray *tags, WlSfRechunk *rc)
{
    const WlSfDb *d = re->d;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        Part pt = {ch->sid, ch->master, (gint)c,
                   g_array_new(FALSE, FALSE, sizeof(guint))};
        for (guint k = 0; k < ch->n_prims; k++) {
            guint at = ch->prim_first + k, pos = g_array_index(d->prims, guint,
                                                             at);
            if (re->dirty[ch->sid]) {
                uint64_t t = g_array_index(tags, uint64_t, at);
                gpointer v = g_hash_table_lookup(re->where, &t);
                if (!v)
                    continue; /* deleted */
                g_hash_table_remove(re->where, &t);
                pos = GPOINTER_TO_UINT(v) - 1;
            }
            g_array_append_val(pt.pos, pos);
        }
        if (pt.pos->len) {
            g_array_append_val(re->parts, pt);
        } else {
            g_array_unref(pt.pos);
            rc->dropped++;
        }
    }
}

/* The chunk of sid with room nearest p, or a new one. */
static Part *home(Re *re, guint sid, Vec3 p, gboolean *fresh)
{
    Part *best = NULL;
    double bd = 0;
    for (guint k = 0; k < re->parts->len; k++) {
        Part *pt = &g_array_index(re->parts, Part, k);
        if (pt->sid != sid || pt->pos->len >= re->d->granularity)
            continue;
        Vec3 dv = vec3_sub(scene_box_center(part_box(re->db, pt)), p);
        double dd = vec3_dot(dv, dv);
        if (!best || dd < bd) {
            best = pt;
            bd = dd;
        }
    }
    *fresh = !best;
    if (!best) {
        Part pt = {sid, re->parts->len % re->d->procs, -1,
                   g_array_new(FALSE, FALSE, sizeof(guint))};
        g_array_append_val(re->parts, pt);
        best = &g_array_index(re->parts, Part, re->parts->len - 1);
    }
    return best;
}

/* New primitives of dirty structures that kept a chunk; *anew gets the
 * dirty structures with primitives and no chunk. */
static void place_new(Re *re, GArray *anew, WlSfRechunk *rc)
{
    guint ns = scene_db_struct_count(re->db);
    guint8 *has = g_new0(guint8, ns + 1);
    for (guint k = 0; k < re->parts->len; k++)
        has[g_array_index(re->parts, Part, k).sid] = 1;
    for (guint s = 0; s < ns; s++) {
        if (!re->dirty[s])
            continue;
        if (!has[s]) {
            g_array_append_val(anew, s);
            continue;
        }
        for (guint i = 0; i < scene_db_len(re->db, s); i++) {
            const SceneElem *e = scene_db_elem(re->db, s, i);
            if (!chunked(e) || !g_hash_table_contains(re->where, &e->tag))
                continue;
            gboolean fresh;
            Part *pt = home(re, s, centroid_of(e), &fresh);
            rc->created += fresh;
            g_array_append_val(pt->pos, i);
        }
    }
    g_free(has);
}

/* The parts as d's chunks; returns each one's old chunk. */
static gint *install(Re *re, WlSfRechunk *rc)
{
    WlSfDb *d = re->d;
    GArray *chunks = g_array_new(FALSE, FALSE, sizeof(WlSfChunk));
    GArray *prims = g_array_new(FALSE, FALSE, sizeof(guint));
    gint *old_of = g_new(gint, re->parts->len + 1);
    for (guint k = 0; k < re->parts->len; k++) {
        Part *pt = &g_array_index(re->parts, Part, k);
        WlSfChunk c = {.sid = pt->sid,
                       .prim_first = prims->len,
                       .n_prims = pt->pos->len,
                       .box = part_box(re->db, pt),
                       .master = pt->master};
        for (guint i = 0; i < pt->pos->len; i++) {
            guint pos = g_array_index(pt->pos, guint, i);
            c.polys += wl_sf_elem_polys(scene_db_elem(re->db, pt->sid, pos));
            g_array_append_val(prims, pos);
        }
        if (pt->old >= 0) {
            const WlSfChunk *was = wl_sf_chunk(d, (guint)pt->old);
            rc->changed += was->n_prims != c.n_prims || was->polys != c.polys ||
                           memcmp(&was->box, &c.box, sizeof c.box) != 0;
        }
        old_of[k] = pt->old;
        g_array_append_val(chunks, c);
        g_array_unref(pt->pos);
    }
    g_array_unref(d->chunks);
    g_array_unref(d->prims);
    d->chunks = chunks;
    d->prims = prims;
    return old_of;
}

gint *wl_sf_db_rechunk(WlSfDb *d, const SceneDb *db, const GArray *tags,
                       const guint8 *dirty, WlSfRechunk *rc)
{
    g_assert(tags->len == d->prims->len);
    Re re = {d, db, dirty, NULL, NULL, g_array_new(FALSE, FALSE, sizeof(Part))};
    index_dirty(&re);
    keep_old(&re, tags, rc);
    GArray *anew = g_array_new(FALSE, FALSE, sizeof(guint));
    place_new(&re, anew, rc);
    gint *old_of = install(&re, rc);
    guint kept = d->chunks->len;
    for (guint k = 0; k < anew->len; k++)
        wl_sf_db_chunk_struct(d, db, g_array_index(anew, guint, k));
    rc->created += d->chunks->len - kept;
    old_of = g_renew(gint, old_of, d->chunks->len + 1);
    for (guint c = kept; c < d->chunks->len; c++)
        old_of[c] = -1;
    d->min_prims = d->prims->len;
    d->n_structs = scene_db_struct_count(db);
    wl_sf_bv_build(d, db);
    g_array_unref(anew);
    g_hash_table_unref(re.where);
    g_free(re.keys);
    g_array_unref(re.parts);
    return old_of;
}

void wl_sf_book_remap_chunks(WlSfBook *b, const gint *old_of_new, guint n_old)
{
    guint nc = wl_sf_n_chunks(b->db);
    guint *master = g_new0(guint, nc + 1);
    uint64_t *held = g_new0(uint64_t, nc + 1), *mdata = g_new0(uint64_t, nc + 1);
    uint64_t *used = g_new0(uint64_t, nc + 1), *prev = g_new0(uint64_t, nc + 1);
    for (guint c = 0; c < nc; c++) {
        gint o = old_of_new[c];
        g_assert(o < (gint)n_old);
        if (o >= 0) {
            master[c] = b->master[o];
            held[c] = b->held_data[o];
            mdata[c] = b->master_data[o];
            used[c] = b->used[o];
            prev[c] = b->used_prev[o];
        } else {
            master[c] = wl_sf_chunk(b->db, c)->master;
            held[c] = mdata[c] = wl_sf_bit(master[c]);
        }
    }
    g_free(b->master);
    g_free(b->held_data);
    g_free(b->master_data);
    g_free(b->used);
    g_free(b->used_prev);
    b->master = master;
    b->held_data = held;
    b->master_data = mdata;
    b->used = used;
    b->used_prev = prev;
}
