/* sweep_spec.c — reading and expanding sweep files.
 *
 *     name: tokenring-size          # optional; default: the file stem
 *     base: tokenring.yaml          # or an inline map
 *     parameters:
 *       machine.nodes: [2, 4, 8]
 *       workload.tokens: {from: 1, to: 4, step: 1}
 *       workload.bytes: {from: 64, to: 4096, factor: 4}
 *       fidelity: {values: [analytic, packet]}
 *     combine: product              # or zip
 *     repetitions: 3
 *     seed: 42                      # optional: overrides run.seed
 *     plots: [...]                  # plot.c
 *
 * Invariants: every parameter has >= 1 value; under zip all have the same
 * count; combos * repetitions fits in a guint.  Seeds: repetition 0 uses
 * the base seed (so a one-point sweep equals `pgsim run`); repetition
 * r > 0 uses sim_rng_mix(seed + r) >> 1 (63 bits: run.seed is signed).
 * The seed depends on the repetition only, so every combination sees the
 * same random streams (common random numbers).
 */
#include "sim/app/sweep/sweep_spec.h"
#include "sim/core/datapath.h"
#include "sim/core/rng.h"
#include <math.h>
#include <string.h>

#define SWEEP_MAX_VALUES 100000
#define SWEEP_MAX_POINTS 10000000

static const char *const top_keys[] = {"name",     "base",        "parameters",
                                       "combine",  "repetitions", "seed",
                                       "seed_key", "plots",       NULL};

static gboolean check_keys(const CfgNode *map, const char *const *allowed,
                           GError **err)
{
    for (guint i = 0; i < cfg_map_len(map); i++) {
        const char *k = cfg_map_key(map, i);
        if (g_strv_contains(allowed, k))
            continue;
        char *found = g_strdup_printf("unknown key '%s'", k);
        char *exp = g_strjoinv(", ", (char **)allowed);
        char *expected = g_strdup_printf("one of: %s", exp);
        cfg_error(err, cfg_map_value(map, i), found, expected);
        g_free(found);
        g_free(exp);
        g_free(expected);
        return FALSE;
    }
    return TRUE;
}

static void param_free(gpointer p)
{
    SweepParam *sp = p;
    g_free(sp->key);
    g_ptr_array_free(sp->values, TRUE);
    g_free(sp);
}

void sweep_spec_free(SweepSpec *s)
{
    if (!s)
        return;
    g_free(s->path);
    g_free(s->name);
    cfg_free(s->base);
    g_ptr_array_free(s->params, TRUE);
    g_free(s->seed_key);
    g_ptr_array_free(s->plots, TRUE);
    g_free(s->base_text);
    g_free(s);
}

/* ---- values ---------------------------------------------------------- */

static gboolean scalar_value(const CfgNode *n, GPtrArray *out, GError **err)
{
    if (cfg_kind(n) != CFG_SCALAR) {
        cfg_error(err, n, cfg_kind(n) == CFG_MAP ? "a map" : "a list",
                  "a scalar parameter value");
        return FALSE;
    }
    g_ptr_array_add(out, g_strdup(cfg_scalar(n)));
    return TRUE;
}

static gboolean list_values(const CfgNode *seq, GPtrArray *out, GError **err)
{
    if (cfg_seq_len(seq) == 0) {
        cfg_error(err, seq, "an empty list", "at least one value");
        return FALSE;
    }
    for (guint i = 0; i < cfg_seq_len(seq); i++)
        if (!scalar_value(cfg_seq_at(seq, i), out, err))
            return FALSE;
    return TRUE;
}

static gboolean is_int_text(const CfgNode *map, const char *key)
{
    const CfgNode *n = cfg_get(map, key);
    return !n || strpbrk(cfg_scalar(n) ? cfg_scalar(n) : ".", ".eE") == NULL;
}

static void add_number(GPtrArray *out, double v, gboolean integer)
{
    if (integer)
        g_ptr_array_add(out, g_strdup_printf("%.0f", v));
    else {
        char buf[G_ASCII_DTOSTR_BUF_SIZE];
        g_ptr_array_add(out,
                        g_strdup(g_ascii_formatd(buf, sizeof buf, "%.12g", v)));
    }
}

