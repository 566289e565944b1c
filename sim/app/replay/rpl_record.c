/* rpl_record.c — the trace recorder (rpl_record.h).
 *
 * Actions and groups are appended to two arrays in issue order; ids are
 * indices into the action array, which is also the order the writer puts
 * them in, so `on ID` always follows action ID.  Cost: O(1) per hook
 * call; writing is O(actions + groups + frames).
 */
#include "sim/app/replay/rpl_record.h"
#include "sim/app/replay/rpl_format.h"
#include "sim/core/error.h"
#include "sim/machine/machine.h"
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#define NO_ACTION G_MAXUINT64

typedef struct {
    uint64_t value; /* ps of work, bytes or a period; RPL_COMPUTE: first in
                       ops */
    SimTime done;   /* completion time (SIM_TIME_MAX: never completed) */
    uint64_t after; /* a join: it waits also for this action (NO_ACTION) */
    uint32_t proc, peer;
    uint16_t phase;
    uint8_t type;  /* RPL_WORK, RPL_COMPUTE, RPL_SEND, RPL_BUS, RPL_REFRESH */
    uint8_t n_ops; /* RPL_COMPUTE: its counts, ops[value ..] */
    uint8_t handled : 1, frame : 1, swap : 1, joined : 1;
} RecAct;

typedef struct {
    uint64_t first; /* its first action */
    uint64_t cause; /* NO_ACTION: an `at` or `sync` group */
    SimTime at;
    gboolean sync; /* issued when all earlier work had just completed */
} RecGroup;

struct RplRecorder {
    SimRecorder hook;
    GArray *acts;      /* RecAct */
    GArray *groups;    /* RecGroup */
    GArray *ops;       /* SimOp of RPL_COMPUTE actions, names interned */
    uint64_t cur;      /* the action whose handler runs, or NO_ACTION */
    uint64_t after;    /* the next action's join (sim_record_after) */
    SimTime max_end;   /* latest end of the work given so far */
    uint64_t inflight; /* messages and transfers not yet delivered */
};

/* Opens a group for an action issued now if the last one does not fit. */
static void group_for(RplRecorder *r, SimTime now)
{
    RecGroup *last =
        r->groups->len ? &g_array_index(r->groups, RecGroup, r->groups->len - 1)
                       : NULL;
    if (last && last->cause == r->cur &&
        (r->cur != NO_ACTION || last->at == now))
        return;
    /* A workload's timer that fires just as the last of all earlier work
     * ends (and no message is in flight) waited for that work. */
    gboolean sync =
        r->cur == NO_ACTION && now > 0 && r->inflight == 0 && r->max_end == now;
    RecGroup g = {r->acts->len, r->cur, now, sync};
    g_array_append_val(r->groups, g);
    if (r->cur != NO_ACTION)
        g_array_index(r->acts, RecAct, r->cur).handled = 1;
}

static uint64_t add(RplRecorder *r, SimTime now, RecAct a)
{
    group_for(r, now);
    a.done = SIM_TIME_MAX;
    a.after = r->after;
    r->after = NO_ACTION;
    g_array_append_val(r->acts, a);
    return r->acts->len - 1;
}

/* Appends the non-zero counts to r->ops (the last one if all are zero:
 * a `c` line or term names at least one); returns how many. */
static guint keep(RplRecorder *r, const SimOp *ops, unsigned n_ops)
{
    guint kept = 0;
    for (unsigned i = 0; i < n_ops; i++) {
        if (ops[i].count == 0 && (kept > 0 || i + 1 < n_ops))
            continue;
        SimOp o = {g_intern_string(ops[i].name), ops[i].count};
        g_array_append_val(r->ops, o);
        kept++;
    }
    return kept;
}

/* Markers in r->ops that open a `|` term: {TERM_AT, node} then its
 * counts; {TERM_BUS, node} then {TERM_BUS, bytes}. */
static const char TERM_AT[] = "|@", TERM_BUS[] = "|b";

static guint keep_term(RplRecorder *r, const SimOpTerm *t)
{
    SimOp mark = {t->bus ? TERM_BUS : TERM_AT, t->node};
    g_array_append_val(r->ops, mark);
    if (!t->bus)
        return 1 + keep(r, t->ops, t->n_ops);
    SimOp bytes = {TERM_BUS, t->bytes};
    g_array_append_val(r->ops, bytes);
    return 2;
}

