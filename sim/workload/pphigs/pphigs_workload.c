/* pphigs_workload.c — the `pphigs` workload: a display list distributed over
 * the GPs of Pixel-Planes 5 (seed 001), drawn frame after frame on the
 * event-driven model (pphigs_frame.h), with per-frame matrix edits (§1.3, §3.1:
 * "changing only a few transformation matrices") and rebalancing (§5).
 *
 * workload section:
 *   type: pphigs
 *   algorithm: simple | complex        (default complex)
 *   gps: 1..64                          (default: the machine's GP count;
 *                                        given, it sets nodes.gp.count)
 *   database: a name in `databases` (the four of seed 001), or a
 *             structure database file (a path ending in .yaml or .yml,
 *             sim/scene/structdb_file.h), read when the config is
 *             loaded and viewed with scene_pphigs_fit_view()
 *   databases: generator parameters (configs/pphigs/databases.yaml;
 *              not needed with a file)
 *   dump_db: writes the database drawn (generated or read) to a file
 *   frame: frame sizes and clustering (configs/pphigs/frame.yaml)
 *   edits_per_frame: matrix modifies per frame (default 0)
 *   edit_angle_deg: rotation each edit applies (default 0)
 *   rebalance: {enabled, threshold, frames, fraction, max_moves}
 *   region_assignment: dynamic | static (default dynamic: a renderer
 *                      takes the next 128x128 region when it finishes
 *                      one, as Pixel-Planes 5's renderers "can be
 *                      independently reassigned to any part of the
 *                      screen", fuchs89 abstract; static: region k is
 *                      renderer k mod R's; pphigs_frame.h)
 *   inheritance: skeleton | precompute (by_structure only; default
 *                skeleton): §2.1's two ways of giving a GP the
 *                attributes its pieces inherit (pphigs_bystruct.c)
 *   attribute_send: all | by_kind (complex; default all): §3.5's choice,
 *                   each attribute with any primitive or only with
 *                   primitives of the type it affects
 *   attr_cache_every: §3.4's attribute states saved every N dealt
 *                     elements of a structure (complex; default 0: no
 *                     cache, the step back stops only as §3.5 says)
 * Relative paths are found as project data files (sim/core/datapath.h)
 * and read when the config is loaded.  The machine is the run
 * config's `machine` section (default: model pixel-planes-5), built by
 * the machine layer at the run's fidelity; `run.until` ends the run
 * after the frame that crosses it.
 * Metrics: frame time, GP and renderer utilisation (busy / elapsed),
 * ring bytes and commands per frame, edits, elements the host sent per
 * frame (edits and moves go over the ring before the frame that needs
 * them, frame.h), rebalancing moves, and seed
 * 001 §6's distribution efficiency, processor utilisation and speed-up
 * of the last frame (GP processor times are its traverse + transform
 * busy times; T1 is the host list's traversal cost, metrics.h, which is
 * what a one-GP frame's busy time is, to the picosecond); the renderers'
 * linear expressions per frame, and image_matches_serial: the frame the
 * renderers drew and the frame buffer assembled equals a serial render
 * of the whole list (pphigs_pixels.h).  With --out DIR the frames go
 * through wl_emit_frame() (DIR/frame.png, or every frame with --frames
 * all).
 * Cost per frame: the frame's (pphigs_frame.h) plus O(host size) per edit.
 */
#include "sim/workload/pphigs/pphigs_pixels.h"
#include "sim/workload/pphigs/pphigs_cfg.h"
#include "sim/workload/pphigs/pphigs_metrics.h"
#include "sim/workload/pphigs/pphigs_rebalance.h"
#include "sim/machine/model.h"
#include "sim/scene/scene_limits.h"
#include "sim/scene/structdb_file.h"
#include "sim/workload/workload.h"
#include <string.h>

/* Edit kinds a frame may carry (seed 001 §3), in the order they run. */
enum { ED_MODIFY, ED_APPEND, ED_INSERT, ED_DELETE, ED_UNPOST, ED_POST, ED_N };
static const char *const edit_names[ED_N] = {"modify", "append", "insert",
                                             "delete", "unpost", "post"};

typedef struct {
    int algo;
    int regions; /* 0: dynamic, 1: static (region_assignment) */
    int inherit; /* WlPphigsInherit (inheritance) */
    int attr_send; /* WlPphigsAttrSend (attribute_send) */
    int64_t gps; /* 0: the machine's count */
    ScenePphigsSpec spec;
    SceneDb *file_db; /* workload.database as a file (owned), else NULL */
    char *dump_db;    /* workload.dump_db, or NULL */
    WlPphigsSetup setup;
    uint64_t edits[ED_N]; /* per frame, of each kind */
    uint64_t attr_cache;  /* §3.4 checkpoint interval, 0: none */
    double edit_angle;
    gboolean rebalance;
    WlPphigsRebalParams rb;
} Params;

