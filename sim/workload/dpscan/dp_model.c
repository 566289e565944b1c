/* dp_model.c — the data-parallel cost model of a machine, from YAML.
 *
 * Each parameter is a map holding `value` and one provenance key
 * (source, assumption or calibrated); a note is allowed.  The value is
 * converted with the typed getters of cfg.h, so errors are located
 * ("file:line:column: found ..., expected ...").  O(keys).
 */
#include "sim/workload/dpscan/dp_model.h"

static const char *const provenance[] = {"source", "assumption", "calibrated",
                                         NULL};

/* The parameter map `key` after checking its provenance; NULL when absent
 * (error set if required). */
static const CfgNode *param(const CfgNode *sec, const char *key,
                            gboolean required, GError **err)
{
    const CfgNode *p = cfg_get(sec, key);
    if (!p) {
        if (required) {
            char *found = g_strdup_printf("no '%s'", key);
            cfg_error(err, sec, found, "the parameter in the section");
            g_free(found);
        }
        return NULL;
    }
    if (cfg_kind(p) != CFG_MAP || !cfg_get(p, "value")) {
        cfg_error(err, p, "a bare value", "{value: ..., source: ...}");
        return NULL;
    }
    int found = 0;
    for (int i = 0; provenance[i]; i++)
        found += cfg_get(p, provenance[i]) != NULL;
    (void)cfg_get(p, "note");
    if (found != 1) {
        cfg_error(err, p, "a value without exactly one provenance",
                  "one of source, assumption, calibrated");
        return NULL;
    }
    return p;
}

static gboolean get_time(const CfgNode *sec, const char *key, gboolean required,
                         SimTime *out, GError **err)
{
    GError *e = NULL;
    const CfgNode *p = param(sec, key, required, &e);
    if (!p) {
        if (e)
            g_propagate_error(err, e);
        return e == NULL;
    }
    return cfg_get_time(p, "value", TRUE, out, err);
}

/* Optional boolean parameter; FALSE (the default) when absent. */
static gboolean get_flag(const CfgNode *sec, const char *key, gboolean *out,
                         GError **err)
{
    GError *e = NULL;
    const CfgNode *p = param(sec, key, FALSE, &e);
    *out = FALSE;
    if (!p) {
        if (e)
            g_propagate_error(err, e);
        return e == NULL;
    }
    return cfg_get_bool(p, "value", TRUE, out, err);
}

static gboolean get_levels(const CfgNode *sec, WlDpMachine *m, GError **err)
{
    GError *e = NULL;
    const CfgNode *p = param(sec, "level_bandwidth", TRUE, &e);
    if (!p) {
        g_propagate_error(err, e);
        return FALSE;
    }
    const CfgNode *seq = cfg_get(p, "value");
    guint n = cfg_kind(seq) == CFG_SEQ ? cfg_seq_len(seq) : 0;
    if (n == 0 || n > NET_MAX_LEVELS) {
        cfg_error(err, seq, "not a list of 1 to 8 bandwidths",
                  "[20 MB/s, 10 MB/s, ...]");
        return FALSE;
    }
    for (guint i = 0; i < n; i++) {
        const CfgNode *v = cfg_seq_at(seq, i);
        const char *s = cfg_scalar(v);
        GError *pe = NULL;
        if (!s ||
            !cfg_parse_bandwidth(s, "level_bandwidth", &m->level_bw[i], &pe) ||
            m->level_bw[i] <= 0.0) {
            g_clear_error(&pe);
            cfg_error(err, v, s ? s : "a non-scalar", "a bandwidth > 0");
            return FALSE;
        }
    }
    m->levels = n;
    return TRUE;
}

static gboolean get_count(const CfgNode *sec, const char *key, uint64_t min,
                          uint64_t max, uint64_t *out, GError **err)
{
    GError *e = NULL;
    const CfgNode *p = param(sec, key, TRUE, &e);
    if (!p) {
        g_propagate_error(err, e);
        return FALSE;
    }
    return cfg_get_count(p, "value", TRUE, min, max, out, err);
}

