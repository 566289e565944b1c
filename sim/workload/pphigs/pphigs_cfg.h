/* pphigs_cfg.h — reading the pphigs workload's YAML through cfg: the
 * database generator parameters (configs/pphigs/databases.yaml), the GP
 * cost table (`pphigs:` section of models/pixel-planes-5.yaml), the
 * Pixel-Planes 5 frame hardware (the model's `nodes` and `network`
 * sections) and the frame's screen and command sizes (configs/pphigs/
 * frame.yaml).  Errors: "file:line:column: found <what>, expected <what>"
 * (SIM_ERROR_INPUT).  Seed 001 §6 (databases), §1.1 (the machine).
 */
#ifndef PGSIM_WORKLOAD_PPHIGS_PPHIGS_CFG_H
#define PGSIM_WORKLOAD_PPHIGS_PPHIGS_CFG_H

#include "sim/core/cfg.h"
#include "sim/scene/pphigs_db.h"
#include "sim/workload/pphigs/frame.h"

/* One database's generator parameters (a map of databases.yaml). */
gboolean wl_pphigs_spec_from_cfg(const CfgNode *map, ScenePphigsSpec *out,
                                 GError **err);
/* Loads databases.yaml and returns the spec named `name`. */
gboolean wl_pphigs_spec_load(const char *path, const char *name,
                             ScenePphigsSpec *out, GError **err);

/* The `pphigs` section of a model tree: costs and cluster_scale. */
gboolean wl_pphigs_costs_from_cfg(const CfgNode *model, WlPphigsCosts *c,
                                  double *cluster_scale, GError **err);

/* Frame hardware from a model tree (GP send cost, renderer and frame
 * buffer costs, renderer and GP counts, ring parameters) and the frame
 * map (screen, region, command bytes, batch).  `s->gp` is left alone. */
gboolean wl_pphigs_hw_from_cfg(const CfgNode *model, const CfgNode *frame,
                               WlPphigsFrameSpec *s, NetParams *np,
                               guint *max_gps, GError **err);

/* Everything the frame needs from a model file and a frame file. */
typedef struct {
    WlPphigsCosts costs;
    double cluster_scale;
    WlPphigsFrameSpec frame; /* frame.gp == costs */
    NetParams net;
    guint max_gps;
    NetFidelity fidelity;    /* of the ring transport */
} WlPphigsHw;

gboolean wl_pphigs_hw_load(const char *model_path, const CfgNode *frame,
                           WlPphigsHw *hw, GError **err);

#endif