/* from + i*step for i = 0 .. while not past `to` (1e-9 relative slack). */
static gboolean step_range(const CfgNode *map, double from, double to,
                           double step, GPtrArray *out, GError **err)
{
    if (step == 0.0 || (to - from) * step < 0.0) {
        cfg_error(err, cfg_get(map, "step"), "a step that never reaches 'to'",
                  "a non-zero step with the sign of to - from");
        return FALSE;
    }
    double n = floor((to - from) / step + 1e-9) + 1.0;
    if (n > SWEEP_MAX_VALUES) {
        cfg_error(err, map, "a range of more than 100000 values",
                  "a smaller range");
        return FALSE;
    }
    gboolean integer = is_int_text(map, "from") && is_int_text(map, "step");
    for (double i = 0; i < n; i++)
        add_number(out, from + i * step, integer);
    return TRUE;
}

static gboolean factor_range(const CfgNode *map, double from, double to,
                             double factor, GPtrArray *out, GError **err)
{
    if (!(factor > 1.0) || !(from > 0.0) || to < from) {
        cfg_error(err, cfg_get(map, "factor"),
                  "a geometric range that "
                  "never reaches 'to'",
                  "0 < from <= to and factor > 1");
        return FALSE;
    }
    gboolean integer = is_int_text(map, "from") && is_int_text(map, "factor");
    for (double v = from; v <= to * (1.0 + 1e-9); v *= factor) {
        if (out->len >= SWEEP_MAX_VALUES)
            break;
        add_number(out, v, integer);
    }
    return TRUE;
}

static gboolean range_values(const CfgNode *map, GPtrArray *out, GError **err)
{
    static const char *const keys[] = {"from", "to", "step", "factor", NULL};
    double from = 0, to = 0, step = 0, factor = 0;
    if (!check_keys(map, keys, err) ||
        !cfg_get_double(map, "from", TRUE, -HUGE_VAL, HUGE_VAL, &from, err) ||
        !cfg_get_double(map, "to", TRUE, -HUGE_VAL, HUGE_VAL, &to, err))
        return FALSE;
    gboolean has_step = cfg_get(map, "step") != NULL;
    if (has_step == (cfg_get(map, "factor") != NULL)) {
        cfg_error(err, map,
                  has_step ? "both 'step' and 'factor'"
                           : "neither 'step' nor 'factor'",
                  "exactly one of them");
        return FALSE;
    }
    if (has_step)
        return cfg_get_double(map, "step", TRUE, -HUGE_VAL, HUGE_VAL, &step,
                              err) &&
               step_range(map, from, to, step, out, err);
    return cfg_get_double(map, "factor", TRUE, -HUGE_VAL, HUGE_VAL, &factor,
                          err) &&
           factor_range(map, from, to, factor, out, err);
}

static gboolean param_values(const CfgNode *n, GPtrArray *out, GError **err)
{
    if (cfg_kind(n) == CFG_SEQ)
        return list_values(n, out, err);
    if (cfg_kind(n) != CFG_MAP)
        return scalar_value(n, out, err);
    const CfgNode *vals = cfg_get(n, "values");
    if (!vals)
        return range_values(n, out, err);
    static const char *const keys[] = {"values", NULL};
    if (!check_keys(n, keys, err))
        return FALSE;
    if (cfg_kind(vals) != CFG_SEQ) {
        cfg_error(err, vals, "a non-list 'values'", "a list of values");
        return FALSE;
    }
    return list_values(vals, out, err);
}

/* ---- the whole file -------------------------------------------------- */

static gboolean read_params(SweepSpec *s, const CfgNode *map, GError **err)
{
    if (!map)
        return TRUE; /* no parameters: one combination */
    if (cfg_kind(map) != CFG_MAP) {
        cfg_error(err, map, "a non-map 'parameters'",
                  "a map of key path -> values");
        return FALSE;
    }
    for (guint i = 0; i < cfg_map_len(map); i++) {
        SweepParam *p = g_new0(SweepParam, 1);
        p->key = g_strdup(cfg_map_key(map, i));
        p->values = g_ptr_array_new_with_free_func(g_free);
        g_ptr_array_add(s->params, p);
        if (!param_values(cfg_map_value(map, i), p->values, err))
            return FALSE;
    }
    return TRUE;
}