static void params_free(void *params)
{
    Params *p = params;
    if (!p)
        return;
    scene_db_free(p->file_db);
    g_free(p->dump_db);
    g_free(p);
}

/* Own memory (WlOps.mem_bytes): the PPHIGS database the workload
 * generates from its spec (not a `scene:` section, so not checked as
 * one): every polygon, boids and well included, at SCENE_POLY_BYTES per
 * triangle of its fan. */
static double mem_bytes(const void *params, GString *what)
{
    const Params *p = params;
    if (p->file_db) { /* read already: its copies, host and GPs */
        SceneDbStats st;
        scene_db_stats(p->file_db, &st);
        g_string_append_printf(what, "a database of %" G_GUINT64_FORMAT
                               " primitive instances", st.primitives);
        return 2.0 * (double)st.primitives * SCENE_POLY_BYTES;
    }
    const ScenePphigsSpec *s = &p->spec;
    double polys = (double)s->polygons + (double)s->boids * s->boid_polygons +
                   s->well_polygons + s->overlays;
    g_string_append_printf(what, "a database of %.0f polygons of %u vertices",
                           polys, s->verts);
    return polys * SCENE_POLY_BYTES * MAX(1.0, s->verts - 2.0);
}

static gboolean parse_rebalance(const CfgNode *sec, Params *p, GError **err)
{
    const CfgNode *r = cfg_get(sec, "rebalance");
    uint64_t frames = p->rb.frames, moves = p->rb.max_moves;
    if (!r)
        return TRUE;
    gboolean ok =
        cfg_get_bool(r, "enabled", FALSE, &p->rebalance, err) &&
        cfg_get_double(r, "threshold", FALSE, 1e-6, 1, &p->rb.threshold, err) &&
        cfg_get_count(r, "frames", FALSE, 1, 1000000, &frames, err) &&
        cfg_get_double(r, "fraction", FALSE, 1e-6, 1, &p->rb.fraction, err) &&
        cfg_get_count(r, "max_moves", FALSE, 1, 1000000, &moves, err);
    p->rb.frames = (guint)frames;
    p->rb.max_moves = (guint)moves;
    return ok;
}

/* Loads the database spec (or the database file) and the frame setup
 * the section names. */
static gboolean parse_files(const CfgNode *sec, Params *p, GError **err)
{
    const char *db = NULL, *dbs = NULL, *fr = NULL, *dump = NULL;
    if (!cfg_get_str(sec, "database", TRUE, &db, err))
        return FALSE;
    gboolean file = wl_pphigs_is_db_file(db);
    if (!cfg_get_str(sec, "databases", !file, &dbs, err) ||
        !cfg_get_str(sec, "frame", TRUE, &fr, err) ||
        !cfg_get_str(sec, "dump_db", FALSE, &dump, err))
        return FALSE;
    p->dump_db = g_strdup(dump);
    const CfgNode *at = cfg_get(sec, "database");
    gboolean ok = file ? (p->file_db = wl_pphigs_db_file_load(db, at, err))
                             != NULL
                       : wl_pphigs_spec_load(dbs, db, at, &p->spec, err);
    return ok && wl_pphigs_setup_load(fr, &p->setup, err);
}

/* edits_per_frame (matrix modifies, the older key) or edits: {kind: n}. */
static gboolean parse_edits(const CfgNode *sec, Params *p, GError **err)
{
    int64_t modifies = 0;
    const CfgNode *e = NULL;
    if (!cfg_get_int(sec, "edits_per_frame", FALSE, 0, 1000000, &modifies,
                     err) ||
        !cfg_get_map(sec, "edits", FALSE,
                     "a map {modify, append, insert, delete, unpost, post} of counts",
                     &e, err))
        return FALSE;
    p->edits[ED_MODIFY] = (uint64_t)modifies;
    if (!e)
        return TRUE;
    if (cfg_get(sec, "edits_per_frame") && cfg_get(e, "modify")) {
        cfg_error(err, cfg_get(e, "modify"),
                  "both edits.modify and edits_per_frame",
                  "one of them (edits_per_frame is edits.modify)");
        return FALSE;
    }
    for (int k = 0; k < ED_N; k++)
        if (!cfg_get_count(e, edit_names[k], FALSE, 0, 1000000, &p->edits[k],
                           err))
            return FALSE;
    return cfg_check_unused(e, err);
}

