/* rpl_replay.c — the replay loop (rpl_replay.h).
 *
 * The reader runs just ahead of the simulation.  A group is read whole
 * (its actions up to the next group line, which stays as lookahead) and
 * then: an `at T` group is issued at T (at once if T is now); an `on X`
 * group is attached to X and issued when X completes.  Reading stops
 * after a group whose cause is still in flight: everything after it in
 * the file was issued after that cause completed when it was recorded.
 * When an awaited action completes and its group has not been read yet,
 * the reader reads on to it, attaching the groups it passes.
 *
 * Flights: one record per action marked `+` or `&`, from when it is
 * read until it completes (`&`: until the action `after` it is issued,
 * which is parked on the flight while the join has not completed);
 * other actions are issued and forgotten.
 *
 * Frames: frame k ends when every action up to its mark (in file order)
 * has completed; in a trace whose frames end at refreshes, when its
 * `swap` wait completes (each swap has its slot in `ends`).  Marks are read in order; each completion time goes to
 * the first mark at or after its action (or to the tail, past the last
 * mark read so far), and frame k ends at the largest time of marks 0..k.
 * Cost: O(1) per action plus one engine event per awaited action.
 */
#include "sim/app/replay/rpl_replay.h"
#include "sim/app/replay/rpl_sgparse.h"
#include "sim/app/replay/rpl_simgrid.h"
#include "sim/app/replay/rpl_target.h"
#include "sim/core/error.h"
#include "sim/core/memlimit.h"
#include <math.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    uint8_t type;
    gboolean handled, frame, joined, has_after;
    uint64_t after; /* has_after: issued once this action has completed */
    uint32_t proc, peer; /* target processors */
    unsigned phase;      /* engine phase id */
    guint slot;          /* a `swap` wait: its frame's slot in ends, +1 */
    guint line;          /* where the trace gives it */
    uint64_t id;
    uint64_t value; /* cost (ps), bytes or a refresh period */
} Act;

typedef struct Group {
    GArray *acts; /* Act */
} Group;

typedef struct {
    uint64_t id;
    Group *group; /* attached `on id` group, or NULL */
    gboolean handled;
    gboolean joined, done; /* `&`; it completed (kept for its `after`) */
    gboolean has_parked;   /* parked: the action `after` it, waiting */
    Act parked;
} Flight;

typedef struct {
    RplTarget *t;
    RplReader *r;
    RplItem look;      /* the next group line */
    gboolean have_look, eof;
    GHashTable *flights; /* id -> Flight * */
    GArray *marks;       /* uint64_t: ids of the frame marks read */
    GArray *ends;        /* SimTime: latest completion per mark */
    SimTime tail;        /* latest completion past the last mark */
    uint64_t actions, late;
    guint waiting; /* groups attached to a flight, not yet issued */
    guint timers;  /* groups scheduled at a time, not yet issued */
    uint64_t sending; /* messages sent, not yet delivered */
    SimTime max_end;  /* latest end of the work given so far */
    SimTime max_wait; /* latest end of a refresh wait (`v`) */
    GQueue syncs;     /* Group *: `sync` groups read, not yet scheduled */
    GError *error;
} Replay;

static void issue_group(Replay *rp, Group *g);
static void progress(Replay *rp);

static void group_free(Group *g)
{
    g_array_free(g->acts, TRUE);
    g_free(g);
}

static void stop(Replay *rp, GError *e)
{
    if (!rp->error)
        rp->error = e;
    else
        g_error_free(e);
    sim_engine_stop(rp->t->eng);
}

/* Reads one line into rp->look (FALSE at the end or on an error). */
static gboolean next_item(Replay *rp)
{
    GError *e = NULL;
    if (rpl_reader_next(rp->r, &rp->look, &e))
        return TRUE;
    rp->eof = TRUE;
    if (e)
        stop(rp, e);
    return FALSE;
}

static Flight *flight_for(Replay *rp, uint64_t id)
{
    return g_hash_table_lookup(rp->flights, &id);
}

