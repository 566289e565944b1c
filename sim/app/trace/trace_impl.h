/* trace_impl.h — shared state of the trace writers (trace_file.c,
 * trace_chrome.c, trace_paje.c); not for other modules.
 *
 * trace_file.c owns everything the formats share: the SimTraceOps (one
 * table for every format), the event cap and its note, node names, flow
 * ids, the counters derived from flows, and the per-link bandwidth use
 * derived from messages' routes.  A TrcFormat only writes.
 */
#ifndef PGSIM_APP_TRACE_TRACE_IMPL_H
#define PGSIM_APP_TRACE_TRACE_IMPL_H

#include "sim/app/trace/trace_file.h"
#include <stdio.h>

typedef struct TrcWriter TrcWriter;

typedef struct {
    void (*begin)(TrcWriter *w);
    /* A node was first seen, or a node first seen without a name (flows
     * know only ids: "node<id>") got one; its name is in w->nodes. */
    void (*node)(TrcWriter *w, uint32_t node);
    void (*span)(TrcWriter *w, uint32_t node, const char *phase,
                 SimTime start, SimTime end);
    /* A message with a per-file id (1, 2, ...). */
    void (*flow)(TrcWriter *w, uint32_t src, uint32_t dst, uint64_t bytes,
                 SimTime sent, SimTime arrived, uint64_t id);
    /* A named instant: frame boundaries, the cap note. */
    void (*mark)(TrcWriter *w, const char *name, SimTime t);
    /* One sample of a machine-wide counter track (trc_counters()), in
     * time order per counter. */
    void (*counter)(TrcWriter *w, int which, SimTime t, double value);
    /* One sample of a network link's bandwidth use (B/s), in time order
     * per link; the link's name is w->link_names[link]. */
    void (*link_counter)(TrcWriter *w, guint link, SimTime t, double bps);
    void (*end)(TrcWriter *w);
} TrcFormat;

/* The counters derived from flows: a message is in flight from its send
 * to its arrival. */
enum { TRC_MSGS_IN_FLIGHT, TRC_BYTES_IN_FLIGHT, TRC_N_COUNTERS };
extern const char *const trc_counter_names[TRC_N_COUNTERS];
extern const char *const trc_counter_units[TRC_N_COUNTERS];

struct TrcWriter {
    SimTrace trace; /* first: a SimTrace * is a TrcWriter * */
    const TrcFormat *fmt;
    FILE *f;
    char *path, *tmp;
    uint64_t cap, events, next_flow;
    gboolean truncated;
    GHashTable *nodes;         /* node id + 1 -> name (seen nodes) */
    GHashTable *default_named; /* node id + 1 of nodes named "node<id>" */
    GArray *deltas;            /* TrcDelta: flow starts and ends */
    GHashTable *link_index;    /* NetLinkId -> index + 1 (links seen) */
    GPtrArray *link_names;     /* index -> name */
    GArray *link_deltas;       /* TrcLinkDelta: rate changes per link */
    gboolean links_begun;      /* Chrome: the links' process is named */
    GPtrArray *buffer;         /* Paje: lines waiting to be sorted by time */
};

extern const TrcFormat trc_chrome;
extern const TrcFormat trc_paje;

#endif