/* Distribute-by-structure has no editing procedure (§2.1 was rejected
 * before §3 was designed): no edits, no rebalancing moves. */
static gboolean check_by_structure(const CfgNode *sec, Params *p,
                                   GError **err)
{
    if (p->algo != WL_PPHIGS_BY_STRUCTURE) {
        if (!cfg_get(sec, "inheritance"))
            return TRUE;
        cfg_error(err, cfg_get(sec, "inheritance"),
                  "inheritance without algorithm by_structure",
                  "algorithm: by_structure (§2.1's inheritance methods; "
                  "by primitive, attributes follow §2.3.1)");
        return FALSE;
    }
    uint64_t edits = 0;
    for (int k = 0; k < ED_N; k++)
        edits += p->edits[k];
    const CfgNode *rb = cfg_get(sec, "rebalance");
    if (edits || (rb && p->rebalance)) {
        cfg_error(err, cfg_get(sec, "algorithm"),
                  "by_structure with edits or rebalancing",
                  "simple or complex for edits and rebalancing "
                  "(distribute-by-structure has no editing procedure)");
        return FALSE;
    }
    p->rebalance = FALSE;
    return TRUE;
}

static void *parse(const CfgNode *sec, GError **err)
{
    static const char *const algos[] = {"simple", "complex", "by_structure",
                                        NULL};
    static const char *const assign[] = {"dynamic", "static", NULL};
    static const char *const inherit[] = {"skeleton", "precompute", NULL};
    static const char *const send[] = {"all", "by_kind", NULL};
    Params *p = g_new0(Params, 1);
    p->algo = WL_PPHIGS_COMPLEX;
    p->rebalance = TRUE;
    p->rb = (WlPphigsRebalParams){0.10, 3, 0.5, 16, 1};
    gboolean ok = cfg_get_enum(sec, "algorithm", FALSE, algos, &p->algo, err) &&
                  cfg_get_int(sec, "gps", FALSE, 1, 64, &p->gps, err) &&
                  cfg_get_enum(sec, "region_assignment", FALSE, assign,
                               &p->regions, err) &&
                  cfg_get_enum(sec, "inheritance", FALSE, inherit,
                               &p->inherit, err) &&
                  cfg_get_enum(sec, "attribute_send", FALSE, send,
                               &p->attr_send, err) &&
                  parse_edits(sec, p, err) &&
                  cfg_get_double(sec, "edit_angle_deg", FALSE, -360, 360,
                                 &p->edit_angle, err) &&
                  cfg_get_count(sec, "attr_cache_every", FALSE, 0, 1000000,
                                &p->attr_cache, err) &&
                  parse_rebalance(sec, p, err) && parse_files(sec, p, err) &&
                  check_by_structure(sec, p, err);
    if (!ok) {
        params_free(p);
        return NULL;
    }
    return p;
}

/* ---- the machine ------------------------------------------------------ */

/* workload.gps and machine.nodes.gp.count must not disagree. */
static gboolean check_gps(const WlContext *ctx, const CfgNode *mach,
                          int64_t gps, GError **err)
{
    const CfgNode *gp = cfg_path(mach, "nodes.gp");
    uint64_t n = 0;
    if (!gps || !gp || !mach_param_node(gp, "count") ||
        !mach_param_count(gp, "count", TRUE, &n, NULL) || n == (uint64_t)gps)
        return TRUE;
    char *found =
        g_strdup_printf("gps %" G_GINT64_FORMAT " while "
                        "machine.nodes.gp.count is %" G_GUINT64_FORMAT,
                        gps, n);
    cfg_error(err, cfg_path(ctx->root, "workload.gps"), found,
              "one GP count (set workload.gps or machine.nodes.gp.count, "
              "or both to the same value)");
    g_free(found);
    return FALSE;
}

/* Pixel-Planes 5 unless the config names a machine; `gps` stands for
 * nodes.gp.count (check_gps refuses two different counts). */
static void plan(const void *params, WlPlan *plan)
{
    const Params *p = params;
    plan->reads = WL_READS_MACHINE;
    plan->default_model = "pixel-planes-5";
    if (p->gps)
        g_ptr_array_add(plan->machine_set,
                        g_strdup_printf("nodes.gp.count=%" G_GINT64_FORMAT,
                                        p->gps));
}

/* ---- one run ---------------------------------------------------------- */