static void add_act(Replay *rp, Group *g, const RplItem *it)
{
    RplTarget *t = rp->t;
    gboolean work = it->type == RPL_WORK || it->type == RPL_COMPUTE;
    Act a = {.type = it->type,
             .handled = it->handled,
             .frame = it->frame,
             .joined = it->joined,
             .has_after = it->has_after,
             .after = it->after,
             .proc = rpl_target_map(t, it->proc),
             .peer = it->type == RPL_SEND || it->type == RPL_BUS
                         ? rpl_target_map(t, it->peer)
                         : 0,
             .phase = work ? t->phase[it->phase] : 0,
             .id = it->id,
             .line = it->line,
             .value = work ? rpl_target_price(t, it) : it->value};
    if (it->swap) {
        SimTime none = 0;
        g_array_append_val(rp->ends, none);
        a.slot = rp->ends->len;
    }
    g_array_append_val(g->acts, a);
    if (a.frame) {
        g_array_append_val(rp->marks, a.id);
        g_array_append_val(rp->ends, rp->tail);
        rp->tail = 0;
    }
    if (a.handled || a.joined) {
        Flight *f = g_new0(Flight, 1);
        f->id = a.id;
        f->handled = a.handled;
        f->joined = a.joined;
        g_hash_table_insert(rp->flights, &f->id, f);
    }
}

/* Reads the group whose header is in rp->look; leaves the next header
 * (or the end) in rp->look. */
static Group *read_group(Replay *rp)
{
    Group *g = g_new0(Group, 1);
    g->acts = g_array_new(FALSE, FALSE, sizeof(Act));
    rp->have_look = FALSE;
    while (next_item(rp)) {
        if (rp->look.type == RPL_AT || rp->look.type == RPL_ON ||
            rp->look.type == RPL_SYNC) {
            rp->have_look = TRUE;
            break;
        }
        add_act(rp, g, &rp->look);
    }
    return g;
}

static void timer_fired(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    Replay *rp = ctx;
    rp->timers--;
    issue_group(rp, arg);
    progress(rp);
}

static void schedule_group(Replay *rp, SimTime t, Group *g)
{
    rp->timers++;
    sim_schedule_at(rp->t->eng, t, timer_fired, rp, g);
}

/* A `sync` group goes when everything before it has been issued and
 * done: no group waiting or scheduled, no message in flight; then at
 * the end of the latest work. */
static void try_sync(Replay *rp)
{
    if (g_queue_is_empty(&rp->syncs) || rp->waiting || rp->timers ||
        rp->sending)
        return;
    SimTime now = sim_now(rp->t->eng);
    schedule_group(rp, MAX(rp->max_end, now), g_queue_pop_head(&rp->syncs));
}

/* Reads the group in rp->look and places it.  Returns the flight it was
 * attached to (NULL for an `at` group). */
static Flight *place_group(Replay *rp)
{
    RplItem head = rp->look;
    Group *g = read_group(rp);
    SimEngine *eng = rp->t->eng;
    if (head.type == RPL_SYNC) {
        g_queue_push_tail(&rp->syncs, g);
        return NULL;
    }
    if (head.type == RPL_AT) {
        SimTime now = sim_now(eng);
        if (head.at < now)
            rp->late++;
        if (head.at <= now && rp->waiting == 0)
            issue_group(rp, g);
        else
            schedule_group(rp, MAX(head.at, now), g);
        return NULL;
    }
    Flight *f = flight_for(rp, head.id);
    g_assert(f && !f->group); /* the reader checked `+` and once */
    f->group = g;
    rp->waiting++;
    return f;
}

/* Reads on while no group waits for its cause (in the recording,
 * everything after such a group came after its cause completed). */
static void pump(Replay *rp)
{
    while (!rp->error && rp->have_look && rp->waiting == 0 &&
           g_queue_is_empty(&rp->syncs))
        place_group(rp);
}

