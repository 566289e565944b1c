/* result.h — the one result structure every workload fills.
 *
 * Frame times, per-node utilisation (overall and per phase), communication
 * volume, named workload metrics in insertion order, and simulator figures.
 * Writers (text, JSON, CSV) are in sim/app/run/report.c; docs/output.md is the
 * schema.  Wall-clock figures are kept apart (wall_s) because they are the
 * only non-deterministic numbers a run produces.
 */
#ifndef PGSIM_CORE_RESULT_H
#define PGSIM_CORE_RESULT_H

#include "sim/core/inputs.h"
#include "sim/core/engine.h"
#include "sim/core/stats.h"

typedef struct {
    char *name;   /* "gp3", "node12" */
    char *kind;   /* "gp", "renderer", "node" ... */
    SimBusy busy; /* per_phase indexed like SimResult.phases */
} SimNodeResult;

/* Processors of one kind that did nothing (busy 0 in every phase): one
 * entry per kind instead of one SimNodeResult each, so a result's size
 * follows the work, not the machine. */
typedef struct {
    char *kind;
    uint64_t count;
} SimIdleResult;

typedef struct {
    char *name;
    char *unit; /* "" when dimensionless */
    double value;
} SimMetric;

typedef struct {
    char *workload;
    char *machine;
    char *fidelity;
    uint64_t seed;
    GArray *frame_times; /* SimTime per frame */
    SimTime elapsed;     /* simulated time at the end of the run */
    GPtrArray *phases;   /* char *, phase names by id */
    GPtrArray *nodes;    /* SimNodeResult *, processors that were busy */
    GPtrArray *idle;     /* SimIdleResult *, by kind in first-seen order */
    uint64_t comm_bytes;
    uint64_t comm_messages;
    char *busiest_link; /* NULL when no message was sent */
    uint64_t busiest_link_bytes;
    GPtrArray *metrics; /* SimMetric *, insertion order */
    uint64_t events;    /* engine events run */
    double wall_s;      /* wall-clock seconds of the run (not deterministic) */
    /* Provenance, filled by the application (NULL when unknown): the
     * config file as named, the SHA-256 of its bytes, the config after
     * overrides as JSON text, and the overrides (char *) in order. */
    char *config_path;
    char *config_sha256;
    char *config_effective;
    GPtrArray *overrides;
    /* Feasibility, filled by the runner (sim/run/): the per-node memory
     * footprint the workload reported (its declared `peak_memory` metric,
     * bytes; NAN when it reports none) and the memory of one node of the
     * processors it used (the smallest over their kinds, mem_kind; 0 when
     * the model gives none). */
    double mem_peak;
    uint64_t mem_node;
    char *mem_kind;
    /* char *: sentences a reader needs beside the numbers, set by the
     * workload or the runner (why a speed-up is above P ...); printed
     * after the metrics, in JSON `notes` (only when there are some). */
    GPtrArray *notes;
    SimInputs *inputs; /* the model, scene, mesh, database and trace
                          files read (inputs.h); NULL: none noted */
} SimResult;

/* Returns a new empty result; free with sim_result_free(). */
SimResult *sim_result_new(const char *workload, const char *machine);
void sim_result_free(SimResult *r);

void sim_result_add_frame(SimResult *r, SimTime t);
/* Appends a node; returns it (borrowed) for filling busy times. */
SimNodeResult *sim_result_add_node(SimResult *r, const char *name,
                                   const char *kind);
/* Counts n more idle processors of `kind` (merged per kind). */
void sim_result_add_idle(SimResult *r, const char *kind, uint64_t n);
/* Idle processors over all kinds. */
uint64_t sim_result_n_idle(const SimResult *r);
/* Sets (or replaces) a named metric, keeping first-insertion order. */
void sim_result_set_metric(SimResult *r, const char *name, double value,
                           const char *unit);
/* Looks a metric up; returns FALSE if absent. */
gboolean sim_result_get_metric(const SimResult *r, const char *name,
                               double *value);
/* A metric's value, NAN when absent (for tables that mark it missing). */
double sim_result_metric(const SimResult *r, const char *name);
/* Copies phase names from the engine so node busy ids resolve. */
void sim_result_set_phases(SimResult *r, const SimEngine *eng);
double sim_result_mean_frame_s(const SimResult *r);
/* busy / elapsed for a node, 0 when elapsed is 0. */
double sim_result_node_util(const SimResult *r, const SimNodeResult *n);

/* Utilisation over the processors the workload used (busy at all, the
 * entries of r->nodes): the idle ones (sim_result_n_idle) are counted
 * apart, not averaged in as zeros, so a run on 2 of a machine's 64 nodes
 * reads its 2 nodes' utilisation.  All 0 when no processor was busy. */
typedef struct {
    uint64_t used; /* processors busy at some time */
    uint64_t idle; /* processors never busy */
    double mean;   /* mean of busy / elapsed over the used ones */
    double max;
} SimUtilUsed;

SimUtilUsed sim_result_util_used(const SimResult *r);

/* Appends a note (copied). */
void sim_result_add_note(SimResult *r, const char *text);

/* The metric a workload declares for its largest per-node footprint. */
#define SIM_PEAK_MEMORY_METRIC "peak_memory"

/* TRUE when the run's per-node footprint is known, the node memory is
 * known and the footprint exceeds it: the configuration would not fit
 * on the machine it was simulated on. */
gboolean sim_result_mem_exceeds(const SimResult *r);
/* "per-node memory 14.02 MiB exceeds the 4.00 MiB of a node (kind node):
 * this configuration does not fit on MACHINE" (g_free), or NULL when it
 * fits or is unknown. */
char *sim_result_mem_note(const SimResult *r);

#endif
