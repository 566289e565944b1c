/* trace_impl.h — shared state of the trace writers (trace_file.c,
 * trace_chrome.c, trace_paje.c); not for other modules.
 *
 * trace_file.c owns everything the formats share: the SimTraceOps (one
 * table for every format), the event cap and its note, node names, flow
 * ids, the counters derived from flows, and the per-link tracks: the
 * bandwidth use (from the packet rung's holds where a link reports them,
 * else from messages' routes) and the queue depth (messages waiting, from
 * the packet rung's waits).  A TrcFormat only writes.
 */
#ifndef PGSIM_APP_TRACE_TRACE_IMPL_H
#define PGSIM_APP_TRACE_TRACE_IMPL_H

#include "sim/app/trace/trace_file.h"
#include <stdio.h>

typedef struct TrcWriter TrcWriter;

/* A link's latest hold not yet turned into deltas: contiguous holds at
 * the same rate are merged, so back-to-back packets make one step. */
typedef struct {
    SimTime start, end;
    double rate;
    gboolean held; /* the link reported holds: ignore route averages */
} TrcHold;

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
    /* One sample of a network link's track `which` (TRC_LINK_BW: its
     * bandwidth use in B/s; TRC_LINK_QUEUE: messages waiting for it), in
     * time order per link and track; the link's name is
     * w->link_names[link]. */
    void (*link_counter)(TrcWriter *w, guint link, int which, SimTime t,
                         double value);
    void (*end)(TrcWriter *w);
} TrcFormat;

/* The counters derived from flows: a message is in flight from its send
 * to its arrival. */
enum { TRC_MSGS_IN_FLIGHT, TRC_BYTES_IN_FLIGHT, TRC_N_COUNTERS };
extern const char *const trc_counter_names[TRC_N_COUNTERS];
extern const char *const trc_counter_units[TRC_N_COUNTERS];

/* The per-link tracks. */
enum { TRC_LINK_BW, TRC_LINK_QUEUE, TRC_N_LINK_TRACKS };

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
    GArray *link_deltas;       /* TrcLinkDelta: track changes per link */
    GArray *link_holds;        /* TrcHold per link index: the open hold */
    gboolean links_begun;      /* Chrome: the links' process is named */
    GPtrArray *buffer;         /* Paje: lines waiting to be sorted by time */
};

extern const TrcFormat trc_chrome;
extern const TrcFormat trc_paje;

#endif
