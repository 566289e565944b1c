/* sweep_spec.h — sweep files: a base config, parameters, repetitions.
 *
 * A sweep file (docs/sweeps.md) names a base run config (a path relative
 * to the sweep file, or an inline map), parameters as --set-style key
 * paths with value lists or ranges, how to combine them (product: every
 * combination, the first parameter varying slowest; zip: the i-th value
 * of each), a number of repetitions with derived seeds, and plots.
 *
 * Points are numbered 0 .. n-1: point = combination * repetitions + rep.
 * Expansion is O(1) per point (mixed-radix decoding); nothing is stored
 * per point.
 */
#ifndef PGSIM_APP_SWEEP_SWEEP_SPEC_H
#define PGSIM_APP_SWEEP_SWEEP_SPEC_H

#include "sim/output/plot.h"
#include "sim/core/cfg.h"

typedef struct {
    char *key;         /* "machine.nodes" */
    GPtrArray *values; /* char *, YAML scalar text */
} SweepParam;

typedef struct {
    char *path;        /* the sweep file */
    char *name;        /* sweep name (file stem by default) */
    CfgNode *base;     /* base config, owned */
    GPtrArray *params; /* SweepParam *, in file order */
    gboolean zip;      /* FALSE: product */
    guint repetitions; /* >= 1 */
    uint64_t seed;     /* seed of repetition 0 */
    char *seed_key;    /* config key the seed is written to ("seed") */
    guint combos;      /* number of parameter combinations */
    GPtrArray *plots;  /* PlotSpec * */
    char *base_text;   /* what the fingerprint covers of the base */
} SweepSpec;

typedef struct {
    guint index, combo, rep;
    uint64_t seed;
} SweepPoint;

/* Reads and expands a sweep file; returns a new spec (free with
 * sweep_spec_free()) or NULL with a located *err. */
SweepSpec *sweep_spec_load(const char *path, GError **err);
/* The same from text; `name` is the file name used in errors and the
 * directory that relative base paths are resolved against. */
SweepSpec *sweep_spec_parse(const char *text, const char *name, GError **err);
void sweep_spec_free(SweepSpec *s);

guint sweep_spec_points(const SweepSpec *s);
/* Decodes a point index (< sweep_spec_points()). */
SweepPoint sweep_spec_point(const SweepSpec *s, guint index);
/* The value of parameter p at a point.  Borrowed. */
const char *sweep_spec_value(const SweepSpec *s, const SweepPoint *pt, guint p);
/* A new config for the point: the base with every parameter and the seed
 * applied (cfg_set_override); NULL with *err if an override fails. */
CfgNode *sweep_spec_config(const SweepSpec *s, const SweepPoint *pt,
                           GError **err);
/* A fingerprint of the expanded sweep (parameters, values, repetitions,
 * seeds, base config text) for checking that --resume continues the same
 * sweep; free with g_free(). */
char *sweep_spec_fingerprint(const SweepSpec *s);

#endif
