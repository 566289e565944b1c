/* rpl_target.h — the machine a trace is replayed on: built from a model
 * with overrides and a size, the map of trace processors onto it, and
 * the price of each action there.
 *
 * rpl_target_check() reads a whole trace once (streaming) before the
 * replay and collects every problem a replay would meet part way:
 * costs the target lacks (all of them, one error), work that cannot be
 * scaled (no clock), sends on a machine without a network (`b`
 * transfers: without a shared memory or a network), and recorded work
 * that the target's clocks and costs all turn into 0 ps.
 *
 * Memory does not grow with the trace's processor count: the map and
 * the clock ratios are computed per action (a map file, one line per
 * trace processor, is kept in an array of that size).
 */
#ifndef PGSIM_APP_REPLAY_RPL_TARGET_H
#define PGSIM_APP_REPLAY_RPL_TARGET_H

#include "sim/app/replay/rpl_format.h"
#include "sim/app/replay/rpl_replay.h"
#include "sim/machine/machine.h"
#include "sim/machine/shmem.h"

typedef struct {
    SimEngine *eng;
    MachMachine *m;
    char *desc;        /* the partition ("node 16"), NULL at the model's size */
    guint n_trace;     /* trace processors */
    gboolean cyclic;   /* the map: cyclic, else block (no map file) */
    guint *map;        /* a map file's: trace processor -> target id + 1,
                          else NULL (rpl_target_map() computes it) */
    RplHeader rec;     /* the trace's machine and kinds (a copy) */
    char *model;       /* the target model's name as given */
    guint64 work, zero_work; /* check: actions with recorded work, and
                                those priced at 0 ps */
    guint zero_line;   /* the first of those */
    gboolean clock_missing; /* a `w` found no clock (reported once) */
    unsigned *phase;   /* header phase index -> engine phase id */
    GHashTable *costs; /* "kind\top" -> SimTime * (NULL: missing) */
    CfgNode *tree;     /* the target model with --set: costs named by a
                          model path (dpscan.op) */
    GHashTable *clocks; /* --clock: trace kind -> double Hz */
    SimEngine *from_eng; /* --costs-from: its model, or NULL */
    MachMachine *from;
    gboolean has_shm;     /* a bus model: `b` transfers use its memory */
    MachShmem shm;        /* else they go through the network as messages */
    gboolean shm_missing; /* a `| b` term found no shared memory */
} RplTarget;

/* Builds the target for a trace whose header is h. */
RplTarget *rpl_target_new(const RplReplayOpts *o, const RplHeader *h,
                          GError **err);
void rpl_target_free(RplTarget *t);
/* The target processor of trace processor p (< n_trace): the map file's,
 * else block or cyclic; O(1), no state per trace processor. */
guint rpl_target_map(const RplTarget *t, guint p);
/* Recording clock / target clock for `w` work of trace processor p: 1 on
 * the recording machine's own kinds, NAN when a clock is missing;
 * O(log kinds). */
double rpl_target_scale(const RplTarget *t, guint p);
/* Reads the trace at path to its end and checks it against the target. */
gboolean rpl_target_check(RplTarget *t, const char *path, GError **err);
/* The cost of one `op` on trace processor p's target kind (else, with
 * --costs-from, the other model's cost of op on p's recording kind,
 * scaled by that kind's clock there — or --clock — over the target
 * kind's), or NULL when the models lack it; *fresh: first time this
 * target kind, recording kind and op were asked. */
const SimTime *rpl_target_op_cost(RplTarget *t, guint p, const char *op,
                                  gboolean *fresh);
/* The cost of a checked `c` or `w` item on its target processor (a `c`
 * line with `|` terms: the longest of its counts and terms, each term's
 * counts priced on its own processor's target kind, a bus term as the
 * transfer's time on an idle shared memory). */
SimTime rpl_target_price(RplTarget *t, const RplItem *it);

#endif
