/* sf_book.c — min-set and max-set bookkeeping (sf_book.h; seed 000
 * §3.3.2.1 push communication with fixed masters, §3.3.2.3 arriving
 * primitives, §3.4.2-§3.4.4 max-set operations, traversal, migration).
 * Per-chunk and per-instance arrays hold exactly one element each, so a
 * read past the end is a memory error the sanitizer build reports (NULL
 * when there is none: never read then; used, used_prev and fresh, which
 * memcpy and memset take, at least one).
 */
#include "sim/workload/sortfirst/sf_book.h"
#include "sim/workload/sortfirst/sf_bv.h"
#include <string.h>

const char *const wl_sf_bookkeeping_names[] = {"minset", "maxset", NULL};
const char *const wl_sf_migration_names[] = {"push", "pull", NULL};
const char *const wl_sf_mastership_names[] = {"fixed", "dynamic", NULL};

void wl_sf_batch_init(WlSfBatch *bt)
{
    memset(bt, 0, sizeof *bt);
    bt->chunks = g_array_new(FALSE, FALSE, sizeof(guint));
    bt->insts = g_array_new(FALSE, FALSE, sizeof(guint));
    bt->masters = g_array_new(FALSE, FALSE, sizeof(guint));
}

void wl_sf_batch_clear(WlSfBatch *bt)
{
    if (bt->chunks)
        g_array_unref(bt->chunks);
    if (bt->insts)
        g_array_unref(bt->insts);
    if (bt->masters)
        g_array_unref(bt->masters);
    memset(bt, 0, sizeof *bt);
}

static void batch_reset(WlSfBatch *bt, guint src, guint dst, const WlSfSizes *s)
{
    g_array_set_size(bt->chunks, 0);
    g_array_set_size(bt->insts, 0);
    g_array_set_size(bt->masters, 0);
    bt->src = src;
    bt->dst = dst;
    bt->polys = 0;
    bt->bytes = s->message;
}

WlSfBook *wl_sf_book_new(const WlSfDb *db, const WlSfRegions *regions,
                         WlSfBookkeeping bk, const WlSfSizes *sizes)
{
    WlSfBook *b = g_new0(WlSfBook, 1);
    guint nc = wl_sf_n_chunks(db), ni = wl_sf_n_insts(db);
    b->db = db;
    b->regions = *regions;
    b->bk = bk;
    b->sizes = *sizes;
    b->need = g_new0(uint64_t, ni);
    b->held_inst = g_new0(uint64_t, ni);
    b->master_inst = g_new0(uint64_t, ni);
    b->held_data = g_new0(uint64_t, nc);
    b->master_data = g_new0(uint64_t, nc);
    b->master = g_new0(guint, nc);
    b->used = g_new0(uint64_t, MAX(nc, 1));
    b->used_prev = g_new0(uint64_t, MAX(nc, 1));
    b->fresh = g_new0(guint8, MAX(ni, 1));
    for (guint c = 0; c < nc; c++) {
        const WlSfChunk *ch = wl_sf_chunk(db, c);
        b->master[c] = ch->master;
        uint64_t m = wl_sf_bit(ch->master);
        b->held_data[c] = b->master_data[c] = m;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
            b->held_inst[i] = b->master_inst[i] = m;
    }
    return b;
}

void wl_sf_book_free(WlSfBook *b)
{
    if (!b)
        return;
    g_free(b->need);
    g_free(b->held_inst);
    g_free(b->master_inst);
    g_free(b->held_data);
    g_free(b->master_data);
    g_free(b->master);
    g_free(b->used);
    g_free(b->used_prev);
    g_free(b->fresh);
    g_free(b);
}

void wl_sf_book_set_policy(WlSfBook *b, WlSfMigration mig, WlSfMastership ms)
{
    g_assert(mig == WL_SF_PUSH || (b->bk == WL_SF_MINSET && ms == WL_SF_FIXED));
    b->mig = mig;
    b->ms = ms;
}

