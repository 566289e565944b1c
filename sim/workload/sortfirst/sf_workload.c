/* sf_workload.c — the `sortfirst` workload: sort-first parallel
 * rendering of a hierarchical graphics database with migrating primitive
 * chunks and min-set or max-set bookkeeping (Mueller, seed 000).
 *
 *   workload:
 *     type: sortfirst
 *     processors: 16         # P <= 64 and <= the machine's `node` count
 *     granularity: 12        # primitives per chunk (§3.2; §4.1: 1 5 12 26)
 *     bookkeeping: maxset    # minset (§3.3) | maxset (§3.4)
 *     migration: push        # push (§3.3.2.1) | pull (§3.3.2.2, minset)
 *     mastership: fixed      # fixed | dynamic (§3.3.2.1, push)
 *     chunking: sorted       # sorted | unsorted | partially_sorted (§4.1)
 *     regions: static        # static grid | adaptive (sf_adapt.h)
 *     grid: 64               # G x G work grid of adaptive regions
 *                            # (default 64, at most the resolution)
 *     estimate: predicted    # previous frame's rectangles | current |
 *                            # predicted (previous, extrapolated a frame;
 *                            # the default: docs/validation.md, mueller97)
 *     feedback: false        # weight cells by measured work / polygon
 *     traversal: plain       # plain | flags | culled | flags_culled
 *                            # (§3.5, sf_trav.h; pull: plain)
 *     edits: {matrix: 1, execute: 1, unpost: 0, post: 0}
 *                            # per frame after the first (sf_edit.h)
 *                            # and create, add, close, prim_create,
 *                            # prim_change, prim_delete, color,
 *                            # execute_add, execute_delete, delete
 *     edit_angle_deg: 10     # rotation of a matrix edit
 *     bounding_volume: aabb  # aabb | sphere | obb | slabs (sf_bv.h);
 *                            # when given, the volume's fit is reported
 *     resolution: 256        # N x N screen
 *     check_image: true      # each frame equals the serial render
 *     cull_back: true
 *     bytes: {message: 64 B, chunk: 40 B, triangle: 36 B, instance: 8 B,
 *             cell: 4 B, request: 8 B, mastership: 16 B, edit: 96 B}
 *     database: my-db.yaml   # optional: a structure database file
 *                            # (structdb_file.h) rendered instead of the
 *                            # scene's; the scene gives the camera
 *     dump_db: db.yaml       # optional: write the database rendered
 *     frame_log: frames.csv  # optional per-frame figures (default under
 *                            # `pgsim run --out DIR`: DIR/sortfirst_frames.csv)
 *
 * With `pgsim run --out DIR` the assembled frame (the regions' pixels,
 * equal to the serial render when checked) goes through the generic
 * frame hook wl_emit_frame(): DIR/frame.png, or DIR/frame-NNNN.png for
 * every frame with --frames all.
 *
 * The scene is the config's `scene:` section and must carry a structure
 * database (the `vehicle` generator: configs/scenes/bronco.yaml); the
 * camera of frame f is the scene path's (camera speed: the scene's
 * `degrees_per_frame`; frames: run.frames).  The machine is the
 * `machine:` section (normally `model: cluster-ib`); its `node` kind
 * must have the costs of sf_frame.h.  Frames: sf_frame.h; bookkeeping:
 * sf_book.h; chunks: sf_db.h.
 *
 * Runs handed one share (WlContext.share, share.h; `pgsim reproduce
 * mueller97`'s cases) that render no image and edit nothing keep there
 * each frame rasterised once (per scene, resolution and culling) and the
 * last chunk database with its screen rectangles (per scene, chunk size,
 * chunking and resolution): the same figures as alone, computed once.
 */
#include "sim/workload/sortfirst/sf_workload.h"
#include "sim/output/provenance.h"
#include "sim/scene/scene_cfg.h"
#include "sim/scene/structdb_file.h"
#include <glib/gstdio.h>
#include <math.h>
#include <stdio.h>

static gboolean parse_bytes(const CfgNode *sec, WlSfSizes *z, GError **err)
{
    *z = (WlSfSizes){64, 40, 36, 8, 4, 8, 16, 96};
    const CfgNode *n;
    if (!cfg_get_map(sec, "bytes", FALSE,
                     "a map {message, chunk, triangle, instance, cell, "
                     "request, mastership, edit} of sizes",
                     &n,
                     err))
        return FALSE;
    if (!n)
        return TRUE;
    return cfg_get_size(n, "message", FALSE, &z->message, err) &&
           cfg_get_size(n, "chunk", FALSE, &z->chunk, err) &&
           cfg_get_size(n, "triangle", FALSE, &z->triangle, err) &&
           cfg_get_size(n, "instance", FALSE, &z->instance, err) &&
           cfg_get_size(n, "cell", FALSE, &z->cell, err) &&
           cfg_get_size(n, "request", FALSE, &z->request, err) &&
           cfg_get_size(n, "mastership", FALSE, &z->mastership, err) &&
           cfg_get_size(n, "edit", FALSE, &z->edit, err);
}

