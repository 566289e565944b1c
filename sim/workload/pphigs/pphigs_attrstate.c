/* pphigs_attrstate.c — attribute states of the PPHIGS distribution
 * (seed 001 §3.4-3.5, pphigs_dist_internal.h).
 *
 * An AttrState holds the positions of the host's current attribute
 * elements at a point of a structure: the colour, the replace-mode
 * matrix and the concatenate-mode matrices after it.  ensure() sends a
 * GP the ones it lacks (its mask says which it holds).  The backward
 * scan of step 2 steps back from the first edited point collecting the
 * host's current attributes until every GP is known current (a primitive
 * dealt to it, §3.5), an ordinary execute (every GP was flushed before
 * it) or the start of the structure: at most c (maxw/minw) (n-1)
 * elements for n GPs, §3.5.
 *
 * The cache (§3.4: "save attribute states every n primitives"): with
 * w.attr_cache = N > 0 (complex, ordinary structures) the host keeps
 * its full attribute state after every N-th dealt element.  The scan
 * also stops at the nearest checkpoint behind the edit and completes
 * what it collected with the checkpoint's state.  That sends the same
 * elements as the scan alone (a GP's copies, its mask, already say
 * which of the state's elements it holds; ensure() sends the rest), so
 * the cache moves where the scan stops, not the distribution.  Each
 * GP's state at a checkpoint is the checkpoint's state restricted to
 * the GP's mask.  Invariant: a checkpoint's state is the host state
 * before its position.  An edit at pos moves the checkpoints after pos
 * (a primitive or execute inserted or deleted) or drops them (an
 * attribute inserted or deleted, a matrix changing mode), and the walk
 * that places them resumes at the last one kept, lazily, when a scan
 * needs one.  Memory: one state per N dealt elements.
 */
#include "sim/workload/pphigs/pphigs_dist_internal.h"
#include <string.h>

void wl_pphigs_attr_init(AttrState *s)
{
    for (guint k = 0; k < NSLOTS; k++)
        s->colour[k] = NONE;
    s->replace = NONE;
    s->concats = g_array_new(FALSE, FALSE, sizeof(gint));
}

void wl_pphigs_attr_clear(AttrState *s)
{
    g_array_unref(s->concats);
}

/* The host state after element i (forward direction). */
void wl_pphigs_attr_step(AttrState *s, const SceneElem *e, gint i)
{
    if (scene_elem_is_color(e->kind)) {
        s->colour[attr_slot(e->kind)] = i;
    } else if (e->kind == SCENE_EL_MATRIX && e->mode == SCENE_MAT_REPLACE) {
        s->replace = i;
        g_array_set_size(s->concats, 0);
    } else if (e->kind == SCENE_EL_MATRIX) {
        g_array_append_val(s->concats, i);
    }
}

void wl_pphigs_attr_ensure(WlPphigsDist *d, guint sid, const AttrState *s,
                           guint g, const SceneElem *e)
{
    gboolean one = d->w.attr_send == WL_PPHIGS_SEND_BY_KIND && e &&
                   scene_elem_is_prim(e->kind);
    guint only = one ? attr_slot(scene_elem_color_of(e->kind)) : 0;
    for (guint k = 0; k < NSLOTS; k++)
        if (s->colour[k] != NONE && (!one || k == only))
            wl_pphigs_dist_put(d, sid, (guint)s->colour[k], g);
    if (s->replace != NONE)
        wl_pphigs_dist_put(d, sid, (guint)s->replace, g);
    for (guint k = 0; k < s->concats->len; k++)
        wl_pphigs_dist_put(d, sid, (guint)g_array_index(s->concats, gint, k),
                           g);
}

void wl_pphigs_attr_ensure_matrices(WlPphigsDist *d, guint sid,
                                    const AttrState *s)
{
    for (guint g = 0; g < d->ngp; g++) {
        if (s->replace != NONE)
            wl_pphigs_dist_put(d, sid, (guint)s->replace, g);
        for (guint k = 0; k < s->concats->len; k++)
            wl_pphigs_dist_put(d, sid,
                               (guint)g_array_index(s->concats, gint, k), g);
    }
}

/* ---- the attribute-state cache (§3.4) --------------------------------- */

