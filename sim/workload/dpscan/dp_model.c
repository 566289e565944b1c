/* dp_model.c — the data-parallel cost model of a machine (dp_model.h):
 * the `dpscan:` section of the machine the runner built, read into a
 * WlDpMachine.  The machine layer found the model on the search path and
 * checked every entry's value and provenance (model.h); this file only
 * reads the values, with the typed getters of cfg.h, so errors are
 * located ("file:line:column: found ..., expected ...").  O(keys).
 */
#include "sim/workload/dpscan/dp_model.h"
#include "sim/machine/model_param.h"

/* The (container, key) holding a parameter's value: its provenance map
 * {value: ...} or, for an override, the section itself. */
static const CfgNode *holder(const CfgNode *sec, const char **key)
{
    const CfgNode *p = cfg_get(sec, *key);
    if (p && cfg_kind(p) == CFG_MAP) {
        *key = "value";
        return p;
    }
    return p ? sec : NULL;
}

/* The holder of `key`; NULL when absent (with *err set if required). */
static const CfgNode *param(const CfgNode *sec, const char **key,
                            gboolean required, GError **err)
{
    const char *name = *key;
    const CfgNode *h = holder(sec, key);
    if (!h && required) {
        char *found = g_strdup_printf("no '%s'", name);
        cfg_error(err, sec, found, "the parameter in the section");
        g_free(found);
    }
    return h;
}

static gboolean get_time(const CfgNode *sec, const char *key, gboolean required,
                         SimTime *out, GError **err)
{
    const CfgNode *h = param(sec, &key, required, err);
    return h ? cfg_get_time(h, key, TRUE, out, err) : !required;
}

/* Optional boolean parameter; FALSE (the default) when absent. */
static gboolean get_flag(const CfgNode *sec, const char *key, gboolean *out,
                         GError **err)
{
    const CfgNode *h = param(sec, &key, FALSE, err);
    *out = FALSE;
    return !h || cfg_get_bool(h, key, TRUE, out, err);
}

static gboolean get_count(const CfgNode *sec, const char *key, uint64_t min,
                          uint64_t max, uint64_t *out, GError **err)
{
    const CfgNode *h = param(sec, &key, TRUE, err);
    return h && cfg_get_count(h, key, TRUE, min, max, out, err);
}

static gboolean get_levels(const CfgNode *sec, WlDpMachine *m, GError **err)
{
    const char *key = "level_bandwidth";
    const CfgNode *h = param(sec, &key, TRUE, err);
    if (!h)
        return FALSE;
    const CfgNode *seq = cfg_get(h, key);
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

static gboolean spmd_params(const CfgNode *sec, WlDpMachine *m, GError **err)
{
    uint64_t arity = 4, bytes = 0;
    const char *key = "msg_bytes";
    const CfgNode *mb = param(sec, &key, TRUE, err);
    if (!mb)
        return FALSE;
    if (!get_time(sec, "net_latency", TRUE, &m->net_latency, err) ||
        !get_time(sec, "msg_overhead", TRUE, &m->msg_overhead, err) ||
        !cfg_get_size(mb, key, TRUE, &bytes, err) ||
        !get_count(sec, "arity", 2, 64, &arity, err) ||
        !get_levels(sec, m, err))
        return FALSE;
    if (bytes == 0 || bytes > 65536) {
        cfg_error(err, cfg_get(mb, key), "a size out of range",
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
static const WlNeed simd_needs[] = {{"dpscan", simd_keys, NULL}, {NULL, NULL, NULL}};
static const WlNeed spmd_needs[] = {{"dpscan", spmd_keys, NULL}, {NULL, NULL, NULL}};
const WlNeedAlt wl_dp_model_needs[] = {
    {"from its machine model's dpscan: section, arch: simd (the "
     "partition is nodes.array.lanes)",
     simd_needs},
    {"the same, arch: spmd (the partition is nodes.node.count)", spmd_needs},
    {NULL, NULL}};

gboolean wl_dp_machine_from_cfg(const CfgNode *sec, WlDpMachine *m,
                                GError **err)
{
    static const char *const arch[] = {"simd", "spmd", NULL};
    if (cfg_kind(sec) != CFG_MAP) {
        cfg_error(err, sec, "not a map", "a dpscan: section");
        return FALSE;
    }
    const char *key = "arch";
    const CfgNode *a = param(sec, &key, TRUE, err);
    int kind = 0;
    if (!a)
        return FALSE;
    if (!cfg_get_enum(a, key, TRUE, arch, &kind, err) ||
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

const char *wl_dp_partition_kind(WlDpArch arch)
{
    return arch == WL_DP_SIMD ? "array" : "node";
}

gboolean wl_dp_machine_from_model(const CfgNode *model, const CfgNode *at,
                                  WlDpMachine *m, GError **err)
{
    const CfgNode *sec = cfg_get(model, "dpscan");
    if (sec)
        return wl_dp_machine_from_cfg(sec, m, err);
    const char *name = cfg_scalar(cfg_get(model, "model"));
    if (!name)
        name = cfg_scalar(cfg_get(model, "name"));
    char *found = g_strdup_printf("machine '%s' without a dpscan: section",
                                  name ? name : "(inline)");
    cfg_error(err, at ? at : model, found,
              "a model with the data-parallel costs of dpscan (arch, op, "
              "step, scan_slice ...: pgsim help run; models/cm200.yaml)");
    g_free(found);
    return FALSE;
}

gboolean wl_dp_machine_from_mach(const MachMachine *mach, WlDpMachine *m,
                                 GError **err)
{
    const CfgNode *model = mach_model_cfg(mach);
    if (!wl_dp_machine_from_model(model, cfg_get(model, "model"), m, err))
        return FALSE;
    const char *kind = wl_dp_partition_kind(m->arch);
    const MachKindInfo *k = mach_kind(mach, kind);
    if (!k) {
        char *found = g_strdup_printf("a %s machine '%s' without '%s' "
                                      "processors",
                                      m->arch == WL_DP_SIMD ? "SIMD" : "SPMD",
                                      mach_name(mach), kind);
        char *exp = g_strdup_printf("nodes.%s (the partition dpscan runs "
                                    "on)",
                                    kind);
        cfg_error(err, cfg_get(model, "nodes") ? cfg_get(model, "nodes")
                                               : model,
                  found, exp);
        g_free(found);
        g_free(exp);
        return FALSE;
    }
    m->procs = m->arch == WL_DP_SIMD ? k->lanes : k->count;
    return TRUE;
}
