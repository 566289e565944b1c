/* pphigs_cfg.c — the pphigs workload's YAML readers (see pphigs_cfg.h).
 * Model entries are maps {value, unit?, source|assumption|calibrated};
 * only `value` is read here (the machine layer checks provenance).
 */
#include "sim/workload/pphigs/pphigs_cfg.h"
#include <string.h>

typedef struct {
    const char *key;
    gsize off;
} Field;

#define F(k) {#k, G_STRUCT_OFFSET(ScenePphigsSpec, k)}
static const Field count_fields[] = {
    F(polygons), F(attributes), F(verts), F(boids), F(boid_polygons),
    F(boid_colors), F(well_structs), F(well_polygons), F(well_attributes),
    F(figures), F(structures), F(levels)};
#undef F

static gboolean spec_kind(const CfgNode *map, ScenePphigsSpec *out,
                          GError **err)
{
    const char *kind = NULL;
    if (!cfg_get_str(map, "kind", TRUE, &kind, err))
        return FALSE;
    if (scene_pphigs_kind_parse(kind, &out->kind))
        return TRUE;
    cfg_error(err, cfg_get(map, "kind"), kind,
              "space_station, building_lobby, flock_old_well or "
              "two_human_figures");
    return FALSE;
}

gboolean wl_pphigs_spec_from_cfg(const CfgNode *map, ScenePphigsSpec *out,
                                 GError **err)
{
    memset(out, 0, sizeof *out);
    if (cfg_kind(map) != CFG_MAP) {
        cfg_error(err, map, "a non-map", "a map of generator parameters");
        return FALSE;
    }
    if (!spec_kind(map, out, err) ||
        !cfg_get_count(map, "seed", FALSE, 0, UINT64_MAX, &out->seed, err) ||
        !cfg_get_double(map, "size", FALSE, 1e-9, 1e9, &out->size, err) ||
        !cfg_get_double(map, "fov_deg", FALSE, 1, 179, &out->fov_deg, err))
        return FALSE;
    for (guint i = 0; i < G_N_ELEMENTS(count_fields); i++) {
        uint64_t v = 0;
        if (!cfg_get_count(map, count_fields[i].key, FALSE, 0, 1u << 30, &v,
                           err))
            return FALSE;
        G_STRUCT_MEMBER(guint, out, count_fields[i].off) = (guint)v;
    }
    return cfg_check_unused(map, err);
}

gboolean wl_pphigs_spec_load(const char *path, const char *name,
                             ScenePphigsSpec *out, GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return FALSE;
    const CfgNode *m = cfg_get(root, name);
    gboolean ok = m != NULL;
    if (!m) {
        char *f = g_strdup_printf("no database '%s'", name);
        cfg_error(err, root, f, "space_station, building_lobby, "
                                "flock_old_well or two_human_figures");
        g_free(f);
    } else {
        ok = wl_pphigs_spec_from_cfg(m, out, err);
    }
    cfg_free(root);
    return ok;
}

/* ---- model values ----------------------------------------------------- */

static const CfgNode *entry(const CfgNode *root, const char *path,
                            GError **err)
{
    const CfgNode *n = cfg_path(root, path);
    if (!n || cfg_kind(n) != CFG_MAP) {
        char *f = g_strdup_printf("no entry '%s'", path);
        cfg_error(err, root, f, "{value: ..., source|assumption: ...}");
        g_free(f);
        return NULL;
    }
    return n;
}

static gboolean num(const CfgNode *root, const char *path, double *out,
                    GError **err)
{
    const CfgNode *n = entry(root, path, err);
    return n && cfg_get_double(n, "value", TRUE, 0, 1e12, out, err);
}

static gboolean tm(const CfgNode *root, const char *path, SimTime *out,
                   GError **err)
{
    const CfgNode *n = entry(root, path, err);
    return n && cfg_get_time(n, "value", TRUE, out, err);
}