void wl_sf_book_screens(const WlSfBook *b, Mat4 view_proj, WlSfScreen *out)
{
    for (guint i = 0; i < wl_sf_n_insts(b->db); i++) {
        const WlSfInst *in = wl_sf_inst(b->db, i);
        out[i] = wl_sf_bv_screen(b->db, &b->regions, in->chunk,
                                 mat4_mul(view_proj, in->matrix));
    }
}

void wl_sf_book_need(WlSfBook *b, Mat4 view_proj)
{
    WlSfScreen *scr = g_new(WlSfScreen, wl_sf_n_insts(b->db));
    wl_sf_book_screens(b, view_proj, scr);
    wl_sf_book_need_from(b, scr);
    g_free(scr);
}

void wl_sf_book_need_from(WlSfBook *b, const WlSfScreen *scr)
{
    guint nc = wl_sf_n_chunks(b->db);
    memcpy(b->used_prev, b->used, nc * sizeof *b->used);
    memset(b->used, 0, nc * sizeof *b->used);
    if (!b->remapped)
        memset(b->fresh, 0, wl_sf_n_insts(b->db));
    b->remapped = FALSE;
    for (guint c = 0; c < nc; c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            b->need[i] = wl_sf_screen_regions(&b->regions, &scr[i]);
            b->used[c] |= b->need[i];
        }
    }
}

/* ---- edits: instances renumbered --------------------------------------- */

static void remap_new(WlSfBook *b, const gint64 *old_of_new, guint ni,
                      uint64_t *held, uint64_t *mast, WlSfRemapWork *w)
{
    gboolean maxset = b->bk == WL_SF_MAXSET;
    for (guint i = 0; i < ni; i++) {
        gint64 o = old_of_new[i];
        if (o >= 0) {
            held[i] = b->held_inst[o];
            mast[i] = b->master_inst[o];
            continue;
        }
        guint m = b->master[wl_sf_inst(b->db, i)->chunk];
        held[i] = mast[i] = wl_sf_bit(m); /* §3.4.3: master pointers */
        b->fresh[i] = 1;
        w[m].ptr_created += maxset;
    }
}

void wl_sf_book_remap(WlSfBook *b, const gint64 *old_of_new, guint n_old,
                      WlSfRemapWork *w)
{
    guint ni = wl_sf_n_insts(b->db);
    uint64_t *held = g_new0(uint64_t, ni), *mast = g_new0(uint64_t, ni);
    guint8 *kept = g_new0(guint8, n_old);
    g_free(b->fresh);
    b->fresh = g_new0(guint8, MAX(ni, 1));
    remap_new(b, old_of_new, ni, held, mast, w);
    for (guint i = 0; i < ni; i++)
        if (old_of_new[i] >= 0)
            kept[old_of_new[i]] = 1;
    for (guint o = 0; b->bk == WL_SF_MAXSET && o < n_old; o++)
        for (uint64_t bits = kept[o] ? 0 : b->held_inst[o], q = 0; bits;
             q++, bits >>= 1)
            w[q].ptr_collected += bits & 1; /* garbage-collected */
    g_free(kept);
    g_free(b->held_inst);
    g_free(b->master_inst);
    g_free(b->need);
    b->held_inst = held;
    b->master_inst = mast;
    b->need = g_new0(uint64_t, ni);
    b->remapped = TRUE;
}

/* ---- sending ------------------------------------------------------------ */

static void send_chunk(WlSfBook *b, WlSfBatch *bt, guint c, guint hint,
                       WlSfBookWork *w)
{
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    g_array_append_val(bt->chunks, c);
    if (b->bk == WL_SF_MINSET)
        g_array_append_val(bt->insts, hint); /* carried in the header */
    bt->polys += ch->polys;
    bt->bytes += b->sizes.chunk + ch->polys * b->sizes.triangle;
    w->sent_chunks++;
    w->sent_polys += ch->polys;
}

static void send_pointer(WlSfBook *b, WlSfBatch *bt, guint i, WlSfBookWork *w)
{
    g_array_append_val(bt->insts, i);
    bt->bytes += b->sizes.instance;
    w->sent_insts++;
}

/* First instance of chunk ch overlapping region q (§3.3.2.3). */
static guint first_in(const WlSfBook *b, const WlSfChunk *ch, guint q)
{
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
        if (b->need[i] & wl_sf_bit(q))
            return i;
    g_assert_not_reached();
    return 0;
}