/* The host state before element pos; front is where the walk that
 * places checkpoints stopped, dealt the elements it counted since the
 * last checkpoint. */
typedef struct {
    guint pos;
    AttrState st;
} AttrCk;

struct WlPphigsAttrCache {
    GArray *ck; /* AttrCk, by increasing pos */
    AttrCk front;
    guint dealt;
};

static void ck_copy(AttrCk *to, const AttrCk *from)
{
    to->pos = from->pos;
    memcpy(to->st.colour, from->st.colour, sizeof to->st.colour);
    to->st.replace = from->st.replace;
    g_array_set_size(to->st.concats, 0);
    g_array_append_vals(to->st.concats, from->st.concats->data,
                        from->st.concats->len);
}

static void ck_clear(gpointer p)
{
    wl_pphigs_attr_clear(&((AttrCk *)p)->st);
}

/* Walks the host list from the front up to `upto`, placing a checkpoint
 * after every n-th dealt element (host work only; counted). */
static void cache_extend(WlPphigsDist *d, guint sid, WlPphigsAttrCache *c,
                         guint upto)
{
    for (guint i = c->front.pos; i < upto; i++) {
        const SceneElem *e = dist_hel(d, sid, i);
        d->traffic.cache_walk++;
        wl_pphigs_attr_step(&c->front.st, e, (gint)i);
        c->front.pos = i + 1;
        if (dist_is_dealt(d, e) && ++c->dealt == d->w.attr_cache) {
            AttrCk k = {0};
            wl_pphigs_attr_init(&k.st);
            ck_copy(&k, &c->front);
            g_array_append_val(c->ck, k);
            c->dealt = 0;
        }
    }
}

WlPphigsAttrCache *wl_pphigs_attr_cache_new(WlPphigsDist *d, guint sid)
{
    WlPphigsAttrCache *c = g_new0(WlPphigsAttrCache, 1);
    c->ck = g_array_new(FALSE, FALSE, sizeof(AttrCk));
    g_array_set_clear_func(c->ck, ck_clear);
    wl_pphigs_attr_init(&c->front.st);
    cache_extend(d, sid, c, scene_db_len(d->host, sid));
    return c;
}

void wl_pphigs_attr_cache_free(WlPphigsAttrCache *c)
{
    if (!c)
        return;
    g_array_unref(c->ck);
    wl_pphigs_attr_clear(&c->front.st);
    g_free(c);
}

/* The last checkpoint at or before `first` (extending the cache to it),
 * or NULL. */
static const AttrCk *cache_at(WlPphigsDist *d, guint sid, guint first)
{
    WlPphigsAttrCache *c = dist_meta(d, sid)->cache;
    if (!c)
        return NULL;
    cache_extend(d, sid, c, first);
    for (guint k = c->ck->len; k-- > 0;)
        if (g_array_index(c->ck, AttrCk, k).pos <= first)
            return &g_array_index(c->ck, AttrCk, k);
    return NULL;
}

/* Positions at or after `pos` (insert, delta +1) or after it (delete,
 * delta -1) move by delta. */
static void shift(gint *p, guint pos, int delta)
{
    if (*p != NONE && (delta > 0 ? *p >= (gint)pos : *p > (gint)pos))
        *p += delta;
}

static void ck_shift(AttrCk *k, guint pos, int delta)
{
    k->pos += delta;
    for (guint s = 0; s < NSLOTS; s++)
        shift(&k->st.colour[s], pos, delta);
    shift(&k->st.replace, pos, delta);
    for (guint j = 0; j < k->st.concats->len; j++)
        shift(&g_array_index(k->st.concats, gint, j), pos, delta);
}

/* Drops every checkpoint after pos; the front restarts at the last one
 * kept (or at the start of the structure). */
static void cache_truncate(WlPphigsAttrCache *c, guint pos)
{
    guint keep = 0;
    while (keep < c->ck->len && g_array_index(c->ck, AttrCk, keep).pos <= pos)
        keep++;
    g_array_set_size(c->ck, keep);
    if (c->front.pos <= pos)
        return;
    c->dealt = 0;
    if (keep) {
        ck_copy(&c->front, &g_array_index(c->ck, AttrCk, keep - 1));
        return;
    }
    c->front.pos = 0;
    for (guint k = 0; k < NSLOTS; k++)
        c->front.st.colour[k] = NONE;
    c->front.st.replace = NONE;
    g_array_set_size(c->front.st.concats, 0);
}