static gboolean cnt(const CfgNode *root, const char *path, guint *out,
                    GError **err)
{
    const CfgNode *n = entry(root, path, err);
    uint64_t v = 0;
    if (!n || !cfg_get_count(n, "value", TRUE, 1, 1u << 20, &v, err))
        return FALSE;
    *out = (guint)v;
    return TRUE;
}

gboolean wl_pphigs_costs_from_cfg(const CfgNode *model, WlPphigsCosts *c,
                                  double *cluster_scale, GError **err)
{
    return num(model, "pphigs.poly", &c->poly, err) &&
           num(model, "pphigs.vertex", &c->vertex, err) &&
           num(model, "pphigs.offscreen", &c->offscreen, err) &&
           num(model, "pphigs.color", &c->color, err) &&
           num(model, "pphigs.matrix", &c->matrix, err) &&
           num(model, "pphigs.concat", &c->concat, err) &&
           num(model, "pphigs.execute", &c->execute, err) &&
           num(model, "pphigs.cluster_scale", cluster_scale, err);
}

static gboolean net_from_cfg(const CfgNode *model, NetParams *np,
                             GError **err)
{
    memset(np, 0, sizeof *np);
    np->switching = NET_SW_RING_SLOTS;
    const CfgNode *bw = entry(model, "network.bandwidth", err);
    const CfgNode *pk = bw ? entry(model, "network.packet_size", err) : NULL;
    uint64_t psz = 0;
    return bw && pk &&
           cfg_get_bandwidth(bw, "value", TRUE, &np->bandwidth, err) &&
           cfg_get_size(pk, "value", TRUE, &psz, err) &&
           (np->packet_bytes = (uint32_t)psz, TRUE) &&
           cnt(model, "network.channels", &np->channels, err) &&
           tm(model, "network.per_hop", &np->per_hop, err) &&
           tm(model, "network.startup", &np->startup, err);
}

static gboolean frame_sizes(const CfgNode *fr, WlPphigsFrameSpec *s,
                            GError **err)
{
    static const char *const keys[] = {"width", "height", "region",
                                       "cmd_bytes", "end_bytes", "batch",
                                       "pixel_bytes"};
    guint *dst[] = {&s->width, &s->height, &s->region, &s->cmd_bytes,
                    &s->end_bytes, &s->batch, &s->pixel_bytes};
    for (guint i = 0; i < G_N_ELEMENTS(keys); i++) {
        uint64_t v = 0;
        if (!cfg_get_count(fr, keys[i], TRUE, 1, 1u << 24, &v, err))
            return FALSE;
        *dst[i] = (guint)v;
    }
    return TRUE;
}

gboolean wl_pphigs_hw_from_cfg(const CfgNode *model, const CfgNode *frame,
                               WlPphigsFrameSpec *s, NetParams *np,
                               guint *max_gps, GError **err)
{
    return tm(model, "nodes.gp.costs.send_primitive", &s->gp_send, err) &&
           tm(model, "nodes.renderer.costs.primitive", &s->rend_prim,
              err) &&
           tm(model, "nodes.renderer.costs.region_begin", &s->rend_begin,
              err) &&
           tm(model, "nodes.renderer.costs.region_shade", &s->rend_shade,
              err) &&
           tm(model, "nodes.frame_buffer.costs.store_region", &s->fb_store,
              err) &&
           cnt(model, "nodes.renderer.count", &s->renderers, err) &&
           cnt(model, "nodes.gp.count", max_gps, err) &&
           net_from_cfg(model, np, err) && frame_sizes(frame, s, err);
}

gboolean wl_pphigs_hw_load(const char *model_path, const CfgNode *frame,
                           WlPphigsHw *hw, GError **err)
{
    CfgNode *m = cfg_load_file(model_path, err);
    if (!m)
        return FALSE;
    memset(hw, 0, sizeof *hw);
    gboolean ok =
        wl_pphigs_costs_from_cfg(m, &hw->costs, &hw->cluster_scale, err) &&
        wl_pphigs_hw_from_cfg(m, frame, &hw->frame, &hw->net, &hw->max_gps,
                              err);
    hw->frame.gp = hw->costs;
    cfg_free(m);
    return ok;
}