static gboolean spmd_params(const CfgNode *sec, WlDpMachine *m, GError **err)
{
    uint64_t arity = 4, bytes = 0;
    GError *e = NULL;
    const CfgNode *mb = param(sec, "msg_bytes", TRUE, &e);
    if (!mb) {
        g_propagate_error(err, e);
        return FALSE;
    }
    if (!get_time(sec, "net_latency", TRUE, &m->net_latency, err) ||
        !get_time(sec, "msg_overhead", TRUE, &m->msg_overhead, err) ||
        !cfg_get_size(mb, "value", TRUE, &bytes, err) ||
        !get_count(sec, "arity", 2, 64, &arity, err) ||
        !get_levels(sec, m, err))
        return FALSE;
    if (bytes == 0 || bytes > 65536) {
        cfg_error(err, cfg_get(mb, "value"), "a size out of range",
                  "1 B to 64 KiB");
        return FALSE;
    }
    m->msg_bytes = (uint32_t)bytes;
    m->arity = (unsigned)arity;
    return TRUE;
}

/* Optional router_procs: processors per router node (default 1). */
static gboolean get_router_procs(const CfgNode *sec, WlDpMachine *m,
                                 GError **err)
{
    uint64_t g = 1;
    if (cfg_get(sec, "router_procs") &&
        !get_count(sec, "router_procs", 1, 1024, &g, err))
        return FALSE;
    m->router_procs = (uint32_t)g;
    return TRUE;
}

/* The keys wl_dp_machine_from_cfg requires of each architecture (the
 * optional ones, news_slice, vp_pow2, router_procs, send_vp and send_msg,
 * default to 0 or off), for `pgsim help run`. */
static const char *const simd_keys[] = {"arch",       "op",         "step",
                                        "scan_slice", "send_setup", "send_slice",
                                        NULL};
static const char *const spmd_keys[] = {
    "arch",         "op",        "step",  "scan_slice",      "net_latency",
    "msg_overhead", "msg_bytes", "arity", "level_bandwidth", NULL};
static const WlNeed simd_needs[] = {{"dpscan", simd_keys}, {NULL, NULL}};
static const WlNeed spmd_needs[] = {{"dpscan", spmd_keys}, {NULL, NULL}};
const WlNeedAlt wl_dp_model_needs[] = {
    {"from its model's dpscan: section (models/<workload.model>.yaml), "
     "arch: simd",
     simd_needs},
    {"the same, arch: spmd", spmd_needs},
    {NULL, NULL}};

gboolean wl_dp_machine_from_cfg(const CfgNode *sec, WlDpMachine *m,
                                GError **err)
{
    static const char *const arch[] = {"simd", "spmd", NULL};
    if (cfg_kind(sec) != CFG_MAP) {
        cfg_error(err, sec, "not a map", "a dpscan: section");
        return FALSE;
    }
    GError *e = NULL;
    const CfgNode *a = param(sec, "arch", TRUE, &e);
    int kind = 0;
    if (!a) {
        g_propagate_error(err, e);
        return FALSE;
    }
    if (!cfg_get_enum(a, "value", TRUE, arch, &kind, err) ||
        !get_time(sec, "op", TRUE, &m->op, err) ||
        !get_time(sec, "step", TRUE, &m->step, err) ||
        !get_time(sec, "scan_slice", TRUE, &m->scan_slice, err) ||
        !get_flag(sec, "vp_pow2", &m->vp_pow2, err) ||
        !get_time(sec, "news_slice", FALSE, &m->news_slice, err) ||
        !get_router_procs(sec, m, err))
        return FALSE;
    m->arch = kind == 0 ? WL_DP_SIMD : WL_DP_SPMD;
    if (m->arch == WL_DP_SIMD)
        return get_time(sec, "send_setup", TRUE, &m->send_setup, err) &&
               get_time(sec, "send_slice", TRUE, &m->send_slice, err) &&
               get_time(sec, "send_vp", FALSE, &m->send_vp, err) &&
               get_time(sec, "send_msg", FALSE, &m->send_msg, err);
    return spmd_params(sec, m, err);
}

gboolean wl_dp_machine_load(const char *models_dir, const char *name,
                            WlDpMachine *m, GError **err)
{
    char *file = g_strdup_printf("%s.yaml", name);
    char *path = g_build_filename(models_dir, file, NULL);
    CfgNode *root = cfg_load_file(path, err);
    gboolean ok = root != NULL;
    if (ok) {
        const CfgNode *sec = cfg_get(root, "dpscan");
        if (!sec) {
            cfg_error(err, root, "no dpscan: section",
                      "the data-parallel costs of the machine");
            ok = FALSE;
        } else {
            ok = wl_dp_machine_from_cfg(sec, m, err);
        }
    }
    cfg_free(root);
    g_free(path);
    g_free(file);
    return ok;
}
