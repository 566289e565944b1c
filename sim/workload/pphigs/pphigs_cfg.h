/* pphigs_cfg.h — reading the pphigs workload's own YAML through cfg: the
 * database generator parameters (configs/pphigs/databases.yaml), a
 * user's structure database file, and the frame sizes and clustering scale (configs/pphigs/frame.yaml).  The
 * hardware (processors, costs, ring) comes from the machine layer
 * (frame.h, wl_pphigs_costs_from_machine).  Errors: "file:line:column:
 * found <what>, expected <what>" (SIM_ERROR_INPUT).
 * Seed 001 §6 (databases), §2.3.2 (clustering), §1.1 (the frame).
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_CFG_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_CFG_H

#include "sim/core/cfg.h"
#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/pphigs_frame.h"

/* One database's generator parameters (a map of databases.yaml). */
gboolean wl_pphigs_spec_from_cfg(const CfgNode *map, ScenePphigsSpec *out,
                                 GError **err);
/* Loads databases.yaml and returns the spec named `name`; an unknown name
 * is reported at `name_at` when given (the config key that asked). */
gboolean wl_pphigs_spec_load(const char *path, const char *name,
                             const CfgNode *name_at, ScenePphigsSpec *out,
                             GError **err);

/* TRUE when workload.database names a structure database file (a
 * path ending in .yaml or .yml) rather than a generator entry. */
gboolean wl_pphigs_is_db_file(const char *value);
/* Reads a user's structure database file (sim/scene/structdb_file.h);
 * NULL with *err: the file's own located error, or one at `at` (the
 * config key, required) when the file cannot be read or posts nothing. */
SceneDb *wl_pphigs_db_file_load(const char *path, const CfgNode *at,
                                GError **err);

/* The workload's own parameters (frame.yaml). */
typedef struct {
    WlPphigsFrameSpec frame;
    double cluster_scale; /* clustering factor c = max(1, scale / GPs) */
    guint strip_split;    /* §2.3.2: strip pieces of at most this many
                             triangles (0, the default: never split) */
} WlPphigsSetup;

gboolean wl_pphigs_setup_from_cfg(const CfgNode *map, WlPphigsSetup *out,
                                  GError **err);
gboolean wl_pphigs_setup_load(const char *path, WlPphigsSetup *out,
                              GError **err);
/* c = max(1, cluster_scale / ngp) (§2.3.2: "based on the number of
 * processors"). */
double wl_pphigs_cluster_factor(double cluster_scale, guint ngp);

#endif