static void progress(Replay *rp)
{
    try_sync(rp);
    pump(rp);
    try_sync(rp);
}

/* Reads on until the group of flight f is attached (or the end). */
static void seek(Replay *rp, Flight *f)
{
    while (!rp->error && rp->have_look && !f->group)
        place_group(rp);
}

static void issue(Replay *rp, const Act *a);

/* Flight f completed: its `on` group is issued, then the action parked
 * `after` it; a joined flight with none parked yet stays, done. */
static void completed(Replay *rp, Flight *f)
{
    if (f->handled)
        seek(rp, f);
    Group *g = f->group;
    f->group = NULL;
    gboolean parked = f->has_parked;
    Act a = f->parked;
    if (f->joined && !parked) {
        f->done = TRUE;
    } else {
        g_hash_table_steal(rp->flights, &f->id);
        g_free(f);
    }
    if (g) {
        rp->waiting--;
        issue_group(rp, g);
    }
    if (parked) {
        rp->waiting--;
        issue(rp, &a);
    }
    progress(rp);
}

/* An action `after` J: TRUE when J has completed (its flight goes),
 * else it is parked on J's flight until then. */
static gboolean join_done(Replay *rp, const Act *a)
{
    Flight *j = flight_for(rp, a->after);
    g_assert(j && j->joined && !j->has_parked); /* the reader checked */
    if (!j->done) {
        j->parked = *a;
        j->parked.has_after = FALSE;
        j->has_parked = TRUE;
        rp->waiting++;
        return FALSE;
    }
    g_hash_table_steal(rp->flights, &j->id);
    g_free(j);
    return TRUE;
}

static void work_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)eng;
    completed(ctx, arg);
}

/* Action id completes at t: the frame whose mark is the first at or
 * after id ends no earlier. */
static void note_done(Replay *rp, uint64_t id, SimTime t)
{
    guint lo = 0, hi = rp->marks->len;
    if (hi == 0 || id > g_array_index(rp->marks, uint64_t, hi - 1)) {
        rp->tail = MAX(rp->tail, t);
        return;
    }
    while (lo < hi) { /* first mark >= id */
        guint mid = (lo + hi) / 2;
        if (g_array_index(rp->marks, uint64_t, mid) < id)
            lo = mid + 1;
        else
            hi = mid;
    }
    SimTime *e = &g_array_index(rp->ends, SimTime, lo);
    *e = MAX(*e, t);
}

/* Message or transfer id arrived at t. */
static void arrived(Replay *rp, uint64_t id, SimTime t)
{
    rp->sending--;
    note_done(rp, id, t);
    Flight *f = flight_for(rp, id);
    if (f)
        completed(rp, f);
    else
        progress(rp);
}

static void delivered(NetNet *net, const NetDelivery *d, void *ctx)
{
    (void)net;
    arrived(ctx, (uintptr_t)d->payload, d->arrived);
}

static void transferred(SimEngine *eng, void *ctx, void *arg)
{
    Replay *rp = ctx;
    rp->max_end = MAX(rp->max_end, sim_now(eng)); /* as the recorder */
    arrived(rp, (uintptr_t)arg, sim_now(eng));
}

/* Work or a wait ending at `end` (SIM_TIME_MAX: past the 64-bit clock,
 * saturated) stops the replay with an error at its line, rather than a
 * result that ends at the end of time.  TRUE when it fits. */
static gboolean fits_clock(Replay *rp, const Act *a, SimTime end)
{
    if (end < SIM_TIME_MAX)
        return TRUE;
    stop(rp, g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                         "%s:%u:1: found %s ending past the simulated clock's "
                         "end (%.0f s), expected actions that end within it",
                         rpl_reader_path(rp->r), a->line,
                         a->type == RPL_REFRESH ? "a refresh wait"
                         : a->type == RPL_SEND || a->type == RPL_BUS
                             ? "a message"
                             : "work",
                         sim_time_to_s(SIM_TIME_MAX)));
    return FALSE;
}

