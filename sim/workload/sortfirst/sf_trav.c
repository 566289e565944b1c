/* sf_trav.c — §3.5 empty flags and bounding-volume culling, counted
 * (sf_trav.h; seed 000 §3.5).
 */
#include "sim/workload/sortfirst/sf_trav.h"

typedef struct {
    guint n;
    guint8 *local;  /* node: p masters or holds something at it */
    guint8 *on;     /* node: some chunk instance at it is in a region */
    guint8 *sflag;  /* structure: p masters or holds one of its chunks */
} Marks;

/* Marks what p has and what is on screen at each node. */
static void mark(const WlSfBook *b, guint p, Marks *m)
{
    const WlSfDb *d = b->db;
    uint64_t me = wl_sf_bit(p);
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        gboolean mine = wl_sf_book_master(b, c) == p;
        gboolean data = mine || (b->held_data[c] & me);
        if (data)
            m->sflag[ch->sid] = 1;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            guint node = wl_sf_inst(d, i)->node;
            gboolean ptr = b->bk == WL_SF_MAXSET ? (b->held_inst[i] & me) != 0
                                                 : data;
            m->local[node] |= mine || ptr;
            m->on[node] |= b->need[i] != 0;
        }
    }
}

/* Children after parents (pre-order): a reverse sweep carries a flag up
 * to every ancestor. */
static void up(const GArray *nodes, guint8 *v)
{
    for (guint k = nodes->len; k-- > 0;) {
        gint parent = g_array_index(nodes, SceneMaxNode, k).parent;
        if (parent >= 0 && v[k])
            v[parent] = 1;
    }
}

static void count_boxes(const WlSfBook *b, guint p, const Marks *m,
                        WlSfTrav *t)
{
    const WlSfDb *d = b->db;
    uint64_t me = wl_sf_bit(p);
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        if (wl_sf_book_master(b, c) != p && !(b->held_data[c] & me))
            continue;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
            t->boxes_culled += !m->on[wl_sf_inst(d, i)->node];
    }
}

void wl_sf_trav_count(const WlSfBook *b, guint p, WlSfTrav *t)
{
    const GArray *nodes = b->db->nodes;
    guint n = nodes->len, ns = b->db->n_structs;
    Marks m = {n, g_new0(guint8, n + 1), g_new0(guint8, n + 1),
               g_new0(guint8, ns + 1)};
    mark(b, p, &m);
    up(nodes, m.local); /* hierarchical: something in the subtree */
    up(nodes, m.on);    /* the subtree's volume is on screen */
    for (guint k = 0; k < n; k++) {
        guint sid = g_array_index(nodes, SceneMaxNode, k).sid;
        gboolean flag = b->bk == WL_SF_MAXSET ? m.local[k] : m.sflag[sid];
        t->plain++;
        t->flags += flag;
        t->culled += m.on[k];
        t->both += flag && m.on[k];
    }
    count_boxes(b, p, &m, t);
    g_free(m.local);
    g_free(m.on);
    g_free(m.sflag);
}
