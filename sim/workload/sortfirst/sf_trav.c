/* sf_trav.c — §3.5 empty flags and bounding-volume culling, counted
 * (sf_trav.h; seed 000 §3.5).
 */
#include "sim/workload/sortfirst/sf_trav.h"

/* Per node and structure, bit masks over processors (P <= 64), so one
 * pass serves all of them. */
typedef struct {
    uint64_t *local; /* node: processors mastering or holding something */
    uint64_t *sflag; /* structure: processors mastering or holding a chunk */
    guint8 *on;      /* node: some chunk instance at it is in a region */
} Marks;

static void mark(const WlSfBook *b, Marks *m)
{
    const WlSfDb *d = b->db;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        uint64_t mine = wl_sf_bit(wl_sf_book_master(b, c));
        uint64_t data = mine | b->held_data[c];
        m->sflag[ch->sid] |= data;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            guint node = wl_sf_inst(d, i)->node;
            m->local[node] |=
                mine | (b->bk == WL_SF_MAXSET ? b->held_inst[i] : data);
            m->on[node] |= b->need[i] != 0;
        }
    }
}

/* Children after parents (pre-order): a reverse sweep carries each
 * node's marks up to every ancestor. */
static void up(const GArray *nodes, Marks *m)
{
    for (guint k = nodes->len; k-- > 0;) {
        gint parent = g_array_index(nodes, SceneMaxNode, k).parent;
        if (parent < 0)
            continue;
        m->local[parent] |= m->local[k];
        m->on[parent] |= m->on[k];
    }
}

/* Boxes of master and held chunks in culled subtrees. */
static void count_boxes(const WlSfBook *b, const Marks *m, WlSfTrav *t)
{
    const WlSfDb *d = b->db;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        uint64_t data = wl_sf_bit(wl_sf_book_master(b, c)) | b->held_data[c];
        guint holders = (guint)__builtin_popcountll(data);
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
            if (!m->on[wl_sf_inst(d, i)->node])
                t->boxes_culled += holders;
    }
}

void wl_sf_trav_count(const WlSfBook *b, WlSfTrav *t)
{
    const GArray *nodes = b->db->nodes;
    guint n = nodes->len, procs = b->regions.procs;
    Marks m = {g_new0(uint64_t, n + 1), g_new0(uint64_t, b->db->n_structs + 1),
               g_new0(guint8, n + 1)};
    mark(b, &m);
    up(nodes, &m);
    for (guint k = 0; k < n; k++) {
        guint sid = g_array_index(nodes, SceneMaxNode, k).sid;
        uint64_t flag = b->bk == WL_SF_MAXSET ? m.local[k] : m.sflag[sid];
        guint f = (guint)__builtin_popcountll(flag);
        t->plain += procs;
        t->flags += f;
        t->culled += m.on[k] ? procs : 0;
        t->both += m.on[k] ? f : 0;
    }
    count_boxes(b, &m, t);
    g_free(m.local);
    g_free(m.sflag);
    g_free(m.on);
}
