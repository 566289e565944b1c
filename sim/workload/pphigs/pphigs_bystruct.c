/* pphigs_bystruct.c — distribute-by-structure (seed 001 §2.1, the
 * paper's rejected alternative; pgsim's own row in reproduce ellsworth90).
 *
 * Every attribute goes to every GP; each primitive and each structure
 * instance goes whole to the least-loaded GP (nominal weight of the
 * instance's subtree, max-set); a structure instanced once and heavier
 * than one GP's share is broken up.  A list whose posted structures are
 * also executed elsewhere cannot be dealt by instance.
 * Cost: O(total elements of the max-set) plus the copies sent.
 */
#include "sim/workload/pphigs/pphigs_dist_internal.h"

/* Nominal weight of a structure with everything it executes (max-set). */
static double subtree_weight(const WlPphigsDist *d, guint sid, double *memo)
{
    if (memo[sid] >= 0)
        return memo[sid];
    double w = 0;
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = dist_hel(d, sid, i);
        w += wl_pphigs_dist_weight(d, e);
        if (e->kind == SCENE_EL_EXECUTE)
            w += subtree_weight(d, e->child, memo);
    }
    return memo[sid] = w;
}

/* A structure and everything it executes, whole, to GP g. */
static void put_whole(WlPphigsDist *d, guint sid, guint g)
{
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        wl_pphigs_dist_put(d, sid, i, g);
        if (dist_hel(d, sid, i)->kind == SCENE_EL_EXECUTE)
            put_whole(d, dist_hel(d, sid, i)->child, g);
    }
}

static guint least_global(const WlPphigsDist *d)
{
    guint best = 0;
    for (guint g = 1; g < d->ngp; g++)
        if (d->gload[g] < d->gload[best] - 1e-12)
            best = g;
    return best;
}

typedef struct {
    double *memo; /* subtree weights, -1 unknown */
    guint *uses;  /* executes of each structure in the host list */
    double share; /* the whole list's weight / GPs */
} ByStruct;

/* Attributes to every GP; each primitive and each structure instance
 * whole to the least-loaded GP; a structure instanced once whose weight
 * exceeds one GP's share is broken up (§2.1: "the structures can be
 * broken up"): its execute to every GP, its elements dealt in turn. */
static void bystruct_walk(WlPphigsDist *d, guint sid, ByStruct *b)
{
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = dist_hel(d, sid, i);
        if (scene_elem_is_attr(e->kind)) {
            wl_pphigs_dist_put_all(d, sid, i);
            continue;
        }
        double w = wl_pphigs_dist_weight(d, e);
        gboolean exec = e->kind == SCENE_EL_EXECUTE;
        if (exec)
            w += subtree_weight(d, e->child, b->memo);
        if (exec && w > b->share && b->uses[e->child] == 1 &&
            !scene_db_is_posted(d->host, e->child)) {
            wl_pphigs_dist_put_all(d, sid, i);
            bystruct_walk(d, e->child, b);
            continue;
        }
        guint g = least_global(d);
        wl_pphigs_dist_add_load(d, sid, g, w);
        wl_pphigs_dist_put(d, sid, i, g);
        if (exec)
            put_whole(d, e->child, g);
    }
}

/* FALSE when a posted structure is also executed: its posted instance
 * and the others would share one portion per GP, so it cannot be dealt
 * by instance. */
static gboolean bystruct_possible(const WlPphigsDist *d, const guint *uses)
{
    for (guint i = 0; i < scene_db_posted_count(d->host); i++)
        if (uses[scene_db_posted_at(d->host, i)])
            return FALSE;
    return TRUE;
}

/* Distributes by structure; FALSE (nothing dealt) when the list cannot
 * be, see bystruct_possible(). */
gboolean wl_pphigs_dist_by_structure(WlPphigsDist *d)
{
    guint n = scene_db_struct_count(d->host);
    ByStruct b = {g_new(double, n), g_new0(guint, n), 0};
    for (guint s = 0; s < n; s++) {
        b.memo[s] = -1;
        for (guint i = 0; i < scene_db_len(d->host, s); i++)
            if (dist_hel(d, s, i)->kind == SCENE_EL_EXECUTE)
                b.uses[dist_hel(d, s, i)->child]++;
    }
    gboolean ok = bystruct_possible(d, b.uses);
    for (guint i = 0; i < scene_db_posted_count(d->host); i++)
        b.share += subtree_weight(d, scene_db_posted_at(d->host, i), b.memo);
    b.share /= d->ngp;
    for (guint i = 0; ok && i < scene_db_posted_count(d->host); i++)
        bystruct_walk(d, scene_db_posted_at(d->host, i), &b);
    g_free(b.memo);
    g_free(b.uses);
    return ok;
}