typedef struct {
    const Params *p;
    MachMachine *m; /* borrowed from the runner */
    ScenePphigsDb db;
    WlPphigsDist *d;
    WlPphigsFrame *frame;
    WlPphigsRebal *rb;
    SimRng *rng;
    guint ngp;
    uint64_t edits[ED_N], moves, commands, host_elems, exprs;
    uint64_t drawn; /* on-screen primitive instances, all frames */
    GArray *unposted; /* guint structure ids, unposted by edits */
    gboolean image_ok; /* the last frame equals the serial render */
    uint64_t sent[64]; /* WlPphigsTraffic.sent_to at the last frame */
    WlPphigsTraffic scan0; /* after the distribution */
    uint64_t scanned;      /* total_scan + cache_walk charged so far */
    double imbalance;
    double rate_gp, rate_frame; /* on-screen primitives / s of the last
                                   frame: over the busiest GP's time, over
                                   the frame time */
    WlPphigsMetrics paper; /* seed 001 §6, of the last frame */
    SceneDbStats db_st;    /* the database as drawn, before any edit */
    double db_offscreen;   /* its off-screen share under the camera */
} Run;

/* The database drawn: a copy of the file's, or generated; written to
 * dump_db when asked. */
static gboolean make_db(Run *r, GError **err)
{
    if (r->p->file_db) {
        r->db.db = scene_db_copy(r->p->file_db);
        r->db.camera = scene_pphigs_fit_view(r->db.db);
    } else if (!scene_pphigs_generate(&r->p->spec, &r->db, err)) {
        return FALSE;
    }
    scene_db_stats(r->db.db, &r->db_st);
    r->db_offscreen = scene_pphigs_offscreen_share(
        r->db.db, scene_camera_view_proj(&r->db.camera));
    return !r->p->dump_db || scene_db_save(r->db.db, r->p->dump_db, err);
}

static gboolean build(Run *r, const WlContext *ctx, GError **err)
{
    r->m = ctx->machine;
    if (!check_gps(ctx, cfg_get(ctx->root, "machine"), r->p->gps, err))
        return FALSE;
    WlPphigsFrameSpec fs = r->p->setup.frame;
    fs.dynamic_regions = r->p->regions == 0;
    r->frame = wl_pphigs_frame_new(r->m, &fs, err);
    if (!r->frame || !make_db(r, err))
        return FALSE;
    r->ngp = wl_pphigs_frame_gps(r->frame);
    WlPphigsWeights w;
    wl_pphigs_weights_from_costs(
        wl_pphigs_frame_costs(r->frame),
        wl_pphigs_cluster_factor(r->p->setup.cluster_scale, r->ngp), &w);
    w.strip_split = r->p->setup.strip_split;
    w.attr_cache = (guint)r->p->attr_cache;
    w.inherit = (WlPphigsInherit)r->p->inherit;
    w.attr_send = (WlPphigsAttrSend)r->p->attr_send;
    r->d = wl_pphigs_dist_new(r->db.db, r->ngp, (WlPphigsAlgo)r->p->algo, &w);
    r->scan0 = *wl_pphigs_dist_traffic(r->d);
    r->scanned = r->scan0.total_scan + r->scan0.cache_walk;
    memcpy(r->sent, wl_pphigs_dist_traffic(r->d)->sent_to, sizeof r->sent);
    WlPphigsRebalParams rb = r->p->rb;
    rb.seed = ctx->seed;
    r->rb = r->p->rebalance ? wl_pphigs_rebal_new(&rb) : NULL;
    r->rng = sim_entity_rng(ctx->eng, sim_entity_add(ctx->eng, "host"));
    r->unposted = g_array_new(FALSE, FALSE, sizeof(guint));
    return TRUE;
}

static void run_clear(Run *r)
{
    wl_pphigs_rebal_free(r->rb);
    wl_pphigs_frame_free(r->frame);
    wl_pphigs_dist_free(r->d);
    if (r->unposted)
        g_array_unref(r->unposted);
    if (r->db.db)
        scene_pphigs_db_clear(&r->db);
}

/* ---- edits (seed 001 §3) --------------------------------------------- */

typedef gboolean (*ElemPred)(const SceneElem *e);

static gboolean is_matrix(const SceneElem *e)
{
    return e->kind == SCENE_EL_MATRIX;
}

static gboolean is_prim(const SceneElem *e)
{
    return scene_elem_is_prim(e->kind);
}

