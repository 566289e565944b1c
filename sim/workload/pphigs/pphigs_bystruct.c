/* pphigs_bystruct.c — distribute-by-structure (seed 001 §2.1, the
 * paper's rejected alternative; pgsim's own row in reproduce ellsworth90).
 *
 * Each primitive and each structure instance goes whole to the
 * least-loaded GP (nominal weight of the instance's subtree, max-set); a
 * structure instanced once and heavier than one GP's share is broken up
 * (its execute to the GPs holding something in it, its elements dealt
 * the same way).  A list whose posted structures are also executed
 * elsewhere cannot be dealt by instance.  The inherited attributes of a
 * GP's pieces reach it one of §2.1's two ways (w.inherit):
 *
 *   skeleton    "a skeleton on each processor of the network from the
 *               local structure back to the root ... only the attribute
 *               elements of the ancestor structures": an attribute of a
 *               broken-up structure goes to every GP holding something
 *               after it there (an element, or something under a
 *               broken-up execute); each GP traverses them again.
 *   precompute  "pre-calculate the inherited attributes, sending those
 *               to the appropriate processors": the host walks the
 *               broken-up structures with their state and, before each
 *               element a GP holds there, sends that GP the state it
 *               lacks: a replace-mode matrix holding the local matrix
 *               (concatenations folded in) and the colour of the
 *               element's primitive type (an execute: every type's),
 *               each only when it differs from what the GP has.  These state
 *               elements are not host elements: they are inserted into
 *               the GPs' lists after the masks and deltas are final
 *               (by-structure has no editing or moves that would read
 *               the masks' positions again); their delta is 0, so ODP
 *               priorities stay as §4 numbered them.
 *
 * Cost: O(total elements of the max-set) plus the copies sent; the
 * precompute walk O(elements of broken-up structures x GPs).
 */
#include "sim/workload/pphigs/pphigs_dist_internal.h"
#include <string.h>

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
    double *memo;      /* subtree weights, -1 unknown */
    guint *uses;       /* executes of each structure in the host list */
    gboolean *broken;  /* structures walked element by element (roots,
                          broken-up ones) */
    double share;      /* the whole list's weight / GPs */
} ByStruct;

/* The skeleton: each attribute of sid to the GPs holding something
 * after it in sid. */
static void skeleton(WlPphigsDist *d, guint sid)
{
    uint64_t after = 0;
    for (guint i = scene_db_len(d->host, sid); i-- > 0;) {
        if (!scene_elem_is_attr(dist_hel(d, sid, i)->kind)) {
            after |= *dist_mask_at(d, sid, i);
            continue;
        }
        for (guint g = 0; g < d->ngp; g++)
            if ((after >> g) & 1)
                wl_pphigs_dist_put(d, sid, i, g);
    }
}

/* Each primitive and structure instance of sid whole to the
 * least-loaded GP; a structure instanced once whose weight exceeds one
 * GP's share is broken up (§2.1: "the structures can be broken up"):
 * its elements dealt in turn, its execute to the GPs holding any.  Then
 * the skeleton's attributes.  Returns the GPs holding anything in sid. */
static uint64_t bystruct_walk(WlPphigsDist *d, guint sid, ByStruct *b)
{
    uint64_t held = 0;
    b->broken[sid] = TRUE;
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = dist_hel(d, sid, i);
        if (scene_elem_is_attr(e->kind))
            continue;
        double w = wl_pphigs_dist_weight(d, e);
        gboolean exec = e->kind == SCENE_EL_EXECUTE;
        if (exec)
            w += subtree_weight(d, e->child, b->memo);
        if (exec && w > b->share && b->uses[e->child] == 1 &&
            !scene_db_is_posted(d->host, e->child)) {
            uint64_t under = bystruct_walk(d, e->child, b);
            for (guint g = 0; g < d->ngp; g++)
                if ((under >> g) & 1)
                    wl_pphigs_dist_put(d, sid, i, g);
            held |= under;
            continue;
        }
        guint g = least_global(d);
        wl_pphigs_dist_add_load(d, sid, g, w);
        wl_pphigs_dist_put(d, sid, i, g);
        if (exec)
            put_whole(d, e->child, g);
        held |= (uint64_t)1 << g;
    }
    if (d->w.inherit == WL_PPHIGS_INHERIT_SKELETON)
        skeleton(d, sid);
    return held;
}

/* ---- precompute: the host sends the inherited state ------------------ */

