/* pphigs_edit.c — editing the distributed display list (seed 001 §3.1-3.3).
 *
 * Modify and append act at once; insert and delete are two steps: step 1
 * changes the host (and sends inserted primitives and executes, deletes
 * from GPs at once) and widens the structure's pending region; step 2
 * (wl_pphigs_dist_finish) runs the backward scan (pphigs_attrstate.c)
 * and the forward walk (pphigs_distrib.c) over each pending region, then
 * recomputes the ODP deltas (§4).
 * Cost: O(n) per insert/delete for the GP position; step 2 as §3.5 says.
 */
#include "sim/workload/pphigs/pphigs_dist_internal.h"

static void region_add(StructMeta *m, gint p)
{
    if (m->first == NONE) {
        m->first = m->last = p;
        return;
    }
    m->first = MIN(m->first, p);
    m->last = MAX(m->last, p);
}

/* Sends a new element as step 1 says: dealt elements and executes at
 * once, attributes only to the host (complex); everything (simple). */
static void step1_send(WlPphigsDist *d, guint sid, guint pos)
{
    const SceneElem *e = dist_hel(d, sid, pos);
    if (dist_is_prim_struct(d, sid) || d->algo == WL_PPHIGS_SIMPLE) {
        wl_pphigs_dist_forward(d, sid, pos, (gint)pos, NULL);
        return;
    }
    if (!dist_is_dealt(d, e)) {
        if (!scene_elem_is_attr(e->kind))
            wl_pphigs_dist_put_all(d, sid, pos);
        return;
    }
    double w = wl_pphigs_dist_weight(d, e);
    dist_meta(d, sid)->cur = NONE;
    guint g = wl_pphigs_dist_choose(d, sid, w);
    wl_pphigs_dist_add_load(d, sid, g, w);
    wl_pphigs_dist_put(d, sid, pos, g);
}

gboolean wl_pphigs_dist_insert(WlPphigsDist *d, guint sid, guint pos,
                               const SceneElem *e, GError **err)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    SceneElem c = *e;
    c.tag = d->next_id;
    if (!scene_db_insert(d->host, sid, pos, &c, err))
        return FALSE;
    wl_pphigs_attr_cache_edit(d, sid, pos, 1, scene_elem_is_attr(c.kind));
    d->next_id++;
    if (scene_elem_is_prim(c.kind))
        d->maxw = MAX(d->maxw, wl_pphigs_dist_weight(d, &c));
    StructMeta *m = dist_meta(d, sid);
    uint64_t zero = 0;
    g_array_insert_val(m->mask, pos, zero);
    if (m->last != NONE && m->last >= (gint)pos)
        m->last++;
    region_add(m, (gint)pos); /* first: a first at or after pos becomes pos */
    step1_send(d, sid, pos);
    return TRUE;
}

void wl_pphigs_dist_delete(WlPphigsDist *d, guint sid, guint pos)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    const SceneElem *e = dist_hel(d, sid, pos);
    uint64_t msk = *dist_mask_at(d, sid, pos);
    if (dist_is_dealt(d, e) && !dist_is_prim_struct(d, sid) && msk)
        wl_pphigs_dist_add_load(d, sid, (guint)__builtin_ctzll(msk),
                                -wl_pphigs_dist_weight(d, e));
    for (guint g = 0; g < d->ngp; g++)
        wl_pphigs_dist_drop(d, sid, pos, g);
    wl_pphigs_attr_cache_edit(d, sid, pos, -1, scene_elem_is_attr(e->kind));
    scene_db_delete(d->host, sid, pos);
    StructMeta *m = dist_meta(d, sid);
    g_array_remove_index(m->mask, pos);
    if (m->last != NONE && m->last >= (gint)pos)
        m->last--;
    region_add(m, (gint)pos); /* first: a first after pos becomes pos */
}

gboolean wl_pphigs_dist_append(WlPphigsDist *d, guint sid, const SceneElem *e,
                               GError **err)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    if (!wl_pphigs_dist_insert(d, sid, scene_db_len(d->host, sid), e, err))
        return FALSE;
    wl_pphigs_dist_finish(d);
    return TRUE;
}

gboolean wl_pphigs_dist_modify(WlPphigsDist *d, guint sid, guint pos,
                               const SceneElem *e, GError **err)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    const SceneElem *old = dist_hel(d, sid, pos);
    gboolean remode = old->kind == SCENE_EL_MATRIX && old->mode != e->mode;
    if (old->kind == e->kind &&
        (remode || dist_is_dealt(d, old) != dist_is_dealt(d, e))) {
        /* an execute changing between ordinary and primitive structure,
         * or a matrix changing mode: the attribute state after it
         * changes (a concatenation needs the matrices before it on every
         * GP drawing after it), so it goes as an insert and a delete */
        if (!wl_pphigs_dist_insert(d, sid, pos, e, err))
            return FALSE;
        wl_pphigs_dist_delete(d, sid, pos + 1);
        wl_pphigs_dist_finish(d);
        return TRUE;
    }
    SceneElem c = *e;
    c.tag = old->tag;
    double dw = dist_is_dealt(d, old) ? wl_pphigs_dist_weight(d, &c) -
                                            wl_pphigs_dist_weight(d, old)
                                      : 0;
    if (!scene_db_modify(d->host, sid, pos, &c, err))
        return FALSE;
    c = *dist_hel(d, sid, pos); /* e's vertices may have been the old host's */
    uint64_t m = *dist_mask_at(d, sid, pos);
    for (guint g = 0; g < d->ngp; g++)
        if ((m >> g) & 1) {
            gboolean ok = scene_db_modify(
                d->gp[g], sid, wl_pphigs_dist_gp_pos(d, sid, pos, g), &c, NULL);
            g_assert(ok);
            d->traffic.elements_sent++; /* §3.1: new data to each holder */
            d->traffic.sent_to[g]++;
        }
    if (dw != 0 && m && !dist_is_prim_struct(d, sid))
        wl_pphigs_dist_add_load(d, sid, (guint)__builtin_ctzll(m), dw);
    wl_pphigs_dist_deltas(d); /* an execute's child may change the ODP counts */
    return TRUE;
}

void wl_pphigs_dist_finish(WlPphigsDist *d)
{
    for (guint s = 0; s < d->meta->len; s++) {
        StructMeta *m = dist_meta(d, s);
        if (m->first == NONE)
            continue;
        guint len = scene_db_len(d->host, s);
        guint first = MIN((guint)m->first, len);
        gint last = MIN(m->last, (gint)len - 1);
        m->first = m->last = NONE;
        wl_pphigs_dist_step2(d, s, first, last);
    }
    wl_pphigs_dist_deltas(d);
}

void wl_pphigs_dist_post(WlPphigsDist *d, guint sid)
{
    g_assert(d->algo != WL_PPHIGS_BY_STRUCTURE); /* no §3 editing */
    scene_db_post(d->host, sid);
    for (guint g = 0; g < d->ngp; g++)
        scene_db_post(d->gp[g], sid);
}

void wl_pphigs_dist_unpost(WlPphigsDist *d, guint sid)
{
    scene_db_unpost(d->host, sid);
    for (guint g = 0; g < d->ngp; g++)
        scene_db_unpost(d->gp[g], sid);
}