/* A random element of the host list satisfying pred: FALSE if none. */
static gboolean pick(Run *r, ElemPred pred, guint *sid, guint *pos)
{
    const SceneDb *h = wl_pphigs_dist_host(r->d);
    GArray *at = g_array_new(FALSE, FALSE, sizeof(guint) * 2);
    for (guint s = 0; s < scene_db_struct_count(h); s++)
        for (guint i = 0; i < scene_db_len(h, s); i++)
            if (pred(scene_db_elem(h, s, i))) {
                guint sp[2] = {s, i};
                g_array_append_val(at, sp);
            }
    gboolean any = at->len > 0;
    if (any) {
        guint *sp = (guint *)at->data + 2 * sim_rng_below(r->rng, at->len);
        *sid = sp[0], *pos = sp[1];
    }
    g_array_unref(at);
    return any;
}

/* A modify of a random matrix element (§3.1: rotate it). */
static gboolean edit_modify(Run *r)
{
    guint sid, pos;
    if (!pick(r, is_matrix, &sid, &pos))
        return FALSE;
    SceneElem e = *scene_db_elem(wl_pphigs_dist_host(r->d), sid, pos);
    double a = r->p->edit_angle * G_PI / 180;
    e.matrix = mat4_mul(e.matrix, mat4_rotate(vec3(0, 1, 0), a));
    gboolean ok = wl_pphigs_dist_modify(r->d, sid, pos, &e, NULL);
    g_assert(ok);
    return TRUE;
}

/* A copy of a random primitive, appended to its structure or inserted
 * at a random position of it (§3.2). */
static gboolean edit_add(Run *r, gboolean append)
{
    guint sid, pos;
    if (!pick(r, is_prim, &sid, &pos))
        return FALSE;
    const SceneDb *h = wl_pphigs_dist_host(r->d);
    SceneElem e = *scene_db_elem(h, sid, pos);
    e.verts = g_memdup2(e.verts, e.nverts * sizeof *e.verts);
    guint at = sim_rng_below(r->rng, scene_db_len(h, sid) + 1);
    gboolean ok = append ? wl_pphigs_dist_append(r->d, sid, &e, NULL)
                         : wl_pphigs_dist_insert(r->d, sid, at, &e, NULL);
    g_assert(ok);
    g_free(e.verts);
    return TRUE;
}

static gboolean edit_delete(Run *r)
{
    guint sid, pos;
    if (!pick(r, is_prim, &sid, &pos))
        return FALSE;
    wl_pphigs_dist_delete(r->d, sid, pos);
    return TRUE;
}

/* Unposts a random posted structure; post re-posts the one unposted
 * last (§3.3: posting and unposting whole structures). */
static gboolean edit_post(Run *r, gboolean post)
{
    const SceneDb *h = wl_pphigs_dist_host(r->d);
    if (post) {
        if (!r->unposted->len)
            return FALSE;
        guint sid = g_array_index(r->unposted, guint, r->unposted->len - 1);
        g_array_set_size(r->unposted, r->unposted->len - 1);
        wl_pphigs_dist_post(r->d, sid);
        return TRUE;
    }
    guint n = scene_db_posted_count(h);
    if (!n)
        return FALSE;
    guint sid = scene_db_posted_at(h, sim_rng_below(r->rng, n));
    wl_pphigs_dist_unpost(r->d, sid);
    g_array_append_val(r->unposted, sid);
    return TRUE;
}

static gboolean edit_kind(Run *r, int kind)
{
    switch (kind) {
    case ED_MODIFY:
        return edit_modify(r);
    case ED_APPEND:
    case ED_INSERT:
        return edit_add(r, kind == ED_APPEND);
    case ED_DELETE:
        return edit_delete(r);
    default:
        return edit_post(r, kind == ED_POST);
    }
}

/* The frame's edits, kind by kind; structural ones end with the
 * distribution's second step and the ODP deltas (§3.2, §4). */
static void edit_frame(Run *r)
{
    gboolean structural = FALSE;
    for (int k = 0; k < ED_N; k++)
        for (uint64_t i = 0; i < r->p->edits[k]; i++)
            if (edit_kind(r, k)) {
                r->edits[k]++;
                structural = structural || k != ED_MODIFY;
            }
    if (structural)
        wl_pphigs_dist_finish(r->d);
}

/* Elements sent to each GP since the last frame (edits, moves), and
 * the elements the host examined to send them (§3.4-3.5). */
static void host_elems(Run *r, uint64_t *out)
{
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(r->d);
    uint64_t scanned = t->total_scan + t->cache_walk;
    wl_pphigs_frame_host_scan(r->frame, scanned - r->scanned);
    r->scanned = scanned;
    const uint64_t *now = wl_pphigs_dist_traffic(r->d)->sent_to;
    for (guint g = 0; g < r->ngp; g++) {
        out[g] = now[g] - r->sent[g];
        r->sent[g] = now[g];
    }
}