/* Dynamic mastership: chunk c's master p needs none of its instances
 * (uni: the regions that do, held: processors holding a copy before
 * this frame's sends); mastership goes to the lowest-numbered holder
 * needing it, else the lowest needing it, and p deletes its copy. */
static gboolean hand_over(WlSfBook *b, guint p, guint c, uint64_t uni,
                          uint64_t held, WlSfBatch *out, WlSfBookWork *w)
{
    if (b->ms != WL_SF_DYNAMIC || !uni || (uni & wl_sf_bit(p)))
        return FALSE;
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    uint64_t pick = (uni & held) ? uni & held : uni;
    WlSfBatch *bt = &out[__builtin_ctzll(pick)];
    uint64_t vec = (b->regions.procs + 7) / 8;
    g_array_append_val(bt->masters, c);
    bt->bytes += b->sizes.mastership;
    if (b->bk == WL_SF_MAXSET)
        bt->bytes += ch->n_inst * (b->sizes.instance + vec);
    b->held_data[c] &= ~wl_sf_bit(p);
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
        b->held_inst[i] &= ~wl_sf_bit(p);
    w->handed++;
    w->deleted_chunks++;
    return TRUE;
}

static void master_minset(WlSfBook *b, guint p, guint c, WlSfBatch *out,
                          WlSfBookWork *w)
{
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    uint64_t uni = 0;
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
        uni |= b->need[i];
    w->master_boxes += ch->n_inst;
    uint64_t held = b->master_data[c];
    uint64_t fresh = uni & ~held & ~wl_sf_bit(p);
    for (guint q = 0; fresh; q++, fresh >>= 1)
        if (fresh & 1)
            send_chunk(b, &out[q], c, first_in(b, ch, q), w);
    b->master_data[c] = uni | wl_sf_bit(p);
    if (hand_over(b, p, c, uni, held, out, w))
        b->master_data[c] = uni;
}

static void master_maxset(WlSfBook *b, guint p, guint c, WlSfBatch *out,
                          WlSfBookWork *w)
{
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    uint64_t uni = 0, me = wl_sf_bit(p), held = b->master_data[c];
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
        uint64_t fresh = b->need[i] & ~b->master_inst[i] & ~me;
        uni |= b->need[i];
        for (guint q = 0; fresh; q++, fresh >>= 1) {
            if (!(fresh & 1))
                continue;
            if (!(b->master_data[c] & wl_sf_bit(q))) {
                send_chunk(b, &out[q], c, i, w);
                b->master_data[c] |= wl_sf_bit(q);
            }
            send_pointer(b, &out[q], i, w);
            w->edit_bytes += b->fresh[i] ? b->sizes.instance : 0;
        }
        b->master_inst[i] = b->need[i] | me;
    }
    w->master_boxes += ch->n_inst;
    b->master_data[c] = uni | me;
    if (!hand_over(b, p, c, uni, held, out, w))
        return;
    b->master_data[c] = uni;
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
        b->master_inst[i] &= ~me;
}

/* Cull tests of every instance (their result is used[] of this frame);
 * the copy goes if no instance needed it last frame (§3.3.2.1). */
static void slave_minset(WlSfBook *b, guint p, guint c, WlSfBookWork *w)
{
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    w->slave_boxes += ch->n_inst;
    if (b->used_prev[c] & wl_sf_bit(p))
        return;
    b->held_data[c] &= ~wl_sf_bit(p);
    w->deleted_chunks++;
    w->collected += ch->n_inst == 0;
}

/* Drops the pointers that left p's region; the copy goes at render. */
static void slave_maxset(WlSfBook *b, guint p, guint c, WlSfBookWork *w)
{
    const WlSfChunk *ch = wl_sf_chunk(b->db, c);
    uint64_t me = wl_sf_bit(p);
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
        if (!(b->held_inst[i] & me))
            continue;
        w->slave_boxes++;
        if (!(b->need[i] & me))
            b->held_inst[i] &= ~me;
    }
}

