/* model_param.c — reading a checked model's parameters (model_param.h).
 *
 * A parameter is either a provenance map {value, source|calibrated|
 * assumption, note} or a bare override; holder() resolves both to the
 * (container, key) of the value, so each getter is one cfg_get_* call on
 * it.  Provenance is judged by files: a `source` given in another file
 * than the value (a model's source under a run config's `value`) does not
 * cover it.  Cost: O(1) per scalar, O(length) per list.
 */
#include "sim/machine/model_param.h"
#include "sim/core/error.h"

const char *const mach_provenance_keys[] = {"source", "calibrated",
                                            "assumption", NULL};

const char *mach_type_example(MachType t)
{
    switch (t) {
    case MACH_T_TIME:
        return "a time with its unit, e.g. '350 us'";
    case MACH_T_BANDWIDTH:
        return "a bandwidth with its unit, e.g. '2.8 MB/s'";
    case MACH_T_FREQ:
        return "a frequency with its unit, e.g. '16 MHz'";
    case MACH_T_SIZE:
        return "a size with its unit, e.g. '4 MB'";
    case MACH_T_BW_LIST:
        return "a list of bandwidths, e.g. [20 MB/s, 10 MB/s]";
    case MACH_T_COUNT_LIST:
        return "a list of counts, e.g. [8, 8]";
    case MACH_T_COUNT:
        return "a count, e.g. 16 or 64K";
    case MACH_T_NUMBER:
        return "a number, e.g. 0.5";
    default:
        return "a word, e.g. hypercube";
    }
}

/* Resolves (map, key) to the (container, key) that holds the value. */
static const CfgNode *holder(const CfgNode *map, const char **key)
{
    const CfgNode *p = cfg_get(map, *key);
    if (p && cfg_kind(p) == CFG_MAP) {
        *key = "value";
        return p;
    }
    return p ? map : NULL;
}

const CfgNode *mach_param_node(const CfgNode *map, const char *key)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get(h, key) : NULL;
}

static gboolean absent(const CfgNode *map, const char *key, gboolean required,
                       GError **err)
{
    if (required) {
        char *found = g_strdup_printf("no parameter '%s'", key);
        cfg_error(err, map, found, "it in the machine model");
        g_free(found);
        return FALSE;
    }
    return TRUE;
}

gboolean mach_param_time(const CfgNode *map, const char *key, gboolean required,
                         SimTime *out, GError **err)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get_time(h, key, TRUE, out, err)
             : absent(map, key, required, err);
}

gboolean mach_param_count(const CfgNode *map, const char *key,
                          gboolean required, uint64_t *out, GError **err)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get_count(h, key, TRUE, 0, UINT64_MAX, out, err)
             : absent(map, key, required, err);
}

gboolean mach_param_bandwidth(const CfgNode *map, const char *key,
                              gboolean required, double *out, GError **err)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get_bandwidth(h, key, TRUE, out, err)
             : absent(map, key, required, err);
}

gboolean mach_param_freq(const CfgNode *map, const char *key, gboolean required,
                         double *out, GError **err)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get_freq(h, key, TRUE, out, err)
             : absent(map, key, required, err);
}

gboolean mach_param_number(const CfgNode *map, const char *key,
                           gboolean required, double *out, GError **err)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get_double(h, key, TRUE, 0, G_MAXDOUBLE, out, err)
             : absent(map, key, required, err);
}

gboolean mach_param_size(const CfgNode *map, const char *key, gboolean required,
                         uint64_t *out, GError **err)
{
    const CfgNode *h = holder(map, &key);
    return h ? cfg_get_size(h, key, TRUE, out, err)
             : absent(map, key, required, err);
}

/* One list item of type t (MACH_T_BANDWIDTH: double, MACH_T_COUNT:
 * uint64_t), parsed where it stands. */
static gboolean parse_item(const CfgNode *v, MachType t, void *out,
                           GError **err)
{
    char *what =
        g_strdup_printf("%s:%d:%d", cfg_file(v), cfg_line(v), cfg_col(v));
    const char *s = cfg_scalar(v);
    gboolean ok =
        s && (t == MACH_T_BANDWIDTH ? cfg_parse_bandwidth(s, what, out, err)
                                    : cfg_parse_count(s, what, out, err));
    if (!s)
        cfg_error(err, v, "a non-scalar list item",
                  t == MACH_T_BANDWIDTH ? "a bandwidth" : "a count");
    g_free(what);
    return ok;
}

/* A list parameter of type t into a new GArray (doubles or uint64_t). */
static gboolean param_list(const CfgNode *map, const char *key,
                           gboolean required, MachType t, GArray **out,
                           GError **err)
{
    const CfgNode *v = mach_param_node(map, key);
    if (!v)
        return absent(map, key, required, err);
    if (cfg_kind(v) != CFG_SEQ) {
        cfg_error(err, v, "a non-list value", mach_type_example(t));
        return FALSE;
    }
    MachType item = t == MACH_T_BW_LIST ? MACH_T_BANDWIDTH : MACH_T_COUNT;
    GArray *a = g_array_new(FALSE, FALSE, 8);
    for (guint i = 0; i < cfg_seq_len(v); i++) {
        union {
            double d;
            uint64_t u;
        } x;
        if (!parse_item(cfg_seq_at(v, i), item, &x, err)) {
            g_array_unref(a);
            return FALSE;
        }
        g_array_append_val(a, x);
    }
    *out = a;
    return TRUE;
}

gboolean mach_param_bw_list(const CfgNode *map, const char *key,
                            gboolean required, GArray **out, GError **err)
{
    return param_list(map, key, required, MACH_T_BW_LIST, out, err);
}

gboolean mach_param_count_list(const CfgNode *map, const char *key,
                               gboolean required, GArray **out, GError **err)
{
    return param_list(map, key, required, MACH_T_COUNT_LIST, out, err);
}

MachProvenance mach_param_provenance(const CfgNode *map, const char *key,
                                     const char **text)
{
    const CfgNode *p = cfg_get(map, key);
    if (text)
        *text = NULL;
    if (!p)
        return MACH_PROV_NONE;
    /* the provenance given in the same file as the value (a scalar or a
     * list has none: cfg_get of a non-map is NULL, so an override) */
    const CfgNode *v = cfg_get(p, "value");
    for (guint i = 0; mach_provenance_keys[i]; i++) {
        const CfgNode *t = cfg_get(p, mach_provenance_keys[i]);
        if (!t || (v && g_strcmp0(cfg_file(v), cfg_file(t)) != 0))
            continue;
        if (text)
            *text = cfg_scalar(t);
        return (MachProvenance)(MACH_PROV_SOURCE + i);
    }
    return MACH_PROV_OVERRIDE;
}

const char *mach_provenance_name(MachProvenance p)
{
    static const char *const names[] = {"none", "source", "calibrated",
                                        "assumption", "override"};
    g_assert((unsigned)p < G_N_ELEMENTS(names));
    return names[p];
}

const char *mach_param_word(const CfgNode *map, const char *key)
{
    const CfgNode *v = mach_param_node(map, key);
    return v ? cfg_scalar(v) : NULL;
}