void wl_pphigs_attr_cache_edit(WlPphigsDist *d, guint sid, guint pos, int delta,
                               gboolean attr)
{
    WlPphigsAttrCache *c = dist_meta(d, sid)->cache;
    if (!c)
        return;
    if (attr) { /* the state after pos changed */
        cache_truncate(c, pos);
        return;
    }
    for (guint k = 0; k < c->ck->len; k++)
        if (g_array_index(c->ck, AttrCk, k).pos > pos)
            ck_shift(&g_array_index(c->ck, AttrCk, k), pos, delta);
    if (c->front.pos > pos)
        ck_shift(&c->front, pos, delta);
}

/* ---- the backward scan (§3.4-3.5) ------------------------------------- */

/* Completes s with a checkpoint's state: what the scan did not find
 * between the checkpoint and its start. */
static void merge(AttrState *s, const AttrCk *k, gboolean replace_found)
{
    for (guint c = 0; c < NSLOTS; c++)
        if (s->colour[c] == NONE)
            s->colour[c] = k->st.colour[c];
    if (replace_found)
        return;
    s->replace = k->st.replace;
    g_array_prepend_vals(s->concats, k->st.concats->data, k->st.concats->len);
}

/* §3.4-3.5: steps back from `first` collecting the host's current
 * attributes until every GP is known current, an ordinary execute
 * (every GP was flushed before it) or a checkpoint of the cache (whose
 * state completes the collection). */
/* TRUE when the scan knows enough: every GP current (§3.5; every
 * colour travels with every primitive); by kind, for the matrices and
 * for each colour slot, the host's element found or every GP current
 * for it (a primitive of that type dealt to it). */
static gboolean scan_done(const WlPphigsDist *d, const AttrState *s,
                          uint64_t cur, const uint64_t *cur_slot,
                          gboolean replace_found)
{
    uint64_t all = dist_all_mask(d);
    if (d->w.attr_send != WL_PPHIGS_SEND_BY_KIND)
        return cur == all;
    if (!replace_found && cur != all)
        return FALSE;
    for (guint k = 0; k < NSLOTS; k++)
        if (s->colour[k] == NONE && cur_slot[k] != all)
            return FALSE;
    return TRUE;
}

void wl_pphigs_attr_backward(WlPphigsDist *d, guint sid, guint first,
                             AttrState *s)
{
    const AttrCk *ck = cache_at(d, sid, first);
    gint stop = ck ? (gint)ck->pos : 0, j = (gint)first - 1;
    uint64_t cur = 0, examined = 0, cur_slot[NSLOTS] = {0};
    gboolean replace_found = FALSE, flushed = FALSE, done = FALSE;
    for (; j >= stop && !done && !flushed; j--) {
        const SceneElem *e = dist_hel(d, sid, (guint)j);
        examined++;
        if (scene_elem_is_color(e->kind)) {
            if (s->colour[attr_slot(e->kind)] == NONE)
                s->colour[attr_slot(e->kind)] = j;
        } else if (e->kind == SCENE_EL_MATRIX) {
            if (replace_found)
                continue;
            if (e->mode == SCENE_MAT_REPLACE) {
                s->replace = j;
                replace_found = TRUE;
            } else {
                g_array_prepend_val(s->concats, j);
            }
        } else if (!dist_is_dealt(d, e)) {
            flushed = TRUE; /* every GP was flushed before this execute */
        } else {
            uint64_t m = *dist_mask_at(d, sid, (guint)j);
            cur |= m;
            for (guint k = 0; k < NSLOTS; k++) /* an execute: every colour */
                if (e->kind == SCENE_EL_EXECUTE ||
                    k == attr_slot(scene_elem_color_of(e->kind)))
                    cur_slot[k] |= m;
        }
        done = scan_done(d, s, cur, cur_slot, replace_found);
    }
    if (ck && j < stop && !done && !flushed)
        merge(s, ck, replace_found);
    d->traffic.last_scan = examined;
    d->traffic.total_scan += examined;
    d->traffic.max_scan = MAX(d->traffic.max_scan, examined);
}