static gboolean count_combos(SweepSpec *s, const CfgNode *pmap, GError **err)
{
    uint64_t n = 1;
    for (guint i = 0; i < s->params->len; i++) {
        const SweepParam *p = g_ptr_array_index(s->params, i);
        if (s->zip && i > 0 && p->values->len != n) {
            char *f =
                g_strdup_printf("%u values for '%s'", p->values->len, p->key);
            char *e =
                g_strdup_printf("%u, as for every zipped parameter", (guint)n);
            cfg_error(err, cfg_get(pmap, p->key), f, e);
            g_free(f);
            g_free(e);
            return FALSE;
        }
        n = s->zip ? p->values->len : n * p->values->len;
        if (n * s->repetitions > SWEEP_MAX_POINTS) {
            cfg_error(err, pmap, "more than 10 million points",
                      "a smaller sweep");
            return FALSE;
        }
    }
    s->combos = (guint)n;
    return TRUE;
}

static gboolean read_combine(SweepSpec *s, const CfgNode *root, GError **err)
{
    static const char *const words[] = {"product", "zip", NULL};
    int which = 0;
    int64_t reps = 1;
    if (!cfg_get_enum(root, "combine", FALSE, words, &which, err) ||
        !cfg_get_int(root, "repetitions", FALSE, 1, 1000000, &reps, err))
        return FALSE;
    s->zip = which == 1;
    s->repetitions = (guint)reps;
    return TRUE;
}

static char *dir_of(const char *path)
{
    return g_path_get_dirname(path);
}

static gboolean read_base(SweepSpec *s, const CfgNode *root, const char *text,
                          GError **err)
{
    const CfgNode *b = cfg_get(root, "base");
    if (!b) {
        cfg_error(err, root, "no 'base'", "base: <config path> or a map");
        return FALSE;
    }
    if (cfg_kind(b) == CFG_MAP) {
        s->base = cfg_copy(b);
        s->base_text = g_strdup(text);
        return TRUE;
    }
    if (cfg_kind(b) != CFG_SCALAR) {
        cfg_error(err, b, "a list", "a config path or an inline map");
        return FALSE;
    }
    char *dir = dir_of(s->path);
    char *path = g_path_is_absolute(cfg_scalar(b))
                     ? g_strdup(cfg_scalar(b))
                     : g_build_filename(dir, cfg_scalar(b), NULL);
    g_free(dir);
    s->base = cfg_load_file(path, err);
    if (s->base && cfg_kind(s->base) != CFG_MAP) {
        char *found = cfg_describe(s->base);
        cfg_error(err, s->base, found, "a run config (a map)");
        g_free(found);
        cfg_free(s->base);
        s->base = NULL;
    }
    if (s->base)
        sim_file_read(path, &s->base_text, NULL, NULL);
    else /* say which sweep file named it */
        g_prefix_error(err, "%s:%d:%d: base: ", cfg_file(b), cfg_line(b),
                       cfg_col(b));
    g_free(path);
    return s->base != NULL;
}

static gboolean read_seed(SweepSpec *s, const CfgNode *root, GError **err)
{
    const char *key = "run.seed";
    if (!cfg_get_str(root, "seed_key", FALSE, &key, err))
        return FALSE;
    s->seed_key = g_strdup(key);
    int64_t seed = 1;
    const CfgNode *in_base = cfg_path(s->base, s->seed_key);
    if (in_base && cfg_scalar(in_base))
        seed = g_ascii_strtoll(cfg_scalar(in_base), NULL, 10);
    if (!cfg_get_int(root, "seed", FALSE, 0, G_MAXINT64, &seed, err))
        return FALSE;
    s->seed = (uint64_t)seed;
    return TRUE;
}

static char *stem_of(const char *path)
{
    char *base = g_path_get_basename(path);
    char *dot = strrchr(base, '.');
    if (dot && dot != base)
        *dot = '\0';
    return base;
}

static gboolean read_name(SweepSpec *s, const CfgNode *root, GError **err)
{
    const char *name = NULL;
    if (!cfg_get_str(root, "name", FALSE, &name, err))
        return FALSE;
    s->name = name ? g_strdup(name) : stem_of(s->path);
    /* it names the default output folder out/<name> */
    return !name ||
           plot_cfg_name_ok(cfg_get(root, "name"), "sweep", name, err);
}