/* A message over the network: its contention-free time from now must fit
 * the clock (a send of 2^64 - 1 bytes would otherwise stop the engine
 * with an unlocated overflow). */
static gboolean send_fits(Replay *rp, const Act *a)
{
    NetNet *net = mach_net(rp->t->m);
    SimTime d = net_ideal_time(net, a->proc, a->peer, a->value);
    if (!fits_clock(rp, a, sim_time_add_sat(sim_now(rp->t->eng), d)))
        return FALSE;
    const NetParams *par = net_params(net);
    gboolean packets = net_fidelity(net) == NET_PACKET &&
                       par->packet_bytes > 0 &&
                       (par->switching == NET_SW_CUT_THROUGH ||
                        par->switching == NET_SW_STORE_FORWARD);
    if (!packets)
        return TRUE;
    /* the packet transport holds a message's packets at once (assumption:
     * 64 bytes each, sim/net/packet.c's NetPkt) */
    double n = ceil((double)a->value / par->packet_bytes);
    char *where = g_strdup_printf("%s:%u:1", rpl_reader_path(rp->r), a->line);
    char *what = g_strdup_printf("a message of %.0f packets", n);
    GError *e = NULL;
    gboolean ok = sim_mem_check(n * 64.0, where, what, &e);
    if (!ok)
        stop(rp, e);
    g_free(what);
    g_free(where);
    return ok;
}

/* A `b` transfer: through the target's shared memory if it has one,
 * else the network, as a message. */
static void transfer(Replay *rp, const Act *a)
{
    RplTarget *t = rp->t;
    if (!t->has_shm && !send_fits(rp, a))
        return;
    rp->sending++;
    if (t->has_shm)
        mach_shmem_send(&t->shm, t->eng, a->proc, a->peer, a->value,
                        transferred, rp, (void *)(uintptr_t)a->id);
    else
        net_send(mach_net(t->m), a->proc, a->peer, a->value,
                 (void *)(uintptr_t)a->id, delivered, rp);
}

/* A `v` wait: done at the next refresh; a `swap` ends its frame then. */
static void refresh(Replay *rp, const Act *a, Flight *f)
{
    SimEngine *eng = rp->t->eng;
    SimTime t = sim_refresh_at(sim_now(eng), a->value);
    if (!fits_clock(rp, a, t))
        return;
    rp->max_wait = MAX(rp->max_wait, t);
    if (a->slot)
        g_array_index(rp->ends, SimTime, a->slot - 1) = t;
    note_done(rp, a->id, t);
    if (f)
        sim_wait_refresh(eng, a->proc, a->value, work_done, rp, f);
}

static void issue(Replay *rp, const Act *a)
{
    if (a->has_after && !join_done(rp, a))
        return;
    MachMachine *m = rp->t->m;
    Flight *f = a->handled || a->joined ? flight_for(rp, a->id) : NULL;
    rp->actions++;
    if (a->type == RPL_SEND) {
        if (!send_fits(rp, a))
            return;
        rp->sending++;
        net_send(mach_net(m), a->proc, a->peer, a->value,
                 (void *)(uintptr_t)a->id, delivered, rp);
        return;
    }
    if (a->type == RPL_BUS) {
        transfer(rp, a);
        return;
    }
    if (a->type == RPL_REFRESH) {
        refresh(rp, a, f);
        return;
    }
    MachProc *p = mach_proc_at(m, a->proc);
    SimTime start = MAX(sim_now(rp->t->eng), mach_proc_free_at(p));
    if (!fits_clock(rp, a, sim_time_add_sat(start, a->value)))
        return;
    mach_proc_compute(p, a->value, a->phase, f ? work_done : NULL, rp, f);
    rp->max_end = MAX(rp->max_end, mach_proc_free_at(p));
    note_done(rp, a->id, mach_proc_free_at(p));
}

static void issue_group(Replay *rp, Group *g)
{
    for (guint i = 0; i < g->acts->len; i++)
        issue(rp, &g_array_index(g->acts, Act, i));
    group_free(g);
}