/* edits: {matrix, execute, unpost, post} counts per frame, and
 * edit_angle_deg. */
static gboolean parse_edits(const CfgNode *sec, WlSfParams *p, GError **err)
{
    const CfgNode *e = NULL;
    p->edits.angle_deg = 10;
    if (!cfg_get_map(sec, "edits", FALSE,
                     "a map {matrix, execute, unpost, post, create, add, "
                     "close, prim_create, prim_change, prim_delete, color, "
                     "execute_add, execute_delete, delete} of counts per "
                     "frame",
                     &e, err) ||
        !cfg_get_double(sec, "edit_angle_deg", FALSE, -360, 360,
                        &p->edits.angle_deg, err))
        return FALSE;
    for (int k = 0; e && k < WL_SF_ED_N; k++)
        if (!cfg_get_count(e, wl_sf_edit_names[k], FALSE, 0, 100000,
                           &p->edits.per_frame[k], err))
            return FALSE;
    if (e && !cfg_check_unused(e, err))
        return FALSE;
    p->setup.edits = wl_sf_edit_any(&p->edits);
    return TRUE;
}

static const char *const region_names[] = {"static", "adaptive", NULL};
static const char *const estimate_names[] = {"previous", "current",
                                             "predicted", NULL};

/* Pull asks a known master for what it lacks (seed 000 §3.3.2.2): the
 * paper describes it for the min-set with fixed masters, and the
 * adaptive estimate rides on push's all-to-all exchange. */
static gboolean check_pull(const CfgNode *sec, const WlSfSetup *s,
                           GError **err)
{
    const char *exp = NULL;
    if (s->mig != WL_SF_PULL)
        return TRUE;
    if (s->bk != WL_SF_MINSET)
        exp = "bookkeeping: minset (mueller97 §3.3.2.2 pulls min-set chunks)";
    else if (s->ms != WL_SF_FIXED)
        exp = "mastership: fixed (a pull asks a known, fixed master)";
    else if (s->adaptive)
        exp = "regions: static (the adaptive estimate rides on the push "
              "exchange)";
    else if (s->trav != WL_SF_TRAV_PLAIN)
        exp = "traversal: plain (mueller97 §3.3.2.2: with pull no portion "
              "of the hierarchy can be skipped over)";
    if (!exp)
        return TRUE;
    cfg_error(err, cfg_get(sec, "migration"), "migration: pull", exp);
    return FALSE;
}

static gboolean parse_policy(const CfgNode *sec, WlSfSetup *s, GError **err)
{
    int mig = WL_SF_PUSH, ms = WL_SF_FIXED;
    if (!cfg_get_enum(sec, "migration", FALSE, wl_sf_migration_names, &mig,
                      err) ||
        !cfg_get_enum(sec, "mastership", FALSE, wl_sf_mastership_names, &ms,
                      err))
        return FALSE;
    s->mig = (WlSfMigration)mig;
    s->ms = (WlSfMastership)ms;
    return check_pull(sec, s, err);
}

static gboolean parse_words(const CfgNode *sec, WlSfParams *p, GError **err)
{
    int bk = WL_SF_MAXSET, ch = WL_SF_CHUNK_SORTED, rg = 0, est = 2, tr = 0;
    int bv = WL_SF_BV_AABB;
    if (!cfg_get_enum(sec, "bookkeeping", FALSE, wl_sf_bookkeeping_names, &bk,
                      err) ||
        !cfg_get_enum(sec, "chunking", FALSE, wl_sf_chunking_names, &ch,
                      err) ||
        !cfg_get_enum(sec, "regions", FALSE, region_names, &rg, err) ||
        !cfg_get_enum(sec, "estimate", FALSE, estimate_names, &est, err) ||
        !cfg_get_bool(sec, "feedback", FALSE, &p->setup.feedback, err) ||
        !cfg_get_enum(sec, "traversal", FALSE, wl_sf_trav_names, &tr, err) ||
        !cfg_get_enum(sec, "bounding_volume", FALSE, wl_sf_bv_names, &bv,
                      err))
        return FALSE;
    p->bv = (WlSfBvKind)bv;
    p->bv_fit = cfg_get(sec, "bounding_volume") != NULL;
    p->setup.trav = (WlSfTravMode)tr;
    p->setup.current = est == 1;
    p->setup.predict = est == 2;
    p->setup.adaptive = rg == 1;
    p->setup.bk = (WlSfBookkeeping)bk;
    p->chunking = (WlSfChunking)ch;
    return parse_policy(sec, &p->setup, err);
}

