/* cfg.h — configuration trees with source locations, and typed getters.
 *
 * A YAML document (libyaml) becomes a tree of CfgNode: maps, sequences
 * and scalars, each remembering file, line and column.  Getters convert
 * scalars to typed values with units and ranges and report every problem
 * as "file:line:column: found <what>, expected <what>" (SIM_ERROR_INPUT).
 * Maps remember which keys were read, so cfg_check_unused() can reject
 * unknown keys after a consumer has taken what it knows.
 *
 * Units (case as written): times ps ns us µs ms s; bandwidths B/s KB/s
 * MB/s GB/s (decimal, also Kbit/s Mbit/s Gbit/s); frequencies Hz kHz MHz
 * GHz; sizes B KB MB GB (decimal) KiB MiB GiB (binary); counts with an
 * optional K (1e3) or M (1e6) suffix ("16K").  A space between number and
 * unit is optional ("2.8MB/s", "640 MB/s").
 */
#ifndef PGSIM_CORE_CFG_H
#define PGSIM_CORE_CFG_H

#include "sim/core/error.h"
#include "sim/core/time.h"
#include <stdint.h>

typedef enum { CFG_MAP, CFG_SEQ, CFG_SCALAR, CFG_NULL } CfgKind;

typedef struct CfgNode CfgNode;

/* Parses a YAML file; returns a new tree (free with cfg_free()) or NULL
 * with *err set (unreadable file, YAML syntax error, duplicate key).  A
 * relative path that does not exist from the current directory is looked
 * up among the data roots (sim/core/datapath.h), so the project's own
 * configs and models load wherever pgsim runs. */
CfgNode *cfg_load_file(const char *path, GError **err);
/* Parses YAML text; `name` is used as the file name in errors. */
CfgNode *cfg_load_string(const char *text, const char *name, GError **err);
void cfg_free(CfgNode *n);
CfgNode *cfg_copy(const CfgNode *n);

CfgKind cfg_kind(const CfgNode *n);
const char *cfg_file(const CfgNode *n);
int cfg_line(const CfgNode *n);
int cfg_col(const CfgNode *n);
/* Scalar text (NULL for non-scalars). Borrowed. */
const char *cfg_scalar(const CfgNode *n);

/* Map access.  cfg_get() marks the key as read; NULL when absent. */
const CfgNode *cfg_get(const CfgNode *map, const char *key);
/* TRUE when map has key; marks nothing and notes nothing (for checks
 * that must not change what counts as read or expected). */
gboolean cfg_has(const CfgNode *map, const char *key);
guint cfg_map_len(const CfgNode *map);
const char *cfg_map_key(const CfgNode *map, guint i); /* marks it read */
const CfgNode *cfg_map_value(const CfgNode *map, guint i);
/* Sequence access. */
guint cfg_seq_len(const CfgNode *seq);
const CfgNode *cfg_seq_at(const CfgNode *seq, guint i);

/* Dotted paths ("machine.links.bandwidth"); NULL when absent. */
const CfgNode *cfg_path(const CfgNode *root, const char *path);

/* Typed getters on a map key.  `required`: an absent key is an error;
 * otherwise *out keeps its value (the default).  Ranges are inclusive. */
gboolean cfg_get_str(const CfgNode *map, const char *key, gboolean required,
                     const char **out, GError **err);
gboolean cfg_get_bool(const CfgNode *map, const char *key, gboolean required,
                      gboolean *out, GError **err);
gboolean cfg_get_int(const CfgNode *map, const char *key, gboolean required,
                     int64_t min, int64_t max, int64_t *out, GError **err);
gboolean cfg_get_double(const CfgNode *map, const char *key, gboolean required,
                        double min, double max, double *out, GError **err);
/* A key whose value must be a map: *out is it, or NULL when the key is
 * absent and optional.  `what` describes the map in errors, e.g.
 * "a map {base, polygon} of sizes". */
gboolean cfg_get_map(const CfgNode *map, const char *key, gboolean required,
                     const char *what, const CfgNode **out, GError **err);
/* One of a NULL-terminated list of words; *out is the index. */
gboolean cfg_get_enum(const CfgNode *map, const char *key, gboolean required,
                      const char *const *words, int *out, GError **err);
gboolean cfg_get_time(const CfgNode *map, const char *key, gboolean required,
                      SimTime *out, GError **err);
gboolean cfg_get_bandwidth(const CfgNode *map, const char *key,
                           gboolean required, double *bytes_per_s,
                           GError **err);
gboolean cfg_get_freq(const CfgNode *map, const char *key, gboolean required,
                      double *hz, GError **err);
gboolean cfg_get_size(const CfgNode *map, const char *key, gboolean required,
                      uint64_t *bytes, GError **err);
gboolean cfg_get_count(const CfgNode *map, const char *key, gboolean required,
                       uint64_t min, uint64_t max, uint64_t *out, GError **err);

/* The same conversions on a bare string (for CLI flags); `what` names the
 * source in errors, e.g. "--lookahead". */
gboolean cfg_parse_time(const char *s, const char *what, SimTime *out,
                        GError **err);
gboolean cfg_parse_bandwidth(const char *s, const char *what, double *out,
                             GError **err);
gboolean cfg_parse_size(const char *s, const char *what, uint64_t *out,
                        GError **err);
gboolean cfg_parse_count(const char *s, const char *what, uint64_t *out,
                         GError **err);

/* Located error at a node: "file:line:col: found <found>, expected <exp>". */
void cfg_error(GError **err, const CfgNode *at, const char *found,
               const char *expected);

/* Rejects the first key in `map` (recursively through maps and sequences)
 * that no getter read: "found unknown key 'k', expected one of: a, b". */
gboolean cfg_check_unused(const CfgNode *map, GError **err);
/* The same, but the values of the listed top-level keys of `map` (a
 * NULL-terminated list) are not descended into when those keys were read:
 * for sections whose consumer runs later. */
gboolean cfg_check_unused_except(const CfgNode *map, const char *const *skip,
                                 GError **err);
/* Marks every key below n as read (a section taken as a whole). */
void cfg_mark_read(const CfgNode *n);

/* Applies "a.b.c=value" (value parsed as YAML) to the tree, creating maps
 * as needed; errors name the override as "--set a.b.c=value". */
gboolean cfg_set_override(CfgNode *root, const char *assignment, GError **err);
/* Deep-merges `over` into `base` (maps merge, anything else replaces);
 * used for machine models included by name and then overridden. */
void cfg_merge(CfgNode *base, const CfgNode *over);
/* Sets key of map to value (taken), replacing the value it had; a new
 * key is located where the value is.  For a run tree built from sections
 * of other files (cfg_copy keeps their locations). */
void cfg_map_put(CfgNode *map, const char *key, CfgNode *value);

/* Describes a node for "found ...": "'text'", "a map", "a sequence",
 * "an empty value".  Returns a new string (g_free). */
char *cfg_describe(const CfgNode *n);

#endif
