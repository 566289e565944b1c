/* sf_mastership.c — redistribution of off-screen master chunks under
 * dynamic mastership (sf_book.h; seed 000 §3.3.2.1: "dynamic mastership
 * exhibits the off-screen primitive problem, where master primitive
 * chunks accumulate at processors rendering the screen edges and thus
 * require redistribution"; issue 37 point 4).
 *
 * After every processor's sort of a frame (push, `mastership: dynamic`,
 * `offscreen: spread`), the off-screen master polygons of each
 * processor (chunks with no instance in any region) are made even: in
 * chunk order, an off-screen chunk whose master holds more than
 * (1 + WL_SF_SPREAD_SLACK) times the mean goes to the processor holding
 * the fewest, if that one stays within the same bound; it rides on the
 * frame's exchange as a handover (bytes.mastership, max-set with every
 * instance pointer and its vector, as a dynamic handover) plus the
 * chunk's data (bytes.chunk + bytes.triangle per polygon, packed by the
 * old master and unpacked by the new one, chunk_pack per polygon) when
 * the new master holds no copy; the old master deletes its copy.  The
 * decision reads every master's off-screen count, which each processor
 * knows from its own bucket sort of its master chunks; we take the
 * counts as exchanged at no cost (8 B in messages that go anyway: an
 * assumption).  Cost O(P + chunks + instances moved) per frame.
 */
#include "sim/workload/sortfirst/sf_book.h"

/* Our tolerance: a master's off-screen polygons may exceed the mean by
 * 10 % before chunks move (an assumption, not from the paper). */
#define WL_SF_SPREAD_SLACK 0.1

const char *const wl_sf_offscreen_names[] = {"keep", "spread", NULL};

static gboolean offscreen(const WlSfBook *b, const WlSfChunk *ch)
{
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
        if (b->need[i])
            return FALSE;
    return TRUE;
}

/* Chunk c's mastership and, when q lacks it, its data from m to q. */
static void move(WlSfBook *b, guint c, guint m, guint q, WlSfBatch *bt,
                 WlSfBookWork *w)
{
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    uint64_t me = wl_sf_bit(m), vec = (b->regions.procs + 7) / 8;
    uint64_t bytes = b->sizes.mastership;
    if (!(b->held_data[c] & wl_sf_bit(q))) {
        guint hint = ch->inst_first; /* none is on screen */
        g_array_append_val(bt->chunks, c);
        if (b->bk == WL_SF_MINSET)
            g_array_append_val(bt->insts, hint);
        bt->polys += ch->polys;
        bytes += b->sizes.chunk + ch->polys * b->sizes.triangle;
        w->sent_chunks++;
        w->sent_polys += ch->polys;
    }
    g_array_append_val(bt->masters, c);
    if (b->bk == WL_SF_MAXSET)
        bytes += ch->n_inst * (b->sizes.instance + vec);
    bt->bytes += bytes;
    w->sent_bytes += bytes;
    b->held_data[c] &= ~me;
    b->master_data[c] &= ~me;
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
        b->held_inst[i] &= ~me;
        b->master_inst[i] &= ~me;
    }
    w->spread++;
    w->deleted_chunks++;
}

static guint fewest(const uint64_t *off, guint procs)
{
    guint q = 0;
    for (guint p = 1; p < procs; p++)
        if (off[p] < off[q])
            q = p;
    return q;
}

void wl_sf_book_spread(WlSfBook *b, WlSfBatch *const *out,
                       WlSfBookWork *const *w)
{
    guint procs = b->regions.procs, nc = wl_sf_n_chunks(b->db);
    uint64_t off[WL_SF_MAX_PROCS] = {0}, total = 0;
    guint8 *is_off = g_new0(guint8, MAX(nc, 1));
    for (guint c = 0; c < nc; c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        /* a chunk handed over this frame left its master's copy */
        if (!(b->held_data[c] & wl_sf_bit(b->master[c])) || !offscreen(b, ch))
            continue;
        is_off[c] = 1;
        off[b->master[c]] += ch->polys;
        total += ch->polys;
    }
    double bound = (1 + WL_SF_SPREAD_SLACK) * (double)total / procs;
    for (guint c = 0; c < nc; c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        guint m = b->master[c], q = fewest(off, procs);
        if (!is_off[c] || (double)off[m] <= bound || q == m ||
            (double)(off[q] + ch->polys) > bound)
            continue;
        move(b, c, m, q, &out[m][q], w[m]);
        off[m] -= ch->polys;
        off[q] += ch->polys;
    }
    g_free(is_off);
}
