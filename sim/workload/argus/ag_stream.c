/* ag_stream.c — building the contexts' command streams (ag_stream.h).
 * Batches: one pass over the polygons; vertex counts: strips share two
 * vertices with the previous triangle when they do in the mesh.
 * O(triangles + cells).
 */
#include "sim/workload/argus/ag_stream.h"
#include "sim/core/error.h"
#include <math.h>

const char *const wl_ag_order_names[] = {"frame", "cells", "none", NULL};
const char *const wl_ag_prim_names[] = {"strips", "triangles", NULL};
const char *const wl_ag_state_names[] = {"none", "stateful", "stateless",
                                         NULL};

/* Vertices triangle i shares with triangle i - 1. */
static guint shared(const SceneMesh *m, guint i)
{
    const uint32_t *a = scene_mesh_poly(m, i - 1), *b = scene_mesh_poly(m, i);
    guint n = 0;
    for (int x = 0; x < 3; x++)
        for (int y = 0; y < 3; y++)
            n += a[x] == b[y];
    return n;
}

static uint64_t distinct_vertices(const SceneMesh *m, guint first, guint n)
{
    GHashTable *h = g_hash_table_new(g_direct_hash, g_direct_equal);
    for (guint i = first; i < first + n; i++)
        for (int k = 0; k < 3; k++)
            g_hash_table_add(h, GUINT_TO_POINTER(scene_mesh_poly(m, i)[k] + 1));
    uint64_t d = g_hash_table_size(h);
    g_hash_table_destroy(h);
    return d;
}

/* Strip vertices: 3 for a strip's first triangle, 1 for one that shares
 * an edge (two vertices) with its predecessor in the batch. */
static uint64_t batch_verts(const SceneMesh *m, guint first, guint n,
                            AgPrim prim)
{
    if (prim == WL_AG_PRIM_TRIANGLES)
        return 3 * (uint64_t)n;
    uint64_t v = 0;
    for (guint i = first; i < first + n; i++)
        v += (i > first && shared(m, i) == 2) ? 1 : 3;
    return v;
}

static GArray *find_batches(const SceneMesh *m, AgPrim prim)
{
    GArray *b = g_array_new(FALSE, TRUE, sizeof(AgBatch));
    guint n = scene_mesh_n_polys(m), i = 0;
    while (i < n) {
        guint tag = g_array_index(m->poly_tag, uint32_t, i), j = i;
        while (j < n && g_array_index(m->poly_tag, uint32_t, j) == tag)
            j++;
        AgBatch x = {i, j - i, tag, batch_verts(m, i, j - i, prim),
                     distinct_vertices(m, i, j - i)};
        g_array_append_val(b, x);
        i = j;
    }
    return b;
}

static void add_sync(AgSync *list, guint *n, AgSyncKind k, guint id)
{
    g_assert(*n < WL_AG_MAX_SYNC);
    list[(*n)++] = (AgSync){k, id};
}

/* Appends the blocks of batch `bi` to context c's stream; pre and post
 * are the batch's waits and signals. */
static void emit_batch(AgStreams *s, const SceneMesh *m, guint c, guint bi,
                       const AgBlock *sync, guint block_tris, AgPrim prim)
{
    const AgBatch *b = &g_array_index(s->batches, AgBatch, bi);
    GArray *out = wl_ag_ctx_blocks(s, c);
    /* an empty batch (a March cell without surface) is still one block:
     * the application visits the cell's voxels whatever it finds */
    guint pieces = b->n ? (b->n + block_tris - 1) / block_tris : 1;
    for (guint k = 0; k < pieces; k++) {
        AgBlock x = {.ctx = c, .batch = bi};
        x.first = b->first + k * block_tris;
        x.n = MIN(block_tris, b->first + b->n - x.first);
        x.opens = k == 0;
        x.verts = batch_verts(m, x.first, x.n, prim);
        if (k == 0)
            for (guint i = 0; i < sync->n_pre; i++)
                add_sync(x.pre, &x.n_pre, sync->pre[i].kind, sync->pre[i].id);
        if (k + 1 == pieces)
            for (guint i = 0; i < sync->n_post; i++)
                add_sync(x.post, &x.n_post, sync->post[i].kind,
                         sync->post[i].id);
        g_array_append_val(out, x);
    }
}

static void build_frame(AgStreams *s, const SceneMesh *m, guint block,
                        AgPrim prim)
{
    guint nb = s->batches->len;
    for (guint c = 0; c < s->contexts; c++)
        for (guint bi = c; bi < nb; bi += s->contexts)
            emit_batch(s, m, c, bi, &(AgBlock){0}, block, prim);
}

/* An empty block (no triangles) appended to, or inserted at the head
 * of, context c's stream. */
