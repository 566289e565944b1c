/* sf_trav.c — §3.5 empty flags and bounding-volume culling, counted and
 * priced per processor (sf_trav.h; seed 000 §3.5).
 */
#include "sim/workload/sortfirst/sf_trav.h"
#include <string.h>

const char *const wl_sf_trav_names[] = {"plain", "flags", "culled",
                                        "flags_culled", NULL};

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
            guint node = wl_sf_inst_node(d, i);
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

enum { W_NODES, W_TESTS, W_MASTER, W_SLAVE };

/* Adds one to field `which` of each processor in bits (per may be
 * NULL); returns how many. */
static uint64_t add_bits(uint64_t bits, WlSfTravProc *per, int which)
{
    uint64_t n = (uint64_t)__builtin_popcountll(bits);
    for (guint q = 0; per && bits; q++, bits >>= 1) {
        if (!(bits & 1))
            continue;
        WlSfTravProc *w = &per[q];
        uint64_t *f = which == W_NODES    ? &w->nodes
                      : which == W_TESTS  ? &w->tests
                      : which == W_MASTER ? &w->master_culled
                                          : &w->slave_culled;
        (*f)++;
    }
    return n;
}

/* Boxes of master and slave chunks in culled subtrees: the holders the
 * book's sort would transform them for. */
static void count_boxes(const WlSfBook *b, const Marks *m, gboolean priced,
                        WlSfTrav *t, WlSfTravProc *per)
{
    const WlSfDb *d = b->db;
    WlSfTravProc *pp = priced ? per : NULL;
    for (guint c = 0; c < wl_sf_n_chunks(d); c++) {
        const WlSfChunk *ch = wl_sf_chunk(d, c);
        uint64_t mine = wl_sf_bit(wl_sf_book_master(b, c));
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            if (m->on[wl_sf_inst_node(d, i)])
                continue;
            uint64_t slaves = (b->bk == WL_SF_MAXSET ? b->held_inst[i]
                                                     : b->held_data[c]) &
                              ~mine;
            t->boxes_culled += add_bits(mine, pp, W_MASTER);
            t->boxes_culled += add_bits(slaves, pp, W_SLAVE);
        }
    }
}

/* Node k in the run's mode: the processors scanning it, and those
 * entering it for a volume test. */
static void node_work(const WlSfBook *b, const Marks *m, const SceneMaxNode *n,
                      guint k, WlSfTravMode mode, uint64_t *scan,
                      uint64_t *test)
{
    uint64_t all = b->regions.procs == 64 ? ~UINT64_C(0)
                                          : wl_sf_bit(b->regions.procs) - 1;
    gboolean maxset = b->bk == WL_SF_MAXSET;
    uint64_t flag = maxset ? m->local[k] : m->sflag[n->sid];
    gboolean entered = n->parent < 0 || m->on[n->parent];
    *scan = mode == WL_SF_TRAV_PLAIN    ? all
            : mode == WL_SF_TRAV_FLAGS  ? flag
            : mode == WL_SF_TRAV_CULLED ? (m->on[k] ? all : 0)
                                        : (m->on[k] ? flag : 0);
    *test = 0;
    if (mode == WL_SF_TRAV_CULLED && entered)
        *test = all;
    else if (mode == WL_SF_TRAV_BOTH && entered)
        *test = maxset ? m->local[k] : all;
}

void wl_sf_trav_count(const WlSfBook *b, WlSfTravMode mode, WlSfTrav *t,
                      WlSfTravProc *per)
{
    const GArray *nodes = b->db->nodes;
    guint n = nodes->len, procs = b->regions.procs;
    Marks m = {g_new0(uint64_t, n + 1), g_new0(uint64_t, b->db->n_structs + 1),
               g_new0(guint8, n + 1)};
    if (per)
        memset(per, 0, procs * sizeof *per);
    mark(b, &m);
    up(nodes, &m);
    for (guint k = 0; k < n; k++) {
        const SceneMaxNode *nd = &g_array_index(nodes, SceneMaxNode, k);
        uint64_t flag = b->bk == WL_SF_MAXSET ? m.local[k] : m.sflag[nd->sid];
        guint f = (guint)__builtin_popcountll(flag);
        t->plain += procs;
        t->flags += f;
        t->culled += m.on[k] ? procs : 0;
        t->both += m.on[k] ? f : 0;
        uint64_t scan, test;
        node_work(b, &m, nd, k, mode, &scan, &test);
        add_bits(scan, per, W_NODES);
        t->tests += add_bits(test, per, W_TESTS);
    }
    count_boxes(b, &m,
                mode == WL_SF_TRAV_CULLED || mode == WL_SF_TRAV_BOTH, t, per);
    g_free(m.local);
    g_free(m.sflag);
    g_free(m.on);
}