/* The action's RPL_COMPUTE fields: its counts, then its terms. */
static RecAct keep_ops(RplRecorder *r, const SimOp *ops, unsigned n_ops,
                       const SimOpTerm *terms, unsigned n_terms)
{
    g_assert(n_ops <= RPL_MAX_OPS && n_terms <= RPL_MAX_TERMS);
    RecAct a = {.value = r->ops->len, .type = RPL_COMPUTE};
    guint n = keep(r, ops, n_ops);
    for (unsigned i = 0; i < n_terms; i++) {
        g_assert(terms[i].bus || terms[i].n_ops <= RPL_TERM_OPS);
        n += keep_term(r, &terms[i]);
    }
    g_assert(n <= G_MAXUINT8);
    a.n_ops = (uint8_t)n;
    return a;
}

static uint64_t on_compute(SimRecorder *h, SimTime now, uint32_t node,
                           unsigned phase, SimTime cost, SimTime end,
                           const SimWork *w, gboolean handled)
{
    const SimOp *ops = w->ops;
    unsigned n_ops = w->n_ops;
    const SimOpTerm *terms = w->terms;
    unsigned n_terms = w->n_terms;
    (void)handled;
    g_assert(phase <= G_MAXUINT16);
    RplRecorder *r = h->state;
    RecAct a = n_ops ? keep_ops(r, ops, n_ops, terms, n_terms)
                     : (RecAct){.value = cost, .type = RPL_WORK};
    a.proc = node;
    a.phase = (uint16_t)phase;
    uint64_t id = add(r, now, a);
    r->max_end = MAX(r->max_end, end);
    return id;
}

static uint64_t on_send(SimRecorder *h, SimTime now, uint32_t src, uint32_t dst,
                        uint64_t bytes, gboolean handled)
{
    (void)handled;
    RplRecorder *r = h->state;
    r->inflight++;
    return add(
        r, now,
        (RecAct){.value = bytes, .proc = src, .peer = dst, .type = RPL_SEND});
}

/* A shared-memory transfer: a message whose end counts as work's. */
static uint64_t on_transfer(SimRecorder *h, SimTime now, uint32_t src,
                            uint32_t dst, uint64_t bytes, SimTime end)
{
    RplRecorder *r = h->state;
    uint64_t id = add(
        r, now,
        (RecAct){.value = bytes, .proc = src, .peer = dst, .type = RPL_BUS});
    r->inflight++;
    r->max_end = MAX(r->max_end, end);
    return id;
}

static uint64_t on_refresh(SimRecorder *h, SimTime now, uint32_t node,
                           SimTime period)
{
    return add(h->state, now,
               (RecAct){.value = period, .proc = node, .type = RPL_REFRESH});
}

static void on_begin(SimRecorder *h, uint64_t id, SimTime t)
{
    RplRecorder *r = h->state;
    RecAct *a = &g_array_index(r->acts, RecAct, id);
    a->done = t;
    if (a->type == RPL_SEND || a->type == RPL_BUS)
        r->inflight--;
    r->cur = id;
}

static void on_end(SimRecorder *h, uint64_t id)
{
    (void)id;
    RplRecorder *r = h->state;
    r->cur = NO_ACTION;
    r->after = NO_ACTION;
}

static uint64_t on_cause(SimRecorder *h)
{
    return ((RplRecorder *)h->state)->cur;
}

/* The next action waits also for action id (an `after ID` word; id is
 * marked `&`). */
static void on_after(SimRecorder *h, uint64_t id)
{
    RplRecorder *r = h->state;
    g_assert(id < r->acts->len);
    RecAct *a = &g_array_index(r->acts, RecAct, id);
    g_assert(!a->joined); /* one join names each action */
    a->joined = 1;
    r->after = id;
}

static const SimRecorderOps rec_ops = {on_compute, on_send,  on_transfer,
                                       on_refresh, on_begin, on_end,
                                       on_cause,   on_after};

RplRecorder *rpl_recorder_new(void)
{
    RplRecorder *r = g_new0(RplRecorder, 1);
    r->hook = (SimRecorder){&rec_ops, r};
    r->acts = g_array_new(FALSE, FALSE, sizeof(RecAct));
    r->groups = g_array_new(FALSE, FALSE, sizeof(RecGroup));
    r->ops = g_array_new(FALSE, FALSE, sizeof(SimOp));
    r->cur = NO_ACTION;
    r->after = NO_ACTION;
    return r;
}

void rpl_recorder_free(RplRecorder *r)
{
    if (!r)
        return;
    g_array_free(r->acts, TRUE);
    g_array_free(r->groups, TRUE);
    g_array_free(r->ops, TRUE);
    g_free(r);
}

SimRecorder *rpl_recorder_hook(RplRecorder *r)
{
    return &r->hook;
}