static AgBlock *empty_block(AgStreams *s, guint c, gboolean head)
{
    GArray *out = wl_ag_ctx_blocks(s, c);
    AgBlock x = {.ctx = c, .batch = G_MAXUINT};
    if (head)
        g_array_prepend_val(out, x);
    else
        g_array_append_val(out, x);
    return &g_array_index(out, AgBlock, head ? 0 : out->len - 1);
}

/* Figure 2's loop around context c's drawing (ag_stream.h). */
static void frame_loop(AgStreams *s, guint c)
{
    GArray *out = wl_ag_ctx_blocks(s, c);
    gboolean par = s->contexts > 1;
    if (par && out->len == 0)
        empty_block(s, c, FALSE); /* a context with nothing to draw */
    if (par) {
        AgBlock *first = &g_array_index(out, AgBlock, 0);
        add_sync(first->pre, &first->n_pre, WL_AG_SYNC_APP_BARRIER, 0);
        if (c > 0)
            add_sync(first->pre, &first->n_pre, WL_AG_SYNC_WAIT_CONTEXT, 0);
        AgBlock *last = &g_array_index(out, AgBlock, out->len - 1);
        add_sync(last->post, &last->n_post, WL_AG_SYNC_BARRIER, 0);
    }
    if (c == 0) {
        empty_block(s, c, TRUE)->clear = TRUE;
        AgBlock *swap = empty_block(s, c, FALSE);
        swap->swap = TRUE;
        if (par)
            add_sync(swap->pre, &swap->n_pre, WL_AG_SYNC_BARRIER_WAIT, 0);
    }
}

static void count_syncs(AgStreams *s)
{
    s->syncs = 0;
    for (guint c = 0; c < s->contexts; c++) {
        GArray *out = wl_ag_ctx_blocks(s, c);
        for (guint i = 0; i < out->len; i++) {
            const AgBlock *k = &g_array_index(out, AgBlock, i);
            s->syncs += k->n_pre + k->n_post;
        }
    }
}

/* The waits and signals of cell (x, y, z) of an n^3 grid. */
static void cell_syncs(guint n, guint x, guint y, guint z, AgBlock *sy)
{
    guint id = x + n * (y + n * z);
    if (z > 0)
        add_sync(sy->pre, &sy->n_pre, WL_AG_SYNC_P, id - n * n);
    if (y > 0)
        add_sync(sy->pre, &sy->n_pre, WL_AG_SYNC_P, id - n);
    if (x > 0)
        add_sync(sy->pre, &sy->n_pre, WL_AG_SYNC_P, id - 1);
    guint fronts = (z + 1 < n) + (y + 1 < n) + (x + 1 < n);
    for (guint k = 0; k < fronts; k++)
        add_sync(sy->post, &sy->n_post, WL_AG_SYNC_V, id);
}

/* Replaces the batches by one per cell of an n^3 grid, in cell order;
 * cells without triangles get empty batches (their semaphores still
 * count).  FALSE when tags are not increasing cell indices below n^3. */
static gboolean cell_batches(AgStreams *s, guint n)
{
    GArray *cells = g_array_new(FALSE, TRUE, sizeof(AgBatch));
    guint k = 0, pos = 0;
    for (guint id = 0; id < n * n * n; id++) {
        AgBatch e = {pos, 0, id, 0, 0};
        if (k < s->batches->len &&
            g_array_index(s->batches, AgBatch, k).tag == id)
            e = g_array_index(s->batches, AgBatch, k++);
        pos = e.first + e.n;
        g_array_append_val(cells, e);
    }
    gboolean ok = k == s->batches->len;
    g_array_unref(s->batches);
    s->batches = cells;
    return ok;
}

static gboolean build_cells(AgStreams *s, const SceneMesh *m, guint n,
                            guint block, AgPrim prim, gboolean sems,
                            GError **err)
{
    if (n == 0) {
        guint last =
            s->batches->len
                ? g_array_index(s->batches, AgBatch, s->batches->len - 1).tag
                : 0;
        n = (guint)ceil(cbrt((double)last + 1) - 1e-9);
    }
    if (!cell_batches(s, n)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "argus: found batch tags that are not increasing cell "
                    "indices below %u^3, expected the cells of an n x n x n "
                    "grid in order (generator: march)",
                    n);
        return FALSE;
    }
    guint C = s->contexts;
    for (guint c = 0; c < C; c++)
        for (guint z = 0; z < n; z++)
            for (guint j = (c + z) % C; j < n * n; j += C) {
                AgBlock sy = {0};
                if (sems && C > 1)
                    cell_syncs(n, j % n, j / n, z, &sy);
                emit_batch(s, m, c, j + n * n * z, &sy, block, prim);
            }
    s->sems = n * n * n;
    return TRUE;
}