static gboolean one_frame(Run *r, SimResult *out, GError **err)
{
    edit_frame(r);
    uint64_t elems[64];
    host_elems(r, elems);
    WlPphigsFrameStats st;
    Mat4 vp = scene_camera_view_proj(&r->db.camera);
    if (!wl_pphigs_frame_run(r->frame, r->d, vp, elems, &st, err))
        return FALSE;
    if (sim_engine_cut(mach_engine(r->m)))
        return TRUE; /* run.until ended the run inside this frame */
    r->host_elems += st.host_elements;
    sim_result_add_frame(out, st.time);
    wl_mark_frame(mach_engine(r->m), out->frame_times->len - 1,
                  sim_now(mach_engine(r->m)));
    r->commands += st.commands;
    r->exprs += st.expressions;
    r->drawn += st.primitives - st.offscreen;
    r->imbalance = wl_pphigs_imbalance(st.gp_time_us, r->ngp);
    const WlPphigsCosts *c = wl_pphigs_frame_costs(r->frame);
    double t1 = sim_time_to_us(
        wl_pphigs_traversal_cost(wl_pphigs_dist_host(r->d), vp, c));
    wl_pphigs_metrics_from(t1, st.gp_time_us, r->ngp, &r->paper);
    double drawn = (double)(st.primitives - st.offscreen);
    r->rate_gp = r->paper.max > 0 ? drawn / (r->paper.max * 1e-6) : 0;
    r->rate_frame = st.time > 0 ? drawn / sim_time_to_s(st.time) : 0;
    if (r->rb) {
        WlPphigsRebalStep rs;
        wl_pphigs_rebal_frame(r->rb, r->d, vp, wl_pphigs_frame_costs(r->frame),
                              st.gp_time_us, &rs);
        r->moves = rs.total_moves;
    }
    return TRUE;
}

/* §3.4-3.5's step back per frame: elements the backward scans examined
 * and the host elements walked to place cache checkpoints (after the
 * initial distribution). */
static void fill_step_back(Run *r, SimResult *out, double n)
{
    const WlPphigsTraffic *t = wl_pphigs_dist_traffic(r->d);
    sim_result_set_metric(out, "step_back_elements_per_frame",
                          (double)(t->total_scan - r->scan0.total_scan) / n,
                          "");
    sim_result_set_metric(out, "step_back_max_elements", (double)t->max_scan,
                          "");
    sim_result_set_metric(out, "attr_cache_walk_per_frame",
                          (double)(t->cache_walk - r->scan0.cache_walk) / n,
                          "");
}

/* Edits of each kind (the structural kinds only when asked for, so runs
 * without them report as before), the step back (the same) and the
 * host's edit time per frame. */
static void fill_edits(Run *r, const WlContext *ctx, SimResult *out)
{
    double n = MAX(out->frame_times->len, 1);
    gboolean structural = r->p->attr_cache > 0;
    for (int k = ED_APPEND; k < ED_N; k++)
        if (r->p->edits[k]) {
            char *name = g_strdup_printf("edits_%s", edit_names[k]);
            sim_result_set_metric(out, name, (double)r->edits[k], "");
            g_free(name);
            structural = TRUE;
        }
    if (structural)
        fill_step_back(r, out, n);
    MachProc *host = mach_proc(r->m, "host", 0);
    unsigned ph = sim_engine_phase(ctx->eng, "edit");
    sim_result_set_metric(out, "host_edit_ms_per_frame",
                          sim_time_to_us(mach_proc_busy_phase(host, ph)) / 1e3 / n,
                          "ms");
}

/* The database as drawn, before any edit (seed 001 §6's database
 * table): its counts and its off-screen share. */
static void fill_db(const Run *r, SimResult *out)
{
    sim_result_set_metric(out, "db_depth", r->db_st.depth, "");
    sim_result_set_metric(out, "db_structures", (double)r->db_st.instances,
                          "");
    sim_result_set_metric(out, "db_primitives", (double)r->db_st.primitives,
                          "");
    sim_result_set_metric(out, "db_attributes", (double)r->db_st.attributes,
                          "");
    sim_result_set_metric(out, "db_offscreen_pct", 100 * r->db_offscreen, "%");
}

/* GPs whose portion holds no primitive instance (seed 001 §2.2's
 * cube: "the last 2 processors execute empty structures"), and the
 * last frame's primitive rates. */