typedef struct {
    Mat4 *local;  /* per GP: its local matrix in the structure */
    Vec3 *colour; /* per GP and colour slot: its colours there */
    guint *pos;   /* per GP: its position of the next host element */
} GpState;

static const SceneElemKind slot_kind[NSLOTS] = {
    SCENE_EL_COLOR, SCENE_EL_LINE_COLOR, SCENE_EL_SPHERE_COLOR};

/* A state element (replace matrix or colour) into GP g's sid at pos. */
static void send_state(WlPphigsDist *d, guint sid, guint g, guint pos,
                       SceneElem e)
{
    e.tag = d->next_id++;
    gboolean ok = scene_db_insert(d->gp[g], sid, pos, &e, NULL);
    g_assert(ok);
    d->traffic.elements_sent++;
    d->traffic.attrs_sent++;
    d->traffic.sent_to[g]++;
}

/* Walks broken-up structure sid entered with colours c (one per slot:
 * the host's and, by induction, every holder's), sending each holder
 * the state it lacks before each element it holds: the matrix, and the
 * colour of the element's primitive type (an execute: every colour). */
static void precompute_walk(WlPphigsDist *d, guint sid, const Vec3 *entry,
                            const ByStruct *b)
{
    GpState s = {g_new(Mat4, d->ngp), g_new(Vec3, d->ngp * NSLOTS),
                 g_new0(guint, d->ngp)};
    Mat4 local = mat4_identity();
    Vec3 c[NSLOTS];
    memcpy(c, entry, sizeof c);
    for (guint g = 0; g < d->ngp; g++) {
        s.local[g] = local;
        memcpy(&s.colour[g * NSLOTS], c, sizeof c);
    }
    for (guint i = 0; i < scene_db_len(d->host, sid); i++) {
        const SceneElem *e = dist_hel(d, sid, i);
        if (scene_elem_is_color(e->kind))
            c[attr_slot(e->kind)] = e->color;
        if (e->kind == SCENE_EL_MATRIX)
            local = e->mode == SCENE_MAT_REPLACE ? e->matrix
                                                 : mat4_mul(local, e->matrix);
        uint64_t m = *dist_mask_at(d, sid, i);
        for (guint g = 0; g < d->ngp; g++) {
            if (!((m >> g) & 1))
                continue;
            if (memcmp(&s.local[g], &local, sizeof local)) {
                send_state(d, sid, g, s.pos[g]++,
                           scene_elem_matrix(local, SCENE_MAT_REPLACE));
                s.local[g] = local;
            }
            for (guint k = 0; k < NSLOTS; k++) {
                Vec3 *have = &s.colour[g * NSLOTS + k];
                if ((e->kind != SCENE_EL_EXECUTE &&
                     k != attr_slot(scene_elem_color_of(e->kind))) ||
                    !memcmp(have, &c[k], sizeof c[k]))
                    continue;
                send_state(d, sid, g, s.pos[g]++,
                           scene_elem_kind_color(slot_kind[k], c[k]));
                *have = c[k];
            }
            s.pos[g]++;
        }
        if (e->kind == SCENE_EL_EXECUTE && b->broken[e->child])
            precompute_walk(d, e->child, c, b);
    }
    g_free(s.local);
    g_free(s.colour);
    g_free(s.pos);
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
 * be, see bystruct_possible().  The state elements of precompute are
 * sent by wl_pphigs_dist_by_structure_state(), after the deltas. */
gboolean wl_pphigs_dist_by_structure(WlPphigsDist *d)
{
    guint n = scene_db_struct_count(d->host);
    ByStruct b = {g_new(double, n), g_new0(guint, n), g_new0(gboolean, n),
                  0};
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
    if (ok)
        d->broken = b.broken;
    else
        g_free(b.broken);
    return ok;
}

void wl_pphigs_dist_by_structure_state(WlPphigsDist *d)
{
    if (d->algo != WL_PPHIGS_BY_STRUCTURE ||
        d->w.inherit != WL_PPHIGS_INHERIT_PRECOMPUTE)
        return;
    ByStruct b = {.broken = d->broken};
    const Vec3 white[NSLOTS] = {vec3(1, 1, 1), vec3(1, 1, 1), vec3(1, 1, 1)};
    for (guint i = 0; i < scene_db_posted_count(d->host); i++)
        precompute_walk(d, scene_db_posted_at(d->host, i), white, &b);
}