AgStreams *wl_ag_streams_new(const SceneMesh *m, guint contexts, AgOrder ord,
                             AgPrim prim, guint block_tris, guint cells,
                             GError **err)
{
    g_assert(contexts >= 1 && block_tris >= 1);
    AgStreams *s = g_new0(AgStreams, 1);
    s->contexts = contexts;
    s->batches = find_batches(m, prim);
    s->ctx = g_ptr_array_new_with_free_func((GDestroyNotify)g_array_unref);
    for (guint c = 0; c < contexts; c++)
        g_ptr_array_add(s->ctx, g_array_new(FALSE, TRUE, sizeof(AgBlock)));
    gboolean ok = TRUE;
    if (ord == WL_AG_ORDER_FRAME)
        build_frame(s, m, block_tris, prim);
    else
        ok = build_cells(s, m, cells, block_tris, prim,
                         ord == WL_AG_ORDER_CELLS, err);
    if (!ok) {
        wl_ag_streams_free(s);
        return NULL;
    }
    for (guint c = 0; c < contexts; c++)
        frame_loop(s, c);
    s->barriers = 1;
    s->barrier_parties = contexts;
    count_syncs(s);
    return s;
}

void wl_ag_streams_free(AgStreams *s)
{
    if (!s)
        return;
    g_array_unref(s->batches);
    g_ptr_array_unref(s->ctx);
    g_free(s);
}

guint wl_ag_n_blocks(const AgStreams *s)
{
    guint n = 0;
    for (guint c = 0; c < s->contexts; c++)
        n += wl_ag_ctx_blocks(s, c)->len;
    return n;
}

static guint drop_from(AgSync *list, guint n, AgSyncKind k)
{
    guint j = 0;
    for (guint i = 0; i < n; i++)
        if (list[i].kind != k)
            list[j++] = list[i];
    return j;
}

void wl_ag_streams_drop(AgStreams *s, AgSyncKind k)
{
    for (guint c = 0; c < s->contexts; c++) {
        GArray *out = wl_ag_ctx_blocks(s, c);
        for (guint i = 0; i < out->len; i++) {
            AgBlock *b = &g_array_index(out, AgBlock, i);
            b->n_pre = drop_from(b->pre, b->n_pre, k);
            b->n_post = drop_from(b->post, b->n_post, k);
        }
    }
    count_syncs(s);
}

guint64 wl_ag_count_syncs(const AgStreams *s, AgSyncKind k)
{
    guint64 n = 0;
    for (guint c = 0; c < s->contexts; c++) {
        GArray *out = wl_ag_ctx_blocks(s, c);
        for (guint i = 0; i < out->len; i++) {
            const AgBlock *b = &g_array_index(out, AgBlock, i);
            for (guint j = 0; j < b->n_pre; j++)
                n += b->pre[j].kind == k;
            for (guint j = 0; j < b->n_post; j++)
                n += b->post[j].kind == k;
        }
    }
    return n;
}

static gboolean same_colour(SceneColor a, SceneColor b)
{
    return a.r == b.r && a.g == b.g && a.b == b.b;
}

/* Context c's stream under STATEFUL: its own state, set in full by its
 * first block, then the colour wherever a batch changes it. */
static uint64_t stateful_ctx(AgStreams *s, const SceneMesh *m, guint c)
{
    GArray *out = wl_ag_ctx_blocks(s, c);
    SceneColor cur = {0, 0, 0};
    for (guint i = 0; i < out->len; i++) { /* the colour set in full */
        const AgBlock *b = &g_array_index(out, AgBlock, i);
        if (b->opens && b->n > 0) {
            cur = g_array_index(m->poly_color, SceneColor, b->first);
            break;
        }
    }
    uint64_t n = 0;
    for (guint i = 0; i < out->len; i++) {
        AgBlock *b = &g_array_index(out, AgBlock, i);
        b->n_state = i == 0 ? WL_AG_STATE_ITEMS : 0;
        if (b->opens && b->n > 0) {
            SceneColor want =
                g_array_index(m->poly_color, SceneColor, b->first);
            if (i > 0 && !same_colour(want, cur))
                b->n_state = 1;
            cur = want;
        }
        n += b->n_state;
    }
    return n;
}

void wl_ag_streams_set_state(AgStreams *s, const SceneMesh *m,
                             AgStateMode mode)
{
    s->states = 0;
    for (guint c = 0; c < s->contexts; c++) {
        GArray *out = wl_ag_ctx_blocks(s, c);
        if (mode == WL_AG_STATE_STATEFUL) {
            s->states += stateful_ctx(s, m, c);
            continue;
        }
        for (guint i = 0; i < out->len; i++) {
            AgBlock *b = &g_array_index(out, AgBlock, i);
            b->n_state =
                mode == WL_AG_STATE_STATELESS ? WL_AG_STATE_ITEMS * b->n : 0;
            s->states += b->n_state;
        }
    }
}