/* The grid's cells must be at least a pixel. */
static gboolean check_grid(const CfgNode *sec, uint64_t grid, uint64_t res,
                           GError **err)
{
    if (grid <= res)
        return TRUE;
    char *found = g_strdup_printf("grid %" G_GUINT64_FORMAT, grid);
    char *exp = g_strdup_printf("at most the resolution (%" G_GUINT64_FORMAT
                                ")",
                                res);
    cfg_error(err, cfg_get(sec, "grid"), found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

static void sf_free_params(void *params)
{
    WlSfParams *p = params;
    if (p) {
        g_free(p->frame_log);
        g_free(p->database);
        g_free(p->dump_db);
    }
    g_free(p);
}

/* Own memory (WlOps.mem_bytes): the screen's z-buffer (depth, prim, rgba:
 * 16 B a pixel; a second one for the serial reference with check_image),
 * the adaptive work grid (a weight and a factor a cell) and each
 * processor's outgoing batches to every other (P x P, 64 B each; an
 * assumption). */
static double sf_mem_bytes(const void *params, GString *what)
{
    const WlSfParams *p = params;
    double n = p->setup.resolution, g = p->setup.grid, procs = p->setup.procs;
    g_string_append_printf(what, "%u processors, %.0f x %.0f pixels, grid %.0f",
                           p->setup.procs, n, n, g);
    return n * n * 16.0 * (p->setup.check_image ? 2 : 1) + g * g * 16.0 +
           procs * procs * 64.0;
}

static void *sf_parse(const CfgNode *sec, GError **err)
{
    WlSfParams *p = g_new0(WlSfParams, 1);
    uint64_t procs = 16, gran = 12, res = 256, grid = 0; /* 0: default */
    gboolean check = TRUE, cull = TRUE;
    const char *log = NULL, *dbf = NULL, *dump = NULL;
    gboolean ok =
        parse_words(sec, p, err) &&
        cfg_get_count(sec, "processors", FALSE, 1, WL_SF_MAX_PROCS, &procs,
                      err) &&
        cfg_get_count(sec, "granularity", FALSE, 1, 1u << 20, &gran, err) &&
        cfg_get_count(sec, "resolution", FALSE, 16, 4096, &res, err) &&
        cfg_get_count(sec, "grid", FALSE, 8, 1024, &grid, err) &&
        check_grid(sec, grid, res, err) &&
        cfg_get_bool(sec, "check_image", FALSE, &check, err) &&
        cfg_get_bool(sec, "cull_back", FALSE, &cull, err) &&
        cfg_get_str(sec, "frame_log", FALSE, &log, err) &&
        cfg_get_str(sec, "database", FALSE, &dbf, err) &&
        cfg_get_str(sec, "dump_db", FALSE, &dump, err) &&
        parse_bytes(sec, &p->setup.sizes, err) && parse_edits(sec, p, err) &&
        wl_sf_parse_costed(sec, &p->setup, err);
    if (!ok) {
        sf_free_params(p);
        return NULL;
    }
    p->setup.procs = (guint)procs;
    p->setup.resolution = (int)res;
    p->setup.grid = (guint)(grid ? grid : MIN(64, res));
    p->setup.check_image = check;
    p->setup.cull_back = cull;
    p->granularity = (guint)gran;
    p->frame_log = g_strdup(log);
    p->database = g_strdup(dbf);
    p->dump_db = g_strdup(dump);
    return p;
}

/* ---- metrics ------------------------------------------------------------- */

typedef struct {
    double chunks, polys, insts, bytes, master, slave, fresh, rendered;
    double imbalance, imbalance_max, poly_imbalance, util, frame_ms;
    double est_bytes, box_side, split_imbalance, trav_ms, tests;
    double edits, edit_bytes, edit_ms, created, collected, ptrs, gc, deleted;
    WlSfTrav trav;
    double probe, messages, requests, handovers, held, master_imb, off_max, off_total;
    uint64_t onscreen, regions, peak;
    gboolean checked, image_ok;
} Sums;

static void sum_frames(const GArray *stats, guint from, Sums *m)
{
    memset(m, 0, sizeof *m);
    m->image_ok = TRUE;
    for (guint f = 0; f < stats->len; f++) {
        const WlSfFrameStats *s = &g_array_index(stats, WlSfFrameStats, f);
        m->peak = MAX(m->peak, s->peak_memory);
        m->checked |= s->image_checked;
        m->image_ok &= !s->image_checked || s->image_ok;
        if (f < from)
            continue;
        m->chunks += s->migrated_chunks;
        m->polys += s->migrated_polys;
        m->insts += s->migrated_insts;
        m->bytes += s->migrated_bytes;
        m->master += s->master_boxes;
        m->slave += s->slave_boxes;
        m->fresh += s->new_boxes;
        m->rendered += s->polys_rendered;
        m->imbalance += s->imbalance;
        m->imbalance_max = MAX(m->imbalance_max, s->imbalance);
        m->poly_imbalance += s->poly_imbalance;
        m->est_bytes += s->estimate_bytes;
        m->split_imbalance += s->split_imbalance;
        m->requests += s->requests;
        m->probe += s->probe_boxes;
        m->trav.plain += s->trav.plain;
        m->trav.flags += s->trav.flags;
        m->trav.culled += s->trav.culled;
        m->trav.both += s->trav.both;
        m->trav.boxes_culled += s->trav.boxes_culled;
        m->tests += s->trav.tests;
        m->edits += s->edits;
        m->edit_bytes += s->edit_bytes;
        m->edit_ms += sim_time_to_ms(s->edit_busy);
        m->created += s->nodes_created;
        m->collected += s->nodes_collected;
        m->ptrs += s->pointers_collected;
        m->gc += s->chunks_collected;
        m->deleted += s->deleted_chunks;
        m->trav_ms += sim_time_to_ms(s->traverse_busy);
        m->messages += s->messages;
        m->handovers += s->handovers;
        m->held += s->held_polys;
        m->master_imb += s->master_imbalance;
        m->off_max += s->offscreen_max;
        m->off_total += s->offscreen_total;
        m->util += s->utilisation;
        m->frame_ms += sim_time_to_ms(s->end - s->start);
        m->onscreen += s->onscreen_insts;
        m->regions += s->region_insts;
        m->box_side += s->box_side;
    }
}

static void set(SimResult *out, const char *name, double v, const char *unit)
{
    sim_result_set_metric(out, name, v, unit);
}

void wl_sf_fill_metrics(SimResult *out, const GArray *stats, const WlSfDb *db,
                        const WlSfSetup *s)
{
    /* Steady state: frames after the first (which distributes from the
     * masters); a one-frame run reports its only frame. */
    guint from = stats->len > 1 ? 1 : 0;
    double n = stats->len - from;
    Sums m;
    sum_frames(stats, from, &m);
    const WlSfFrameStats *f0 = &g_array_index(stats, WlSfFrameStats, 0);
    set(out, "processors", s->procs, "");
    set(out, "granularity", db->granularity, "");
    set(out, "resolution", s->resolution, "");
    set(out, "chunks", wl_sf_n_chunks(db), "");
    set(out, "chunk_instances", wl_sf_n_insts(db), "");
    set(out, "min_set_polygons", (double)db->min_prims, "");
    set(out, "max_set_polygons", (double)scene_mesh_n_polys(db->flat), "");
    set(out, "frame_ms", m.frame_ms / n, "ms");
    set(out, "migrated_chunks_per_frame", m.chunks / n, "");
    set(out, "migrated_polygons_per_frame", m.polys / n, "");
    set(out, "migrated_pointers_per_frame", m.insts / n, "");
    set(out, "migrated_bytes_per_frame", m.bytes / n, "B");
    set(out, "initial_bytes", (double)f0->migrated_bytes, "B");
    set(out, "master_boxes_per_frame", m.master / n, "");
    set(out, "slave_boxes_per_frame", m.slave / n, "");
    set(out, "new_boxes_per_frame", m.fresh / n, "");
    set(out, "polygons_rendered_per_frame", m.rendered / n, "");
    if (s->mig == WL_SF_PULL)
        set(out, "probe_boxes_per_frame", m.probe / n, "");
    set(out, "transforms_per_frame",
        (m.master + m.slave + m.fresh + m.probe + m.rendered) / n, "");
    set(out, "messages_per_frame", m.messages / n, "");
    set(out, "chunk_overlap", m.onscreen ? (double)m.regions / m.onscreen : 0,
        "");
    /* mean box side over the mean region side √(W H / P) */
    double region = sqrt((double)s->resolution * s->resolution / s->procs);
    set(out, "box_region_ratio",
        m.onscreen ? m.box_side / m.onscreen / region : 0, "");
    set(out, "load_imbalance", m.imbalance / n, "");
    set(out, "load_imbalance_max", m.imbalance_max, "");
    set(out, "polygon_imbalance", m.poly_imbalance / n, "");
    if (s->adaptive) {
        set(out, "estimate_bytes_per_frame", m.est_bytes / n, "B");
        set(out, "split_imbalance", m.split_imbalance / n, "");
    }
    if (s->mig == WL_SF_PULL)
        set(out, "requests_per_frame", m.requests / n, "");
    if (s->ms == WL_SF_DYNAMIC)
        set(out, "handovers_per_frame", m.handovers / n, "");
    /* copies: polygons held over the min-set's (seed 000 §3.3.2.1: two
     * with fixed masters, about one with dynamic) */
    set(out, "copies", m.held / n / (double)db->min_prims, "");
    set(out, "master_polygon_imbalance", m.master_imb / n, "");
    set(out, "offscreen_master_polygons_max", m.off_max / n, "");
    set(out, "offscreen_master_polygons", m.off_total / n, "");
    /* §3.5 (sf_trav.h): structure instances scanned, all processors */
    set(out, "traversal_nodes_per_frame", m.trav.plain / n, "");
    set(out, "traversal_nodes_flags", m.trav.flags / n, "");
    set(out, "traversal_nodes_culled", m.trav.culled / n, "");
    set(out, "traversal_nodes_flags_culled", m.trav.both / n, "");
    set(out, "boxes_culled_per_frame", m.trav.boxes_culled / n, "");
    /* what the run's `traversal` mode charged: mean per processor */
    set(out, "volume_tests_per_frame", m.tests / n, "");
    set(out, "traversal_ms", m.trav_ms / n / s->procs, "ms");
    set(out, "slave_deletions_per_frame", m.deleted / n, "");
    set(out, "chunks_collected_per_frame", m.gc / n, "");
    if (s->edits) {
        set(out, "edits_per_frame", m.edits / n, "");
        set(out, "edit_bytes_per_frame", m.edit_bytes / n, "B");
        set(out, "edit_ms", m.edit_ms / n / s->procs, "ms");
        set(out, "maxset_nodes_created_per_frame", m.created / n, "");
        set(out, "maxset_nodes_collected_per_frame", m.collected / n, "");
        set(out, "pointers_collected_per_frame", m.ptrs / n, "");
    }
    set(out, "utilisation", m.util / n, "");
    set(out, "peak_memory", (double)m.peak, "B");
    wl_sf_fill_costed_metrics(out, stats, from, s);
    if (m.checked)
        set(out, "image_matches_serial", m.image_ok, "");
}

static gboolean write_log(const char *path, const GArray *stats, GError **err)
{
    GString *s = g_string_new(
        "frame,frame_ms,migrated_chunks,migrated_polygons,"
        "migrated_pointers,migrated_bytes,master_boxes,slave_boxes,"
        "new_boxes,polygons_rendered,load_max,load_min,imbalance,"
        "polygon_imbalance,utilisation,peak_memory,estimate_bytes\n");
    for (guint f = 0; f < stats->len; f++) {
        const WlSfFrameStats *t = &g_array_index(stats, WlSfFrameStats, f);
        g_string_append_printf(
            s,
            "%u,%.6f,%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT
            ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT
            ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT
            ",%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT
            ",%.6f,%.6f,%.6f,%" G_GUINT64_FORMAT ",%" G_GUINT64_FORMAT "\n",
            f, sim_time_to_ms(t->end - t->start), t->migrated_chunks,
            t->migrated_polys, t->migrated_insts, t->migrated_bytes,
            t->master_boxes, t->slave_boxes, t->new_boxes, t->polys_rendered,
            t->load_max, t->load_min, t->imbalance, t->poly_imbalance,
            t->utilisation, t->peak_memory, t->estimate_bytes);
    }
    gboolean ok = wl_frame_log_write(path, s, "sortfirst", err);
    g_string_free(s, TRUE);
    return ok;
}

/* ---- running --------------------------------------------------------------
 */

static gboolean check_procs(MachMachine *m, const WlSfSetup *s,
                            const CfgNode *at, GError **err)
{
    const MachKindInfo *k = mach_kind(m, "node");
    if (!mach_require_net(m, err))
        return FALSE;
    if (k && k->count >= s->procs &&
        net_nodes(mach_net(m)) > k->first + s->procs - 1)
        return TRUE;
    char *found = g_strdup_printf("'%u' processors", s->procs);
    char *exp = g_strdup_printf("at most the %u nodes of kind 'node' of "
                                "machine '%s'",
                                k ? k->count : 0, mach_name(m));
    if (at)
        cfg_error(err, at, found, exp);
    else
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "sortfirst: found %s, expected %s", found, exp);
    g_free(found);
    g_free(exp);
    return FALSE;
}

/* A database file that posts nothing, or whose posted structures hold
 * no primitive, has nothing to sort: every per-primitive metric would be
 * 0 / 0.  Located at the `database` key. */
static gboolean db_renders(const SceneDb *db, const CfgNode *root,
                           const char *path, GError **err)
{
    SceneDbStats st;
    scene_db_stats(db, &st);
    if (st.primitives > 0)
        return TRUE;
    char *found = g_strdup_printf(
        "database file '%s' %s", path,
        scene_db_posted_count(db) ? "whose posted structures hold no "
                                    "primitive"
                                  : "with nothing posted");
    const CfgNode *at = cfg_get(cfg_get(root, "workload"), "database");
    cfg_error(err, at ? at : root, found,
              "a structure database that posts at least one structure "
              "holding primitives (posted: [...])");
    g_free(found);
    return FALSE;
}

/* The runner's scene (its camera) with the database rendered: the
 * scene's, or the `database` file's in its place; written to `dump_db`
 * when asked. */
static gboolean load_db(const CfgNode *root, Scene *sc, const WlSfParams *p,
                        GError **err)
{
    if (p->database) {
        SceneDb *db = scene_db_load(p->database, err);
        if (!db || !db_renders(db, root, p->database, err)) {
            scene_db_free(db);
            return FALSE;
        }
        scene_set_db(sc, db);
    }
    if (sc->db && p->dump_db && !scene_db_save(sc->db, p->dump_db, err))
        return FALSE;
    if (sc->db)
        return TRUE;
    const CfgNode *sec = cfg_get(root, "scene");
    cfg_error(err, sec ? sec : root, "a scene without a structure database",
              "a hierarchical scene (e.g. generator: vehicle) or "
              "workload.database: a structure database file");
    return FALSE;
}

typedef struct {
    const WlContext *ctx;
    const Scene *scene;
} FrameOut;

/* The frame hook: the assembled regions' image through the generic
 * frame output (DIR/frame.png, or every frame with --frames all). */
static gboolean emit_frame(void *ctx, int frame, const RastZBuffer *zb,
                           GError **err)
{
    const FrameOut *o = ctx;
    if (!wl_wants_frame(o->ctx, frame))
        return TRUE;
    SceneColor c = o->scene->background;
    RastImage *img = rast_image_new(zb->width, zb->height);
    rast_image_from_zbuffer(img, zb, (RastColor){c.r, c.g, c.b});
    gboolean ok = wl_emit_frame(o->ctx, frame, img, err);
    rast_image_free(img);
    return ok;
}

/* ---- what runs of one scene share (share.h) ----------------------------- */

/* The chunk database kept for the next run, with its instances' screen
 * rectangles per frame: valid for runs of one scene, granularity,
 * chunking and resolution (P changes it only through its masters,
 * wl_sf_db_set_procs). */
typedef struct {
    char *key;
    WlSfDb *db;
    WlSfScreenSet *screens;
} SfKept;

static void kept_free(gpointer p)
{
    SfKept *k = p;
    g_free(k->key);
    wl_sf_db_free(k->db);
    wl_sf_screen_set_free(k->screens);
    g_free(k);
}

/* A run may use what earlier runs kept when it renders no image and
 * edits nothing (both change what a frame draws) and draws the scene's
 * own database. */
static gboolean shares(const WlContext *ctx, const WlSfParams *p)
{
    return ctx->share && !ctx->out_dir && !p->setup.edits &&
           !p->setup.check_image && !p->database;
}

/* The scene as configured, the resolution and culling: what each
 * frame's render depends on. */
static char *scene_key(const WlContext *ctx, const WlSfParams *p)
{
    const CfgNode *sec = cfg_get(ctx->root, "scene");
    char *json = prov_cfg_json(sec);
    char *key = g_strdup_printf("sortfirst %s %s res %d cull %d",
                                cfg_file(sec), json, p->setup.resolution,
                                p->setup.cull_back);
    g_free(json);
    return key;
}

/* A new chunk database with the run's bounding volumes. */
static WlSfDb *new_db(const WlContext *ctx, const WlSfParams *p, GError **err)
{
    WlSfDb *db = wl_sf_db_new(ctx->scene->db, p->setup.procs, p->granularity,
                              p->chunking, err);
    if (db && p->bv != WL_SF_BV_AABB)
        wl_sf_bv_set(db, ctx->scene->db, p->bv);
    return db;
}

/* The chunk database of this run: kept from an earlier run of the same
 * key (masters re-dealt for P), or new (and then kept when sharing). */
static WlSfDb *run_db(const WlContext *ctx, const WlSfParams *p,
                      const char *skey, WlSfSetup *st, GError **err)
{
    if (!skey)
        return new_db(ctx, p, err);
    char *key = g_strdup_printf("%s gran %u chunking %d bv %d", skey,
                                p->granularity, (int)p->chunking, (int)p->bv);
    SfKept *k = wl_share_get(ctx->share, "sortfirst db");
    if (!k || strcmp(k->key, key) != 0) {
        WlSfDb *db = new_db(ctx, p, err);
        if (!db) {
            g_free(key);
            return NULL;
        }
        k = g_new0(SfKept, 1);
        *k = (SfKept){key, db, wl_sf_screen_set_new()};
        wl_share_put(ctx->share, "sortfirst db", k, kept_free);
    } else {
        g_free(key);
        wl_sf_db_set_procs(k->db, p->setup.procs);
    }
    st->screens = k->screens;
    RastPrerenderSet *pre = wl_share_get(ctx->share, skey);
    if (!pre) {
        pre = rast_prerender_set_new();
        wl_share_put(ctx->share, skey, pre,
                     (GDestroyNotify)rast_prerender_set_free);
    }
    st->pre = pre;
    return k->db;
}

/* ---- running ------------------------------------------------------------- */

static gboolean run_frames(const WlContext *ctx, MachMachine *m,
                           const Scene *sc, const WlSfParams *p, SimResult *out,
                           GError **err)
{
    WlSfCosts c;
    if (!wl_sf_costs_from_machine(m, &c, err) ||
        !check_procs(m, &p->setup, cfg_path(ctx->root, "workload.processors"),
                     err))
        return FALSE;
    WlSfSetup st = p->setup;
    char *skey = shares(ctx, p) ? scene_key(ctx, p) : NULL;
    WlSfDb *db = run_db(ctx, p, skey, &st, err);
    g_free(skey);
    gboolean own = !st.screens; /* not kept for the next run */
    if (!db)
        return FALSE;
    WlSfRun *r = wl_sf_run_new(m, sc, db, &st, &c);
    WlSfEdit *ed = NULL;
    if (p->setup.edits) {
        SimEngine *eng = mach_engine(m);
        ed = wl_sf_edit_new(sc->db, db, &p->edits,
                            sim_entity_rng(eng, sim_entity_add(eng, "editor")));
        wl_sf_run_set_edit(r, ed);
    }
    FrameOut fo = {ctx, sc};
    if (ctx->out_dir) /* a hook renders every frame's image */
        wl_sf_run_set_hook(r, emit_frame, &fo);
    gboolean ok = wl_sf_run_frames(r, ctx->frames, ctx->until, err);
    const GArray *stats = wl_sf_run_stats(r);
    for (guint f = 0; ok && f < stats->len; f++) {
        const WlSfFrameStats *t = &g_array_index(stats, WlSfFrameStats, f);
        sim_result_add_frame(out, t->end - t->start);
        wl_mark_frame(mach_engine(m), f, t->end);
    }
    if (ok) { /* frames run.until cut are not in stats */
        mach_fill_result(m, out);
        out->elapsed = sim_now(mach_engine(m));
    }
    if (ok && stats->len)
        wl_sf_fill_metrics(out, stats, db, &p->setup);
    if (ok && stats->len && p->bv_fit)
        wl_sf_bv_metrics(out, sc, db, ed ? wl_sf_edit_db(ed) : sc->db,
                         &p->setup, &c, stats->len);
    char *log = wl_frame_log_path(ctx, p->frame_log, "sortfirst_frames.csv");
    if (ok && log)
        ok = write_log(log, stats, err);
    g_free(log);
    wl_sf_run_free(r);
    wl_sf_edit_free(ed);
    if (own)
        wl_sf_db_free(db);
    return ok;
}

static gboolean sf_run(const WlContext *ctx, void *params, SimResult *out,
                       GError **err)
{
    return load_db(ctx->root, ctx->scene, params, err) &&
           run_frames(ctx, ctx->machine, ctx->scene, params, out, err);
}

/* Every metric wl_sf_fill_metrics sets, in order; per-frame figures are
 * means over the frames after the first (docs/workloads.md, "sortfirst"). */
static const WlMetric sf_metrics[] = {
    {"processors", "", "P, the processors run"},
    {"granularity", "", "chunk granularity, as run"},
    {"resolution", "", "the image side in pixels, as run"},
    {"chunks", "", "chunks formed"},
    {"chunk_instances", "", "chunks x max-set instances of their structure"},
    {"min_set_polygons", "", "polygons stored once by the whole hierarchy"},
    {"max_set_polygons", "", "polygons drawn per frame by the hierarchy"},
    {"frame_ms", "ms", "frame time"},
    {"migrated_chunks_per_frame", "", "chunk data sent"},
    {"migrated_polygons_per_frame", "", "polygons of the chunk data sent"},
    {"migrated_pointers_per_frame", "", "max-set instance pointers sent"},
    {"migrated_bytes_per_frame", "B", "bytes of all messages, headers too"},
    {"initial_bytes", "B", "the first frame's bytes"},
    {"master_boxes_per_frame", "", "box transforms of master chunks"},
    {"slave_boxes_per_frame", "", "box transforms of slave chunks"},
    {"new_boxes_per_frame", "", "box transforms of newly received chunks"},
    {"polygons_rendered_per_frame", "",
     "polygons transformed for rendering, all processors"},
    {"probe_boxes_per_frame", "",
     "pull only: boxes transformed of chunks the processor lacks"},
    {"transforms_per_frame", "", "box transforms plus polygons rendered"},
    {"messages_per_frame", "", "exchange messages"},
    {"chunk_overlap", "", "mean regions per on-screen chunk instance"},
    {"box_region_ratio", "",
     "mean on-screen box side over the mean region side (Chart 3)"},
    {"load_imbalance", "", "max / mean busy time per processor, mean"},
    {"load_imbalance_max", "", "max / mean busy time, worst frame"},
    {"polygon_imbalance", "", "max / mean polygons rendered per processor"},
    {"estimate_bytes_per_frame", "B",
     "adaptive only: grid bytes riding on the exchange"},
    {"split_imbalance", "",
     "adaptive only: max / mean estimate over the split's regions"},
    {"requests_per_frame", "", "pull only: chunks requested"},
    {"handovers_per_frame", "", "dynamic only: masterships passed on"},
    {"copies", "", "polygons held by all processors / min-set polygons"},
    {"master_polygon_imbalance", "",
     "max / mean master polygons per processor"},
    {"offscreen_master_polygons_max", "",
     "most master polygons off screen held by one processor"},
    {"offscreen_master_polygons", "", "all master polygons off screen"},
    {"traversal_nodes_per_frame", "",
     "sec. 3.5: structure instances scanned, plain traversal"},
    {"traversal_nodes_flags", "",
     "sec. 3.5: structure instances scanned with empty flags"},
    {"traversal_nodes_culled", "",
     "sec. 3.5: structure instances scanned with volume culling"},
    {"traversal_nodes_flags_culled", "",
     "sec. 3.5: structure instances scanned with flags and culling"},
    {"boxes_culled_per_frame", "",
     "sec. 3.5: chunk boxes skipped under a culled subtree"},
    {"volume_tests_per_frame", "",
     "sec. 3.5: bounding-volume tests under the run's traversal"},
    {"traversal_ms", "ms", "phase traverse, mean per processor per frame"},
    {"slave_deletions_per_frame", "", "slave copies deleted"},
    {"chunks_collected_per_frame", "",
     "slave copies of chunks no instance references any more"},
    {"edits_per_frame", "", "edits only: commands applied"},
    {"edit_bytes_per_frame", "B",
     "edits only: command messages and the pointers they created"},
    {"edit_ms", "ms", "edits only: phase edit per processor per frame"},
    {"maxset_nodes_created_per_frame", "",
     "edits only: max-set nodes the edits created"},
    {"maxset_nodes_collected_per_frame", "",
     "edits only: max-set nodes the edits made obsolete"},
    {"pointers_collected_per_frame", "",
     "edits only: instance pointers garbage-collected"},
    {"bv_area_ratio", "",
     "bounding_volume only: screen area of the volumes over that of the "
     "chunks' vertices, on-screen instances of every frame"},
    {"bv_false_regions_per_polygon", "",
     "bounding_volume only: regions a volume reaches and its vertices do "
     "not, per polygon"},
    {"bv_test_ns", "ns", "bounding_volume only: one volume test's price"},
    {"utilisation", "", "busy time / (P x frame time), mean over frames"},
    {"peak_memory", "B", "the largest processor store"},
    {"offscreen_spread_per_frame", "", "dynamic only: off-screen moved"},
    {"interrupt_ms", "ms", "pull only: request interrupts, all masters"},
    {"framebuffer_bytes_per_frame", "B", "framebuffer only: pixels sent"},
    {"assembly_ms", "ms", "framebuffer only: its assembly a frame"},
    {"image_matches_serial", "",
     "1 when every checked frame equalled the serial render"},
    {NULL, NULL, NULL},
};

const WlOps wl_sortfirst_ops = {
    .name = "sortfirst",
    .summary = "mueller97: sort-first rendering of a hierarchical database "
               "with migrating primitive chunks, min-set or max-set "
               "bookkeeping",
    .parse = sf_parse,
    .free_params = sf_free_params,
    .plan = wl_plan_machine_scene,
    .run = sf_run,
    .mem_bytes = sf_mem_bytes,
    .needs = wl_sf_needs,
    .metrics = sf_metrics,
};
