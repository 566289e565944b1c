/* rpl_simgrid.h — replaying a SimGrid time-independent trace
 * (rpl_sgparse.h) on a pgsim machine.
 *
 * Each rank is a sequential process on its mapped processor: `compute`
 * is priced at the target's `nodes.KIND.costs.flop` (time per flop, the
 * per-node rate; set it with --set machine.nodes.KIND.costs.flop=...),
 * `send` blocks until its message is delivered and `isend` does not,
 * `recv` blocks until a message from SRC with TAG has arrived (FIFO per
 * source, destination and tag), `wait`/`waitall` block on requests, and
 * a collective starts when every rank has reached it and runs as
 * pgsim's collective over the machine's network (sim/net/collective.h):
 * barrier, broadcast, allreduce (recursive doubling), all-to-all (shift
 * schedule); reduce runs as a broadcast from the root (the same
 * binomial tree, messages reversed: equal time on the symmetric
 * networks pgsim models — an assumption).  Collectives need one rank per
 * network endpoint, in order (--nodes RANKS, --map block).
 *
 * Streaming: one pass checks the file; the replay reads lines as ranks
 * need them, buffering other ranks' lines (memory follows the skew
 * between ranks, not the trace length).
 */
#ifndef PGSIM_APP_REPLAY_RPL_SIMGRID_H
#define PGSIM_APP_REPLAY_RPL_SIMGRID_H

#include "sim/app/replay/rpl_replay.h"

SimResult *rpl_replay_simgrid(const RplReplayOpts *o, GError **err);

#endif