uint64_t rpl_recorder_actions(const RplRecorder *r)
{
    return r->acts->len;
}

/* The recording machine's kinds, clocks and resolved fidelity: the
 * machine the runner built for the run (none: no header lines). */
static gboolean machine_header(const CfgRun *run, RplHeader *h, GError **err)
{
    (void)err;
    const MachMachine *m = run->machine_built;
    if (!m)
        return TRUE;
    for (guint i = 0; i < mach_kind_count(m); i++) {
        const MachKindInfo *k = mach_kind_at(m, i);
        RplKind rk = {g_strdup(k->name), k->first, k->count, k->clock_hz, 0, 0};
        g_array_append_val(h->kinds, rk);
    }
    h->procs = mach_proc_total(m);
    h->fidelity = g_strndup(mach_fidelity(m), strcspn(mach_fidelity(m), " "));
    return TRUE;
}

static guint place_ends(RplRecorder *r, const SimResult *res);

/* Frames that end at a display refresh (frames overlap: pipelined):
 * frame k ends at T on the last refresh wait (`v`) that completes at T,
 * marked `swap` (a replay ends the frame when that wait completes).
 * Returns how many frames found none. */
static guint place_swaps(RplRecorder *r, const SimResult *res)
{
    GHashTable *last = g_hash_table_new(g_int64_hash, g_int64_equal);
    for (guint i = 0; i < r->acts->len; i++) {
        RecAct *a = &g_array_index(r->acts, RecAct, i);
        a->frame = 0;
        if (a->type == RPL_REFRESH && a->done != SIM_TIME_MAX)
            g_hash_table_insert(last, &a->done, a);
    }
    guint missed = 0;
    SimTime end = 0;
    const RecAct *prev = NULL; /* a replay takes swaps in file order */
    for (guint k = 0; k < res->frame_times->len; k++) {
        end += g_array_index(res->frame_times, SimTime, k);
        RecAct *a = g_hash_table_lookup(last, &end);
        if (a && a > prev) {
            a->swap = 1;
            prev = a;
        } else
            missed++;
    }
    g_hash_table_destroy(last);
    return missed;
}

/* Marks the action ending each frame: frame k ends at the sum of the
 * first k+1 frame times, T, on the last action that completes at T and
 * after every action before it (a replay ends the frame when all actions
 * up to the mark are done); if that misses frames, place_swaps().
 * Returns how many frames found none. */
static guint place_frames(RplRecorder *r, const SimResult *res)
{
    guint missed = place_ends(r, res);
    if (missed == 0)
        return 0;
    guint swaps = place_swaps(r, res);
    if (swaps < missed)
        return swaps;
    for (guint i = 0; i < r->acts->len; i++)
        g_array_index(r->acts, RecAct, i).swap = 0;
    return place_ends(r, res);
}

/* The mark moves past the actions after a that were done by `end` too
 * (a transfer issued with the frame's last work), so that a replay
 * waits for them as well. */
static RecAct *mark_past(RplRecorder *r, RecAct *a, SimTime end)
{
    RecAct *stop = &g_array_index(r->acts, RecAct, r->acts->len);
    while (a + 1 < stop && a[1].done <= end)
        a++;
    return a;
}

/* The rule of place_frames(). */
static guint place_ends(RplRecorder *r, const SimResult *res)
{
    GHashTable *last = g_hash_table_new(g_int64_hash, g_int64_equal);
    SimTime upto = 0; /* latest completion of actions 0 .. i */
    for (guint i = 0; i < r->acts->len; i++) {
        RecAct *a = &g_array_index(r->acts, RecAct, i);
        a->frame = 0;
        upto = a->done == SIM_TIME_MAX ? SIM_TIME_MAX : MAX(upto, a->done);
        if (a->done != SIM_TIME_MAX && a->done == upto)
            g_hash_table_insert(last, &a->done, a);
    }
    guint missed = 0;
    SimTime end = 0;
    for (guint k = 0; k < res->frame_times->len; k++) {
        end += g_array_index(res->frame_times, SimTime, k);
        RecAct *a = g_hash_table_lookup(last, &end);
        if (a)
            mark_past(r, a, end)->frame = 1;
        else
            missed++;
    }
    g_hash_table_destroy(last);
    return missed;
}

/* The `|` term whose marker is o[i]; returns the index after it. */
static guint act_term(RplTerm *t, const SimOp *o, guint i, guint n)
{
    *t = (RplTerm){.proc = (uint32_t)o[i].count, .bus = o[i].name == TERM_BUS};
    if (t->bus) {
        t->bytes = o[i + 1].count;
        return i + 2;
    }
    for (i++; i < n && o[i].name != TERM_AT && o[i].name != TERM_BUS; i++) {
        t->op[t->n_ops] = o[i].name;
        t->count[t->n_ops++] = o[i].count;
    }
    return i;
}