static SimResult *result(Replay *rp, const RplReplayOpts *o)
{
    RplTarget *t = rp->t;
    SimResult *res = sim_result_new("replay", o->machine);
    g_free(res->fidelity);
    res->fidelity = g_strdup(mach_fidelity(t->m));
    res->seed = 1;
    mach_fill_result(t->m, res);
    res->comm_bytes += t->shm.bytes; /* `b` transfers, as `pgsim run` */
    res->comm_messages += t->shm.transfers;
    SimTime prev = 0, end = 0;
    for (guint i = 0; i < rp->ends->len; i++) {
        end = MAX(end, g_array_index(rp->ends, SimTime, i));
        sim_result_add_frame(res, end - prev);
        prev = end;
    }
    /* the end of the last event, work or refresh wait, whichever is
     * later (work and waits with no handler have no event at their end) */
    res->elapsed = MAX(sim_now(t->eng), MAX(rp->max_end, rp->max_wait));
    res->events = sim_engine_events(t->eng);
    res->config_path = g_strdup(o->trace);
    sim_result_set_metric(res, "actions", (double)rp->actions, "");
    if (rp->late)
        sim_result_set_metric(res, "late_timer_groups", (double)rp->late, "");
    return res;
}

/* Runs the replay of an opened, checked trace. */
static gboolean run(Replay *rp, GError **err)
{
    if (next_item(rp)) {
        rp->have_look = TRUE;
        progress(rp);
    }
    GError *e = NULL;
    if (!sim_engine_run(rp->t->eng, SIM_TIME_MAX, &e) && !rp->error)
        rp->error = e;
    else if (e)
        g_error_free(e);
    if (!rp->error && (rp->have_look || g_hash_table_size(rp->flights) ||
                       !g_queue_is_empty(&rp->syncs)))
        rp->error = g_error_new(SIM_ERROR, SIM_ERROR_INTERNAL,
                                "%s: the replay stopped with %u actions "
                                "awaited and the trace not finished",
                                rpl_reader_path(rp->r),
                                g_hash_table_size(rp->flights));
    if (rp->error) {
        g_propagate_error(err, rp->error);
        rp->error = NULL;
        return FALSE;
    }
    return TRUE;
}

/* TRUE when the trace's first line is a SimGrid action. */
static gboolean is_simgrid(const char *path)
{
    RplLines *l = rpl_lines_open(path, NULL);
    gboolean sg = l && rpl_lines_next(l, NULL) > 0 && rpl_sg_is_action(l);
    rpl_lines_free(l);
    return sg;
}

SimResult *rpl_replay(const RplReplayOpts *o, GError **err)
{
    if (is_simgrid(o->trace))
        return rpl_replay_simgrid(o, err);
    RplReader *r = rpl_reader_open(o->trace, err);
    if (!r)
        return NULL;
    RplTarget *t = rpl_target_new(o, rpl_reader_header(r), err);
    if (!t || !rpl_target_check(t, o->trace, err)) {
        rpl_target_free(t);
        rpl_reader_free(r);
        return NULL;
    }
    Replay rp = {.t = t,
                 .r = r,
                 .flights = g_hash_table_new_full(g_int64_hash, g_int64_equal,
                                                  NULL, g_free),
                 .marks = g_array_new(FALSE, FALSE, sizeof(uint64_t)),
                 .ends = g_array_new(FALSE, FALSE, sizeof(SimTime))};
    gint64 t0 = g_get_monotonic_time();
    SimResult *res = run(&rp, err) ? result(&rp, o) : NULL;
    if (res)
        res->wall_s = (double)(g_get_monotonic_time() - t0) * 1e-6;
    g_hash_table_destroy(rp.flights);
    g_array_free(rp.marks, TRUE);
    g_array_free(rp.ends, TRUE);
    rpl_target_free(t);
    rpl_reader_free(r);
    return res;
}
