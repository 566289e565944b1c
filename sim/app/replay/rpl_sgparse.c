/* rpl_sgparse.c — SimGrid action lines (rpl_sgparse.h).  Cost: O(words)
 * a line. */
#include "sim/app/replay/rpl_sgparse.h"
#include <math.h>
#include <string.h>

typedef struct {
    const char *name;
    SgType type;
    int min, max; /* arguments after the action word (datatype excluded) */
} SgSpec;

static const SgSpec specs[] = {
    {"init", SG_NOP, 0, 1},          {"finalize", SG_NOP, 0, 0},
    {"comm_size", SG_NOP, 1, 1},     {"compute", SG_COMPUTE, 1, 1},
    {"sleep", SG_SLEEP, 1, 1},       {"send", SG_SEND, 2, 4},
    {"isend", SG_ISEND, 2, 4},       {"recv", SG_RECV, 2, 4},
    {"irecv", SG_IRECV, 2, 4},       {"wait", SG_WAIT, 0, 3},
    {"waitall", SG_WAITALL, 0, 0},   {"barrier", SG_BARRIER, 0, 0},
    {"bcast", SG_BCAST, 1, 3},       {"reduce", SG_REDUCE, 2, 4},
    {"allreduce", SG_ALLREDUCE, 2, 3}, {"allReduce", SG_ALLREDUCE, 2, 3},
    {"alltoall", SG_ALLTOALL, 2, 4}, {"allToAll", SG_ALLTOALL, 2, 4},
};

static const SgSpec *spec(const char *w)
{
    for (guint i = 0; i < G_N_ELEMENTS(specs); i++)
        if (!strcmp(specs[i].name, w))
            return &specs[i];
    return NULL;
}

static gboolean rank_word(const RplLines *l, int i, guint *out, GError **err)
{
    const char *w = rpl_lines_word(l, i);
    guint64 v;
    if (*w == 'p')
        w++;
    if (g_ascii_string_to_unsigned(w, 10, 0, G_MAXUINT32 - 1, &v, NULL)) {
        *out = (guint)v;
        return TRUE;
    }
    g_propagate_error(err, rpl_lines_error(l, i, "a rank (3 or p3)"));
    return FALSE;
}

gboolean rpl_sg_is_action(const RplLines *l)
{
    guint r;
    return rpl_lines_count(l) >= 2 && rank_word(l, 0, &r, NULL) &&
           spec(rpl_lines_word(l, 1));
}

static gboolean num(const RplLines *l, int i, double *out, GError **err)
{
    const char *w = rpl_lines_word(l, i);
    char *end;
    double v = g_ascii_strtod(w, &end);
    if (*w && !*end && isfinite(v) && v >= 0 && v < 1e300) {
        *out = v;
        return TRUE;
    }
    g_propagate_error(err, rpl_lines_error(l, i, "a non-negative number"));
    return FALSE;
}

static gboolean int_arg(const RplLines *l, int i, int64_t *out, GError **err)
{
    gint64 v;
    if (g_ascii_string_to_signed(rpl_lines_word(l, i), 10, -G_MAXINT32,
                                 G_MAXINT32, &v, NULL)) {
        *out = v;
        return TRUE;
    }
    g_propagate_error(err, rpl_lines_error(l, i, "an integer tag"));
    return FALSE;
}

/* send/recv: PEER SIZE, PEER TAG SIZE, or PEER TAG SIZE DATATYPE. */
static gboolean p2p(const RplLines *l, int n, SgAct *a, GError **err)
{
    if (!rank_word(l, 2, &a->peer, err))
        return FALSE;
    if (n == 2)
        return num(l, 3, &a->size, err);
    return int_arg(l, 3, &a->tag, err) && num(l, 4, &a->size, err);
}

static gboolean args(const RplLines *l, int n, SgAct *a, GError **err)
{
    guint root = 0;
    switch (a->type) {
    case SG_COMPUTE:
        return num(l, 2, &a->flops, err);
    case SG_SLEEP:
        return num(l, 2, &a->seconds, err);
    case SG_SEND: case SG_ISEND: case SG_RECV: case SG_IRECV:
        return p2p(l, n, a, err);
    case SG_WAIT:
        a->matched = n == 3;
        return n == 0 || (n == 3 && rank_word(l, 2, &a->src, err) &&
                          rank_word(l, 3, &a->dst, err) &&
                          int_arg(l, 4, &a->tag, err)) ||
               (n != 3 && (g_propagate_error(err, rpl_lines_error(
                               l, 2 + n, "no arguments or SRC DST TAG")),
                           FALSE));
    case SG_BCAST:
        a->root_col = n < 2 ? 0 : rpl_lines_col(l, 3);
        return num(l, 2, &a->size, err) &&
               (n < 2 || rank_word(l, 3, &root, err)) && (a->peer = root, 1);
    case SG_REDUCE:
        a->root_col = n < 3 ? 0 : rpl_lines_col(l, 4);
        return num(l, 2, &a->size, err) && num(l, 3, &a->flops, err) &&
               (n < 3 || rank_word(l, 4, &root, err)) && (a->peer = root, 1);
    case SG_ALLREDUCE:
        return num(l, 2, &a->size, err) && num(l, 3, &a->flops, err);
    case SG_ALLTOALL:
        return num(l, 2, &a->size, err) && num(l, 3, &a->flops, err);
    case SG_NOP:
        a->doubles = !strcmp(rpl_lines_word(l, 1), "init") && n == 1;
        return TRUE;
    default:
        return TRUE;
    }
}

gboolean rpl_sg_parse(const RplLines *l, SgAct *a, GError **err)
{
    memset(a, 0, sizeof *a);
    a->line = rpl_lines_number(l);
    if (!rank_word(l, 0, &a->rank, err))
        return FALSE;
    const SgSpec *s = spec(rpl_lines_word(l, 1));
    if (!s) {
        g_propagate_error(err, rpl_lines_error(
                                   l, 1,
                                   "a SimGrid action (compute, send, recv, "
                                   "isend, irecv, wait, waitall, barrier, "
                                   "bcast, reduce, allreduce, alltoall, "
                                   "sleep, init, finalize)"));
        return FALSE;
    }
    a->type = s->type;
    int n = rpl_lines_count(l) - 2;
    a->arg_col = n > 0 ? rpl_lines_col(l, 2) : 0;
    if (n < s->min || n > s->max) {
        char *what = g_strdup_printf("%d to %d arguments after '%s'", s->min,
                                     s->max, s->name);
        g_propagate_error(err, rpl_lines_error(l, n < s->min ? 2 + n : 2 + s->max,
                                               what));
        g_free(what);
        return FALSE;
    }
    return args(l, n, a, err);
}