static void fill_idle(const Run *r, SimResult *out)
{
    guint idle = 0;
    for (guint g = 0; g < r->ngp; g++) {
        SceneDbStats st;
        scene_db_stats(wl_pphigs_dist_gp(r->d, g), &st);
        idle += st.primitives == 0;
    }
    sim_result_set_metric(out, "gps_without_primitives", idle, "");
    sim_result_set_metric(out, "gp_polygons_per_s", r->rate_gp, "1/s");
    sim_result_set_metric(out, "frame_polygons_per_s", r->rate_frame, "1/s");
    double bytes = r->p->setup.frame.element_bytes;
    sim_result_set_metric(out, "distribution_elements",
                          (double)r->scan0.elements_sent, "");
    sim_result_set_metric(out, "distribution_attributes",
                          (double)r->scan0.attrs_sent, "");
    sim_result_set_metric(out, "distribution_bytes",
                          bytes * (double)r->scan0.elements_sent, "B");
}

static void fill(Run *r, const WlContext *ctx, SimResult *out)
{
    SimTime now = sim_now(ctx->eng);
    NetNet *net = mach_net(r->m);
    out->elapsed = now;
    mach_fill_result(r->m, out);
    double gu, ru;
    wl_pphigs_frame_util(r->frame, now, &gu, &ru);
    double n = MAX(out->frame_times->len, 1);
    sim_result_set_metric(out, "frame_ms", sim_result_mean_frame_s(out) * 1e3,
                          "ms");
    sim_result_set_metric(out, "gp_util_pct", 100 * gu, "%");
    sim_result_set_metric(out, "renderer_util_pct", 100 * ru, "%");
    sim_result_set_metric(out, "ring_bytes_per_frame",
                          (double)net_total_bytes(net) / n, "B");
    sim_result_set_metric(out, "commands_per_frame", r->commands / n, "");
    sim_result_set_metric(out, "gps", r->ngp, "");
    sim_result_set_metric(out, "last_imbalance_pct", 100 * r->imbalance, "%");
    sim_result_set_metric(out, "edits", (double)r->edits[ED_MODIFY], "");
    sim_result_set_metric(out, "host_elements_per_frame",
                          (double)r->host_elems / n, "");
    sim_result_set_metric(out, "rebalance_moves", (double)r->moves, "");
    sim_result_set_metric(out, "distribution_efficiency_pct",
                          100 * r->paper.efficiency, "%");
    sim_result_set_metric(out, "processor_utilisation_pct",
                          100 * r->paper.utilisation, "%");
    sim_result_set_metric(out, "speedup", r->paper.speedup, "");
    sim_result_set_metric(out, "expressions_per_frame", r->exprs / n, "");
    sim_result_set_metric(out, "image_matches_serial", r->image_ok, "");
    fill_edits(r, ctx, out);
    fill_db(r, out);
    double rlo, rhi;
    wl_pphigs_frame_rend_range(r->frame, now, &rlo, &rhi);
    sim_result_set_metric(out, "renderer_util_min_pct", 100 * rlo, "%");
    sim_result_set_metric(out, "renderer_util_max_pct", 100 * rhi, "%");
    fill_idle(r, out);
    /* one scene, three sorts (docs/sorts.md): the sort's own traffic and
     * Molnar's overlap factor */
    const WlPphigsFrameSpec *fs = &r->p->setup.frame;
    double pixels = (double)fs->width * fs->height * fs->pixel_bytes;
    sim_result_set_metric(out, "sort_bytes_per_frame",
                          (double)net_total_bytes(net) / n - pixels, "B");
    sim_result_set_metric(out, "region_overlap",
                          r->drawn ? (double)r->commands / r->drawn : 0, "");
}

/* The last frame against a serial render of the host's list. */
static void check_image(Run *r)
{
    const RastImage *img = wl_pphigs_frame_image(r->frame);
    RastImage *ref = wl_pphigs_render_serial(
        wl_pphigs_dist_host(r->d), scene_camera_view_proj(&r->db.camera),
        (guint)img->width, (guint)img->height);
    r->image_ok = rast_image_equal(img, ref);
    rast_image_free(ref);
}