static RplItem act_item(const RplRecorder *r, const RecAct *a, uint64_t id)
{
    RplItem it = {.type = a->type,
                  .id = id,
                  .proc = a->proc,
                  .peer = a->peer,
                  .phase = a->phase,
                  .value = a->value,
                  .handled = a->handled,
                  .frame = a->frame,
                  .swap = a->swap,
                  .joined = a->joined,
                  .has_after = a->after != NO_ACTION,
                  .after = a->after};
    if (a->type != RPL_COMPUTE)
        return it;
    const SimOp *o = &g_array_index(r->ops, SimOp, a->value);
    guint i = 0;
    for (; i < a->n_ops && o[i].name != TERM_AT && o[i].name != TERM_BUS; i++) {
        it.op[i] = o[i].name;
        it.count[i] = o[i].count;
    }
    it.n_ops = i;
    while (i < a->n_ops)
        i = act_term(&it.term[it.n_terms++], o, i, a->n_ops);
    return it;
}

static void write_body(RplRecorder *r, RplWriter *w)
{
    for (guint g = 0; g < r->groups->len; g++) {
        const RecGroup *gr = &g_array_index(r->groups, RecGroup, g);
        uint64_t stop = g + 1 < r->groups->len
                            ? g_array_index(r->groups, RecGroup, g + 1).first
                            : r->acts->len;
        RplItem it = {.type = gr->cause != NO_ACTION ? RPL_ON
                              : gr->sync             ? RPL_SYNC
                                                     : RPL_AT,
                      .id = gr->cause,
                      .at = gr->at};
        rpl_write_item(w, &it);
        for (uint64_t i = gr->first; i < stop; i++) {
            it = act_item(r, &g_array_index(r->acts, RecAct, i), i);
            rpl_write_item(w, &it);
        }
    }
}

/* The header: machine, kinds, procs (at least every id used), phases. */
static gboolean fill_header(RplRecorder *r, const CfgRun *run,
                            const SimResult *res, RplHeader *h, GError **err)
{
    h->phases = g_ptr_array_new_with_free_func(g_free);
    h->kinds = g_array_new(FALSE, FALSE, sizeof(RplKind));
    h->machine = g_strdup(res->machine);
    if (!machine_header(run, h, err))
        return FALSE;
    for (guint i = 0; i < res->phases->len; i++)
        g_ptr_array_add(h->phases, g_strdup(res->phases->pdata[i]));
    for (guint i = 0; i < r->acts->len; i++) {
        const RecAct *a = &g_array_index(r->acts, RecAct, i);
        h->procs = MAX(h->procs, MAX(a->proc, a->peer) + 1);
        if ((a->type == RPL_WORK || a->type == RPL_COMPUTE) &&
            a->phase >= h->phases->len) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                        "recording: phase %u of action %u is not among the "
                        "result's %u phases",
                        a->phase, i, h->phases->len);
            return FALSE;
        }
    }
    return TRUE;
}

gboolean rpl_recorder_write(RplRecorder *r, const char *path, const CfgRun *run,
                            const SimResult *res, guint *unplaced, GError **err)
{
    RplHeader h = {0};
    if (!fill_header(r, run, res, &h, err)) {
        rpl_header_clear(&h);
        return FALSE;
    }
    guint missed = place_frames(r, res);
    if (unplaced)
        *unplaced = missed;
    RplWriter *w = rpl_writer_open(path, err);
    if (!w) {
        rpl_header_clear(&h);
        return FALSE;
    }
    rpl_write_header(w, &h);
    rpl_header_clear(&h);
    write_body(r, w);
    return rpl_writer_close(w, err);
}

gboolean rpl_record_finish(RplRecorder *r, const char *path, const CfgRun *run,
                           const SimResult *res, gboolean quiet, GError **err)
{
    guint missed = 0;
    if (!rpl_recorder_write(r, path, run, res, &missed, err))
        return FALSE;
    if (!quiet)
        fprintf(stderr, "pgsim run: recorded %" PRIu64 " actions in %s\n",
                rpl_recorder_actions(r), path);
    if (missed)
        fprintf(stderr,
                "pgsim run: %u of %u frames end when no recorded action "
                "completes; a replay reports no frame times for them "
                "(docs/traces.md)\n",
                missed, res->frame_times->len);
    return TRUE;
}
