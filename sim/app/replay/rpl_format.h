/* rpl_format.h — pgsim's time-independent trace format, version 4
 * (docs/traces.md; version 3 is version 4 without `after` and `&`,
 * version 2 is version 3 without `|` terms, version 1 is version 2
 * without b, v and swap).
 *
 * A trace is text, one item per line, '#' starts a comment:
 *
 *     pgsim-trace 4                       first line: the version
 *     machine ipsc2                       recording machine (a model name)
 *     fidelity packet                     its transport when recorded
 *     procs 17                            processors 0 .. 16
 *     kind node 0 16 16000000             recording kinds: name, first id,
 *                                         count, clock in Hz (0: none)
 *     phase compute                       phase names, ids 0, 1, ... in order
 *     at 0                                a group: issued at time 0 (ps)
 *     sync 8000                           a group: issued when all earlier
 *                                         work is done (recorded at 8000 ps)
 *     on 12                               a group: issued when action 12
 *                                         completes (work done / delivered)
 *     c 3 1 span=1240 zcmp=5310 [+] [frame]   work on processor 3, phase 1,
 *                                         priced from the machine's costs
 *     c 2 3 draw_vertex=900 | @4 triangle=300 | b 4 86400
 *                                         work on 2 as long as the longest
 *                                         term: its own counts, counts priced
 *                                         on 4's kind, 86400 bytes to 4
 *                                         through the shared memory
 *     w 3 1 125000 [+] [frame]            work that took 125000 ps on the
 *                                         recording kind (scaled by clocks)
 *     s 3 5 1024 [+] [frame]              3 sends 1024 bytes to 5
 *     b 3 4 1024 [+] [frame]              3 moves 1024 bytes to 4 through
 *                                         the shared memory
 *     v 2 33333333334 [+] [swap]          processor 2 waits for the first
 *                                         multiple of this period (a display
 *                                         refresh); `swap`: a frame ends then
 *
 * Actions (c, w, s) are numbered 0, 1, ... in file order; `+` says an
 * `on ID` group for this action follows later; `frame` says a frame ends
 * when it completes.  Every action belongs to the group above it.
 * `after ID` before the flags (version 4): the action is issued when its
 * group is and action ID has completed (a join); ID is an earlier action
 * marked `&`, named by exactly one `after`.
 *
 * The reader checks everything a replay relies on (ranges, that `on`
 * names an earlier action marked `+`, once) with located errors, and
 * keeps O(1) state per line apart from one bit per action marked `+`
 * that is still awaited (hash set).
 */
#ifndef PGSIM_APP_REPLAY_RPL_FORMAT_H
#define PGSIM_APP_REPLAY_RPL_FORMAT_H

#include "sim/app/replay/rpl_lines.h"
#include "sim/core/time.h"

#define RPL_VERSION 4
#define RPL_MAX_OPS 30
#define RPL_MAX_TERMS 3 /* `|` terms of a `c` line (version 3) */
#define RPL_TERM_OPS 8  /* OP=COUNT words in one `|` term */
/* Clocks a trace or --clock may give (Hz): below 1 Hz or above 1 PHz a
 * clock ratio turns any recorded work into 0 ps or the end of time. */
#define RPL_CLOCK_MIN 1.0
#define RPL_CLOCK_MAX 1e15

/* A further term of a `c` line: its work overlaps the processor's own
 * counts, and the action lasts as long as the longest term (version 3). */
typedef struct {
    uint32_t proc;  /* `@Q`: priced on Q's kind; `b Q`: the receiver */
    gboolean bus;   /* `b Q BYTES`: a shared-memory transfer's time */
    uint64_t bytes; /* bus: the bytes */
    guint n_ops;
    const char *op[RPL_TERM_OPS]; /* borrowed until the next item */
    uint64_t count[RPL_TERM_OPS];
    int op_col[RPL_TERM_OPS];
    int col; /* where the term's first word starts */
} RplTerm;

typedef struct {
    char *name;
    guint first, count;
    double clock_hz; /* 0: not given */
    guint line;      /* where the reader found it (0: not read) */
    int col;         /* ... and its FIRST word */
} RplKind;

typedef struct {
    char *machine;  /* NULL when absent */
    char *fidelity; /* NULL when absent */
    guint procs;
    GPtrArray *phases; /* char * */
    GArray *kinds;     /* RplKind: sorted by first id, disjoint, each
                          within procs (the reader checks and sorts) */
} RplHeader;

typedef enum {
    RPL_AT,
    RPL_ON,
    RPL_COMPUTE,
    RPL_WORK,
    RPL_SEND,
    RPL_SYNC,
    RPL_BUS,    /* b: a shared-memory transfer (version 2) */
    RPL_REFRESH /* v: a wait for a refresh (version 2) */
} RplItemType;

typedef struct {
    RplItemType type;
    guint line;
    uint64_t id;    /* actions: their number; RPL_ON: the cause */
    SimTime at;     /* RPL_AT, RPL_SYNC (the recorded time) */
    uint32_t proc;  /* actions: the processor (sender) */
    uint32_t peer;  /* RPL_SEND: the receiver */
    unsigned phase; /* RPL_COMPUTE, RPL_WORK */
    uint64_t value; /* RPL_WORK: ps; RPL_SEND, RPL_BUS: bytes;
                       RPL_REFRESH: the period (ps) */
    gboolean handled, frame, swap;
    gboolean joined;    /* `&` (version 4): a later action is `after` it */
    gboolean has_after; /* `after ID` (version 4): it waits also for ID */
    uint64_t after;
    guint n_ops;   /* RPL_COMPUTE: op names (borrowed until the next item) */
    guint n_terms; /* RPL_COMPUTE: `|` terms (version 3), else 0 */
    const char *op[RPL_MAX_OPS];
    uint64_t count[RPL_MAX_OPS];
    int op_col[RPL_MAX_OPS]; /* where each op=count word starts */
    RplTerm term[RPL_MAX_TERMS];
} RplItem;

typedef struct RplReader RplReader;

/* Opens a trace and reads its header; NULL with a located *err. */
RplReader *rpl_reader_open(const char *path, GError **err);
void rpl_reader_free(RplReader *r);
const RplHeader *rpl_reader_header(const RplReader *r);
const char *rpl_reader_path(const RplReader *r);
/* The next body item: TRUE and *it, or FALSE at the end (*err NULL) or
 * on an error (*err set, located). */
gboolean rpl_reader_next(RplReader *r, RplItem *it, GError **err);
/* Actions marked `+` whose `on` group, or `&` whose `after`, has not
 * been read yet. */
guint rpl_reader_awaited(const RplReader *r);

/* The kind (borrowed) that holds recording processor p, or NULL;
 * O(log kinds). */
const RplKind *rpl_header_kind_of(const RplHeader *h, guint p);
void rpl_header_clear(RplHeader *h);

/* Writing: the header lines, then items, with the same syntax. */
void rpl_write_header(RplWriter *w, const RplHeader *h);
void rpl_write_item(RplWriter *w, const RplItem *it);

#endif
