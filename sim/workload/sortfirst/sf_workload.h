/* sf_workload.h — the `sortfirst` workload (seed 000, Mueller,
 * "Hierarchical graphics databases in sort-first"): WlOps row and the
 * entry points the tests use.  Keys and metrics: docs/workloads.md. */
#ifndef PGSIM_WORKLOAD_SORTFIRST_SF_WORKLOAD_H
#define PGSIM_WORKLOAD_SORTFIRST_SF_WORKLOAD_H

#include "sim/workload/sortfirst/sf_frame.h"
#include "sim/workload/workload.h"

typedef struct {
    WlSfSetup setup;
    guint granularity;
    WlSfChunking chunking;
    char *frame_log; /* CSV of per-frame figures, or NULL */
    char *database;  /* structure database file rendered instead of the
                        scene's (structdb_file.h), or NULL */
    char *dump_db;   /* where to write the database rendered, or NULL */
    WlSfEditSpec edits; /* edits per frame (sf_edit.h) */
    WlSfBvKind bv;      /* chunks' bounding volumes (sf_bv.h) */
    gboolean bv_fit;    /* bounding_volume given: its fit reported */
} WlSfParams;

extern const WlOps wl_sortfirst_ops;

/* The metrics of a finished run into out (frames: stats of each). */
void wl_sf_fill_metrics(SimResult *out, const GArray *stats, const WlSfDb *db,
                        const WlSfSetup *s);

/* The bounding volumes' fit over frames 0 .. frames-1 of the scene's
 * path (wl_sf_bv_fit() on sdb, the database db's chunks come from) and
 * one test's price: metrics bv_area_ratio, bv_false_regions_per_polygon,
 * bv_test_ns (sf_bv_metrics.c). */
void wl_sf_bv_metrics(SimResult *out, const Scene *sc, const WlSfDb *db,
                      const SceneDb *sdb, const WlSfSetup *s,
                      const WlSfCosts *c, guint frames);

#endif
