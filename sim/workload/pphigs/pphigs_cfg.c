/* pphigs_cfg.c — the pphigs workload's YAML readers (see pphigs_cfg.h).
 * Every reader marks what it reads and rejects unknown keys.
 */
#include "sim/workload/pphigs/pphigs_cfg.h"
#include "sim/core/inputs.h"
#include "sim/scene/structdb_file.h"
#include <string.h>

typedef struct {
    const char *key;
    gsize off;
} Field;

#define F(k)                                                                   \
    {                                                                          \
#k, G_STRUCT_OFFSET(ScenePphigsSpec, k)                                \
    }
static const Field count_fields[] = {
    F(polygons),        F(attributes),  F(verts),        F(boids),
    F(boid_polygons),   F(boid_colors), F(well_structs), F(well_polygons),
    F(well_attributes), F(figures),     F(structures),   F(levels),
    F(overlays)};
#undef F

static const char *const db_names =
    "space_station, building_lobby, flock_old_well or two_human_figures";

static gboolean spec_kind(const CfgNode *map, ScenePphigsSpec *out,
                          GError **err)
{
    const char *kind = NULL;
    if (!cfg_get_str(map, "kind", TRUE, &kind, err))
        return FALSE;
    if (scene_pphigs_kind_parse(kind, &out->kind))
        return TRUE;
    char *found = g_strdup_printf("kind '%s'", kind);
    cfg_error(err, cfg_get(map, "kind"), found, db_names);
    g_free(found);
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

/* "no database 'x'" at name_at (or the file), listing the file's keys. */
static void no_such_db(const CfgNode *root, const char *name,
                       const CfgNode *name_at, GError **err)
{
    GString *exp = g_string_new("one of the databases of ");
    g_string_append(exp, cfg_file(root));
    for (guint i = 0; cfg_kind(root) == CFG_MAP && i < cfg_map_len(root); i++)
        g_string_append_printf(exp, "%s %s", i ? "," : ":",
                               cfg_map_key(root, i));
    g_string_append(exp, ", or a structure database file (*.yaml)");
    char *found = g_strdup_printf("database '%s'", name);
    cfg_error(err, name_at ? name_at : root, found, exp->str);
    g_free(found);
    g_string_free(exp, TRUE);
}

gboolean wl_pphigs_spec_load(const char *path, const char *name,
                             const CfgNode *name_at, ScenePphigsSpec *out,
                             GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return FALSE;
    sim_inputs_note_file("database", path);
    const CfgNode *m = cfg_kind(root) == CFG_MAP ? cfg_get(root, name) : NULL;
    gboolean ok = m && wl_pphigs_spec_from_cfg(m, out, err);
    if (!m)
        no_such_db(root, name, name_at, err);
    cfg_free(root);
    return ok;
}

/* ---- a user's structure database file ---------------------------------- */

gboolean wl_pphigs_is_db_file(const char *value)
{
    return g_str_has_suffix(value, ".yaml") || g_str_has_suffix(value, ".yml");
}

/* An error of the file as a whole (unreadable, nothing posted), located
 * at the config key that named it. */
static void file_error(const CfgNode *at, const char *path, const char *why,
                       const char *expected, GError **err)
{
    char *found = g_strdup_printf("database file '%s' %s", path, why);
    cfg_error(err, at, found, expected);
    g_free(found);
}

SceneDb *wl_pphigs_db_file_load(const char *path, const CfgNode *at,
                                GError **err)
{
    g_assert(at != NULL);
    GError *e = NULL;
    SceneDb *db = scene_db_load(path, &e);
    if (!db && g_error_matches(e, SIM_ERROR, SIM_ERROR_IO)) {
        file_error(at, path, "that cannot be read",
                   "a readable structure database file (from the current "
                   "directory or a data root)",
                   err);
        g_error_free(e);
        return NULL;
    }
    if (!db) {
        g_propagate_error(err, e);
        return NULL;
    }
    if (scene_db_posted_count(db) == 0) {
        file_error(at, path, "with nothing posted",
                   "a structure database file that posts at least one "
                   "structure (posted: [...])",
                   err);
        scene_db_free(db);
        return NULL;
    }
    return db;
}

/* ---- frame.yaml ------------------------------------------------------- */

static gboolean frame_sizes(const CfgNode *fr, WlPphigsFrameSpec *s,
                            GError **err)
{
    static const char *const keys[] = {"width",       "height",       "region",
                                       "cmd_bytes",   "end_bytes",    "batch",
                                       "pixel_bytes", "element_bytes"};
    guint *dst[] = {&s->width,       &s->height,       &s->region,
                    &s->cmd_bytes,   &s->end_bytes,    &s->batch,
                    &s->pixel_bytes, &s->element_bytes};
    for (guint i = 0; i < G_N_ELEMENTS(keys); i++) {
        uint64_t v = 0;
        if (!cfg_get_count(fr, keys[i], TRUE, 1, 1u << 24, &v, err))
            return FALSE;
        *dst[i] = (guint)v;
    }
    return TRUE;
}

/* cluster_scale: {value: N, calibrated|assumption|source: "..."} */
static gboolean cluster_scale(const CfgNode *fr, double *out, GError **err)
{
    static const char *const prov[] = {"calibrated", "assumption", "source"};
    const CfgNode *p = cfg_get(fr, "cluster_scale");
    if (!p || cfg_kind(p) != CFG_MAP) {
        cfg_error(err, p ? p : fr,
                  p ? "a bare cluster_scale"
                    : "no key 'cluster_scale' in this map",
                  "cluster_scale: {value: <number>, calibrated: <cells>}");
        return FALSE;
    }
    gboolean have = FALSE;
    for (guint i = 0; i < G_N_ELEMENTS(prov); i++)
        have = cfg_get(p, prov[i]) != NULL || have;
    if (!have) {
        cfg_error(err, p, "cluster_scale without a provenance",
                  "one of calibrated:, assumption: or source:");
        return FALSE;
    }
    return cfg_get_double(p, "value", TRUE, 1e-6, 1e6, out, err);
}

gboolean wl_pphigs_setup_from_cfg(const CfgNode *map, WlPphigsSetup *out,
                                  GError **err)
{
    memset(out, 0, sizeof *out);
    if (cfg_kind(map) != CFG_MAP) {
        cfg_error(err, map, "a non-map", "a map of frame sizes");
        return FALSE;
    }
    uint64_t split = 0;
    gboolean ok = frame_sizes(map, &out->frame, err) &&
                  cluster_scale(map, &out->cluster_scale, err) &&
                  cfg_get_count(map, "strip_split", FALSE, 0, 1u << 20, &split,
                                err) &&
                  cfg_check_unused(map, err);
    out->strip_split = (guint)split;
    return ok;
}

gboolean wl_pphigs_setup_load(const char *path, WlPphigsSetup *out,
                              GError **err)
{
    CfgNode *root = cfg_load_file(path, err);
    if (!root)
        return FALSE;
    gboolean ok = wl_pphigs_setup_from_cfg(root, out, err);
    cfg_free(root);
    return ok;
}

double wl_pphigs_cluster_factor(double cluster_scale, guint ngp)
{
    return MAX(1.0, cluster_scale / ngp);
}
