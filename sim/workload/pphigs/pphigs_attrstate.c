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
 */
#include "sim/workload/pphigs/pphigs_dist_internal.h"

void wl_pphigs_attr_init(AttrState *s)
{
    s->colour = s->replace = NONE;
    s->concats = g_array_new(FALSE, FALSE, sizeof(gint));
}

void wl_pphigs_attr_clear(AttrState *s)
{
    g_array_unref(s->concats);
}

/* The host state after element i (forward direction). */
void wl_pphigs_attr_step(AttrState *s, const SceneElem *e, gint i)
{
    if (e->kind == SCENE_EL_COLOR) {
        s->colour = i;
    } else if (e->kind == SCENE_EL_MATRIX && e->mode == SCENE_MAT_REPLACE) {
        s->replace = i;
        g_array_set_size(s->concats, 0);
    } else if (e->kind == SCENE_EL_MATRIX) {
        g_array_append_val(s->concats, i);
    }
}

/* Sends GP g every known current attribute it lacks. */
void wl_pphigs_attr_ensure(WlPphigsDist *d, guint sid, const AttrState *s,
                           guint g)
{
    if (s->colour != NONE)
        wl_pphigs_dist_put(d, sid, (guint)s->colour, g);
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

/* §3.4-3.5: steps back from `first` collecting the host's current
 * attributes until every GP is known current. */
void wl_pphigs_attr_backward(WlPphigsDist *d, guint sid, guint first,
                             AttrState *s)
{
    uint64_t cur = 0, examined = 0;
    gboolean replace_found = FALSE;
    for (gint j = (gint)first - 1; j >= 0 && cur != dist_all_mask(d); j--) {
        const SceneElem *e = dist_hel(d, sid, (guint)j);
        examined++;
        if (e->kind == SCENE_EL_COLOR) {
            if (s->colour == NONE)
                s->colour = j;
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
            break; /* every GP was flushed before this execute */
        } else {
            cur |= *dist_mask_at(d, sid, (guint)j);
        }
    }
    d->traffic.last_scan = examined;
    d->traffic.max_scan = MAX(d->traffic.max_scan, examined);
}