void wl_sf_book_sort(WlSfBook *b, guint p, WlSfBatch *out, WlSfBookWork *w)
{
    for (guint q = 0; q < b->regions.procs; q++)
        batch_reset(&out[q], p, q, &b->sizes);
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        gboolean minset = b->bk == WL_SF_MINSET;
        if (b->master[c] == p && minset)
            master_minset(b, p, c, out, w);
        else if (b->master[c] == p)
            master_maxset(b, p, c, out, w);
        else if (minset && (b->held_data[c] & wl_sf_bit(p)))
            slave_minset(b, p, c, w);
        else if (!minset && (b->held_data[c] & wl_sf_bit(p)))
            slave_maxset(b, p, c, w);
    }
    for (guint q = 0; q < b->regions.procs; q++)
        if (q != p)
            w->sent_bytes += out[q].bytes;
}

/* ---- pull (§3.3.2.2) ------------------------------------------------------ */

void wl_sf_book_pull_sort(WlSfBook *b, guint p, WlSfBatch *out,
                          WlSfBookWork *w)
{
    g_assert(b->mig == WL_SF_PULL);
    uint64_t me = wl_sf_bit(p);
    for (guint q = 0; q < b->regions.procs; q++)
        batch_reset(&out[q], p, q, &b->sizes);
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        uint64_t any = 0;
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
            any |= b->need[i] & me;
        gboolean held = (b->held_data[c] & me) != 0;
        if (b->master[c] == p)
            w->master_boxes += ch->n_inst;
        else if (held)
            w->slave_boxes += ch->n_inst;
        else
            w->probe_boxes += ch->n_inst;
        if (b->master[c] == p)
            continue;
        if (held && !(b->used_prev[c] & me)) { /* a frame late, as push */
            b->held_data[c] &= ~me;
            w->deleted_chunks++;
            w->collected += ch->n_inst == 0;
            held = FALSE;
        }
        if (!held && any) {
            WlSfBatch *bt = &out[b->master[c]];
            g_array_append_val(bt->chunks, c);
            bt->bytes += b->sizes.request;
            w->requested++;
        }
    }
    for (guint q = 0; q < b->regions.procs; q++)
        if (q != p && out[q].chunks->len)
            w->sent_bytes += out[q].bytes;
}

void wl_sf_book_serve(WlSfBook *b, const WlSfBatch *req, WlSfBatch *reply,
                      WlSfBookWork *w)
{
    batch_reset(reply, req->dst, req->src, &b->sizes);
    for (guint k = 0; k < req->chunks->len; k++) {
        guint c = g_array_index(req->chunks, guint, k);
        g_assert(b->master[c] == req->dst);
        send_chunk(b, reply, c, first_in(b, wl_sf_chunk(b->db, c), req->src),
                   w);
    }
    w->sent_bytes += reply->bytes;
}

/* ---- receiving and rendering --------------------------------------------- */

void wl_sf_book_receive(WlSfBook *b, const WlSfBatch *in, WlSfBookWork *w)
{
    uint64_t me = wl_sf_bit(in->dst);
    for (guint k = 0; k < in->chunks->len; k++) {
        guint c = g_array_index(in->chunks, guint, k);
        g_assert(!(b->held_data[c] & me));
        b->held_data[c] |= me;
        w->recv_chunks++;
        w->recv_polys += wl_sf_chunk(b->db, c)->polys;
    }
    for (guint k = 0; k < in->masters->len; k++) {
        guint c = g_array_index(in->masters, guint, k);
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        g_assert(b->held_data[c] & me);
        b->master[c] = in->dst;
        b->master_data[c] |= me;
        for (guint i = ch->inst_first;
             b->bk == WL_SF_MAXSET && i < ch->inst_first + ch->n_inst; i++)
        {
            b->held_inst[i] |= me; /* the master holds every pointer */
            b->master_inst[i] |= me;
        }
    }
    if (b->bk == WL_SF_MINSET)
        return;
    for (guint k = 0; k < in->insts->len; k++) {
        guint i = g_array_index(in->insts, guint, k);
        g_assert(b->held_data[wl_sf_inst(b->db, i)->chunk] & me);
        b->held_inst[i] |= me;
        w->recv_insts++;
        w->new_boxes++;
    }
}