static gboolean run(const WlContext *ctx, void *params, SimResult *out,
                    GError **err)
{
    Run r = {.p = params};
    gboolean ok = build(&r, ctx, err);
    for (int f = 0; ok && f < ctx->frames && !sim_engine_cut(ctx->eng); f++)
        ok = one_frame(&r, out, err) &&
             (sim_engine_cut(ctx->eng) ||
              wl_emit_frame(ctx, f, wl_pphigs_frame_image(r.frame), err));
    if (ok && sim_engine_cut(ctx->eng)) {
        mach_fill_result(r.m, out);
        out->elapsed = sim_now(ctx->eng);
    } else if (ok) {
        check_image(&r);
        fill(&r, ctx, out);
    }
    run_clear(&r);
    return ok;
}

/* Every metric run() sets, in order (docs/workloads.md, "pphigs"). */
static const WlMetric pphigs_metrics[] = {
    {"frame_ms", "ms", "mean frame time"},
    {"gp_util_pct", "%", "busy / simulated time, mean over GPs"},
    {"renderer_util_pct", "%", "busy / simulated time, mean over renderers"},
    {"ring_bytes_per_frame", "B", "ring traffic per frame"},
    {"commands_per_frame", "", "renderer commands per frame"},
    {"sort_bytes_per_frame", "B",
     "ring bytes per frame less the frame buffer's pixels (width x height "
     "x pixel_bytes): commands, markers, bins and edits"},
    {"region_overlap", "",
     "renderer commands per on-screen primitive instance: the screen "
     "regions a primitive's box overlaps (Molnar's overlap factor)"},
    {"gps", "", "GPs run"},
    {"last_imbalance_pct", "%",
     "(max - mean) / max GP processor time, last frame (sec. 5)"},
    {"edits", "", "matrix modifies run in all"},
    {"host_elements_per_frame", "",
     "display-list elements the host sent the GPs (edits, moves)"},
    {"rebalance_moves", "", "rebalancing moves in all (sec. 5)"},
    {"distribution_efficiency_pct", "%",
     "sec. 6: T1 / sum of GP processor time, last frame"},
    {"processor_utilisation_pct", "%",
     "sec. 6: sum of GP processor time / (P x the largest)"},
    {"speedup", "", "sec. 6: T1 / the largest GP processor time"},
    {"expressions_per_frame", "",
     "linear expressions the renderers evaluated per frame"},
    {"image_matches_serial", "",
     "1 when the last frame equals a serial render of the list"},
    {"edits_append", "", "append edits run in all (when asked for)"},
    {"edits_insert", "", "insert edits run in all (when asked for)"},
    {"edits_delete", "", "delete edits run in all (when asked for)"},
    {"edits_unpost", "", "unpost edits run in all (when asked for)"},
    {"edits_post", "", "post edits run in all (when asked for)"},
    {"step_back_elements_per_frame", "",
     "elements the backward scans examined per frame (sec. 3.4-3.5)"},
    {"step_back_max_elements", "", "elements of the largest backward scan"},
    {"attr_cache_walk_per_frame", "",
     "host elements walked per frame to place checkpoints again"},
    {"host_edit_ms_per_frame", "ms",
     "the host's time stepping back and packing elements, per frame"},
    {"db_depth", "", "levels of the database's structure network, as drawn"},
    {"db_structures", "", "structure instances of the database (max-set)"},
    {"db_primitives", "", "primitive instances of the database (max-set)"},
    {"db_attributes", "", "attribute instances of the database (max-set)"},
    {"db_offscreen_pct", "%",
     "share of the database's polygons wholly outside the view"},
    {"renderer_util_min_pct", "%", "busy / simulated time, least renderer"},
    {"renderer_util_max_pct", "%", "busy / simulated time, busiest renderer"},
    {"gps_without_primitives", "",
     "GPs whose portion holds no primitive instance (sec. 2.2)"},
    {"gp_polygons_per_s", "1/s",
     "on-screen primitives of the last frame / the busiest GP's time"},
    {"frame_polygons_per_s", "1/s",
     "on-screen primitives of the last frame / its frame time"},
    {"distribution_elements", "",
     "element copies the host sent the GPs to distribute the list"},
    {"distribution_attributes", "",
     "of them attributes (sec. 2.3.1; by structure: sec. 2.1's inheritance)"},
    {"distribution_bytes", "B",
     "distribution_elements x element_bytes (frame.yaml)"},
    {NULL, NULL, NULL},
};

const WlOps wl_pphigs_ops = {
    .name = "pphigs",
    .summary = "PPHIGS display list distributed by primitive over the "
               "GPs of Pixel-Planes 5 (ellsworth90)",
    .parse = parse,
    .free_params = params_free,
    .plan = plan,
    .run = run,
    .mem_bytes = mem_bytes,
    .needs = wl_pphigs_needs,
    .metrics = pphigs_metrics,
};