static gboolean read_spec(SweepSpec *s, const CfgNode *root, const char *text,
                          GError **err)
{
    if (cfg_kind(root) != CFG_MAP) {
        cfg_error(err, root, "a document that is not a map",
                  "a map with 'base' and 'parameters'");
        return FALSE;
    }
    const CfgNode *pmap = cfg_get(root, "parameters");
    const CfgNode *plots = cfg_get(root, "plots");
    return check_keys(root, top_keys, err) && read_name(s, root, err) &&
           read_base(s, root, text, err) && read_seed(s, root, err) &&
           read_combine(s, root, err) && read_params(s, pmap, err) &&
           count_combos(s, pmap, err) &&
           (!plots || plot_specs_read(s->plots, plots, err));
}

SweepSpec *sweep_spec_parse(const char *text, const char *name, GError **err)
{
    CfgNode *root = cfg_load_string(text, name, err);
    if (!root)
        return NULL;
    SweepSpec *s = g_new0(SweepSpec, 1);
    s->path = g_strdup(name);
    s->params = g_ptr_array_new_with_free_func(param_free);
    s->plots = g_ptr_array_new_with_free_func(plot_spec_free);
    gboolean ok = read_spec(s, root, text, err);
    cfg_free(root);
    if (!ok) {
        sweep_spec_free(s);
        return NULL;
    }
    return s;
}

SweepSpec *sweep_spec_load(const char *path, GError **err)
{
    char *text = NULL;
    if (!sim_file_read(path, &text, NULL, err))
        return NULL;
    SweepSpec *s = sweep_spec_parse(text, path, err);
    g_free(text);
    return s;
}

/* ---- points ---------------------------------------------------------- */

guint sweep_spec_points(const SweepSpec *s)
{
    return s->combos * s->repetitions;
}

SweepPoint sweep_spec_point(const SweepSpec *s, guint index)
{
    g_assert(index < sweep_spec_points(s));
    SweepPoint pt = {index, index / s->repetitions, index % s->repetitions,
                     s->seed};
    if (pt.rep > 0) /* 63 bits: run.seed is read as a signed integer */
        pt.seed = sim_rng_mix(s->seed + pt.rep) >> 1;
    return pt;
}

const char *sweep_spec_value(const SweepSpec *s, const SweepPoint *pt, guint p)
{
    g_assert(p < s->params->len);
    guint c = pt->combo;
    const SweepParam *sp = NULL;
    /* product: the last parameter varies fastest */
    for (guint i = s->params->len; i-- > p;) {
        sp = g_ptr_array_index(s->params, i);
        if (i > p && !s->zip)
            c /= sp->values->len;
    }
    return g_ptr_array_index(sp->values, c % sp->values->len);
}

static gboolean set_one(CfgNode *cfg, const char *key, const char *value,
                        GError **err)
{
    char *a = g_strdup_printf("%s=%s", key, value);
    gboolean ok = cfg_set_override(cfg, a, err);
    g_free(a);
    return ok;
}

CfgNode *sweep_spec_config(const SweepSpec *s, const SweepPoint *pt,
                           GError **err)
{
    CfgNode *cfg = cfg_copy(s->base);
    char seed[32];
    g_snprintf(seed, sizeof seed, "%" G_GUINT64_FORMAT, pt->seed);
    gboolean ok = set_one(cfg, s->seed_key, seed, err);
    for (guint p = 0; ok && p < s->params->len; p++) {
        const SweepParam *sp = g_ptr_array_index(s->params, p);
        ok = set_one(cfg, sp->key, sweep_spec_value(s, pt, p), err);
    }
    if (!ok) {
        cfg_free(cfg);
        return NULL;
    }
    return cfg;
}

char *sweep_spec_fingerprint(const SweepSpec *s)
{
    GString *t = g_string_new(s->base_text);
    g_string_append_printf(t, "\n%s %u %" G_GUINT64_FORMAT " %s\n",
                           s->zip ? "zip" : "product", s->repetitions, s->seed,
                           s->seed_key);
    for (guint i = 0; i < s->params->len; i++) {
        const SweepParam *p = g_ptr_array_index(s->params, i);
        g_string_append_printf(t, "%s:", p->key);
        for (guint v = 0; v < p->values->len; v++)
            g_string_append_printf(t, " %s",
                                   (char *)g_ptr_array_index(p->values, v));
        g_string_append_c(t, '\n');
    }
    char *sum = g_compute_checksum_for_string(G_CHECKSUM_SHA256, t->str, -1);
    g_string_free(t, TRUE);
    return sum;
}