static gboolean any_pointer(const WlSfBook *b, const WlSfChunk *ch, uint64_t me)
{
    for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
        if (b->held_inst[i] & me)
            return TRUE;
    return FALSE;
}

static void count_held(const WlSfBook *b, guint p, WlSfBookWork *w)
{
    uint64_t me = wl_sf_bit(p);
    w->held_chunks = w->held_polys = 0;
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        if (!(b->held_data[c] & me))
            continue;
        w->held_chunks++;
        w->held_polys += wl_sf_chunk(b->db, c)->polys;
    }
}

void wl_sf_book_render_set(WlSfBook *b, guint p, const GArray *fresh,
                           GArray *render, WlSfBookWork *w)
{
    uint64_t me = wl_sf_bit(p);
    gboolean maxset = b->bk == WL_SF_MAXSET;
    for (guint k = 0; !maxset && fresh && k < fresh->len; k++)
        w->new_boxes +=
            wl_sf_chunk(b->db, g_array_index(fresh, guint, k))->n_inst;
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        if (!(b->held_data[c] & me))
            continue;
        if (maxset && b->master[c] != p && !any_pointer(b, ch, me)) {
            b->held_data[c] &= ~me; /* reference count 0 (§3.4.3) */
            w->deleted_chunks++;
            w->collected += ch->n_inst == 0;
            continue;
        }
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++)
            if ((b->need[i] & me) && (!maxset || (b->held_inst[i] & me)))
                g_array_append_val(render, i);
    }
    count_held(b, p, w);
}

uint64_t wl_sf_book_memory(const WlSfBook *b, guint p)
{
    uint64_t me = wl_sf_bit(p), bytes = 0;
    uint64_t vec = (b->regions.procs + 7) / 8;
    gboolean maxset = b->bk == WL_SF_MAXSET;
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        if (b->master[c] == p)
            bytes += vec * (1 + (maxset ? ch->n_inst : 0));
        if (!(b->held_data[c] & me))
            continue;
        bytes += b->sizes.chunk + ch->polys * b->sizes.triangle;
        for (guint i = ch->inst_first;
             maxset && i < ch->inst_first + ch->n_inst; i++)
            bytes += (b->held_inst[i] & me) ? b->sizes.instance : 0;
    }
    return bytes;
}

/* Adds `bytes` to each processor in bits. */
static void add_to(uint64_t *per, uint64_t bits, uint64_t bytes)
{
    for (; bits; bits &= bits - 1)
        per[__builtin_ctzll(bits)] += bytes;
}

uint64_t wl_sf_book_peak_memory(const WlSfBook *b)
{
    uint64_t per[WL_SF_MAX_PROCS] = {0}, peak = 0;
    uint64_t vec = (b->regions.procs + 7) / 8;
    gboolean maxset = b->bk == WL_SF_MAXSET;
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        uint64_t data = b->held_data[c];
        per[b->master[c]] += vec * (1 + (maxset ? ch->n_inst : 0));
        add_to(per, data, b->sizes.chunk + ch->polys * b->sizes.triangle);
        for (guint i = ch->inst_first;
             maxset && i < ch->inst_first + ch->n_inst; i++)
            add_to(per, b->held_inst[i] & data, b->sizes.instance);
    }
    for (guint p = 0; p < b->regions.procs; p++)
        peak = MAX(peak, per[p]);
    return peak;
}

gboolean wl_sf_book_check(const WlSfBook *b, guint *inst, guint *proc)
{
    /* by chunk (instances are grouped by chunk in chunk order): the
     * first miss is the lowest-numbered instance missing */
    for (guint c = 0; c < wl_sf_n_chunks(b->db); c++) {
        const WlSfChunk *ch = wl_sf_chunk(b->db, c);
        for (guint i = ch->inst_first; i < ch->inst_first + ch->n_inst; i++) {
            uint64_t miss = b->need[i] & ~b->held_data[c];
            if (b->bk == WL_SF_MAXSET)
                miss |= b->need[i] & ~b->held_inst[i];
            if (miss) {
                *inst = i;
                *proc = (guint)__builtin_ctzll(miss);
                return FALSE;
            }
        }
    }
    return TRUE;
}
