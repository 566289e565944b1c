/* rpl_sgparse.h — reading SimGrid time-independent trace actions.
 *
 * One action a line, `RANK ACTION ARGS...` (RANK may be written p3), as
 * SimGrid's MPI replay reads them (src/smpi/internals/smpi_replay.cpp):
 *
 *     R init [T]              R finalize            R comm_size N
 *     R compute FLOPS         R sleep SECONDS
 *     R send DST [TAG] SIZE   R isend DST [TAG] SIZE
 *     R recv SRC [TAG] SIZE   R irecv SRC [TAG] SIZE
 *     R wait [SRC DST TAG]    R waitall
 *     R barrier               R bcast SIZE [ROOT]
 *     R reduce COMM COMP [ROOT]   R allreduce COMM COMP   R alltoall SEND RECV
 *
 * (older spellings allReduce and allToAll too; a trailing datatype word
 * is accepted and ignored).  Sizes are elements: bytes, or 8-byte
 * doubles when the rank's `init` names a datatype (SimGrid's MPE
 * default).  Errors are located (file:line:column).
 */
#ifndef PGSIM_APP_REPLAY_RPL_SGPARSE_H
#define PGSIM_APP_REPLAY_RPL_SGPARSE_H

#include "sim/app/replay/rpl_lines.h"

typedef enum {
    SG_NOP, /* init, finalize, comm_size */
    SG_COMPUTE,
    SG_SLEEP,
    SG_SEND,
    SG_ISEND,
    SG_RECV,
    SG_IRECV,
    SG_WAIT,
    SG_WAITALL,
    SG_BARRIER,
    SG_BCAST,
    SG_REDUCE,
    SG_ALLREDUCE,
    SG_ALLTOALL
} SgType;

typedef struct {
    SgType type;
    guint line;
    guint rank;
    guint peer;     /* send/recv partner; bcast/reduce root */
    int64_t tag;
    double size;    /* elements (message, or comm part of a collective) */
    double flops;   /* compute; comp part of reduce/allreduce */
    double seconds; /* sleep */
    gboolean doubles; /* init named a datatype: elements are 8 bytes */
    gboolean matched; /* wait names SRC DST TAG */
    guint src, dst;   /* wait */
    int arg_col;      /* where the first argument starts (end of line: 0) */
    int root_col;     /* bcast/reduce: where ROOT starts (0: not given) */
} SgAct;

/* TRUE when a line's words look like a SimGrid action (used to tell an
 * imported trace from a pgsim one by its first line). */
gboolean rpl_sg_is_action(const RplLines *l);
/* Parses the current line of l into *a; FALSE with a located *err. */
gboolean rpl_sg_parse(const RplLines *l, SgAct *a, GError **err);

#endif
