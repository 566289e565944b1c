/* trace_impl.h — shared state of the trace writers (trace_file.c,
 * trace_chrome.c, trace_paje.c); not for other modules. */
#ifndef PGSIM_APP_TRACE_TRACE_IMPL_H
#define PGSIM_APP_TRACE_TRACE_IMPL_H

#include "sim/app/trace/trace_file.h"
#include <stdio.h>

typedef struct TrcWriter TrcWriter;

typedef struct {
    void (*begin)(TrcWriter *w);
    /* Writes the note that the cap was reached, at simulated time t. */
    void (*cap_note)(TrcWriter *w, SimTime t);
    void (*end)(TrcWriter *w);
    const SimTraceOps *ops;
} TrcFormat;

struct TrcWriter {
    SimTrace trace; /* first: a SimTrace * is a TrcWriter * */
    const TrcFormat *fmt;
    FILE *f;
    char *path, *tmp;
    uint64_t cap, events, next_flow;
    gboolean truncated;
    GHashTable *nodes;         /* node id + 1 -> name (seen nodes) */
    GHashTable *default_named; /* node id + 1 of nodes named "node<id>" */
    GPtrArray *buffer;         /* Paje: lines waiting to be sorted by time */
};

/* Counts one event; FALSE once the cap is reached (then the note is
 * written once).  Every hook calls it first. */
gboolean trc_admit(TrcWriter *w, SimTime t);
/* TRUE the first time a node id is seen, and when a node first seen
 * without a name (NULL: "node<id>") gets one; the name is remembered. */
gboolean trc_new_node(TrcWriter *w, uint32_t node, const char *name);

extern const TrcFormat trc_chrome;
extern const TrcFormat trc_paje;

#endif
