/* engine.c — the event loop.
 *
 * Events (time, seq, handler, ctx, arg) live in the queue itself
 * (evq.h).  Hot path: the event being run is copied out but not popped
 * before its handler runs; the first event the handler schedules takes
 * its place in one replace-top.  If the handler schedules nothing, the
 * top is popped afterwards.  Order is unchanged: the top is the least
 * event, and a new event is never less than the one being run.
 */
#include "sim/core/engine.h"
#include "sim/core/memlimit.h"
#include "sim/core/evq.h"

typedef struct {
    char *name;
    SimRng *rng;
} SimEntity;

struct SimEngine {
    SimEvq *q;
    uint64_t cap; /* pending events allowed before the next memory check */
    SimTime now;
    uint64_t seq;
    uint64_t events;
    uint64_t seed;
    gboolean hole; /* heap root is the event being run */
    gboolean stopped;
    gboolean dry; /* sim_engine_set_dry_run() */
    gboolean cut; /* stopped at the horizon with events pending */
    SimTime horizon; /* sim_engine_set_horizon(); SIM_TIME_MAX: none */
    GError *error;
    GArray *entities; /* SimEntity */
    GPtrArray *phases;
    GHashTable *phase_ids; /* name -> id + 1 */
    uint64_t progress_every;
    SimProgressFn progress_fn;
    void *progress_ctx;
    SimTrace *trace;
    SimRecorder *recorder;
    SimNodeNameFn namer;
    void *namer_ctx;
};

SimEngine *sim_engine_new(uint64_t seed)
{
    SimEngine *e = g_new0(SimEngine, 1);
    e->q = sim_evq_new();
    e->seed = seed;
    e->horizon = SIM_TIME_MAX;
    e->entities = g_array_new(FALSE, TRUE, sizeof(SimEntity));
    e->phases = g_ptr_array_new_with_free_func(g_free);
    e->phase_ids = g_hash_table_new(g_str_hash, g_str_equal);
    sim_engine_phase(e, "compute"); /* phase 0: the default */
    return e;
}

void sim_engine_free(SimEngine *e)
{
    if (!e)
        return;
    sim_evq_free(e->q);
    for (guint i = 0; i < e->entities->len; i++) {
        SimEntity *en = &g_array_index(e->entities, SimEntity, i);
        g_free(en->name);
        g_free(en->rng);
    }
    g_array_free(e->entities, TRUE);
    g_hash_table_destroy(e->phase_ids);
    g_ptr_array_free(e->phases, TRUE);
    if (e->error)
        g_error_free(e->error);
    g_free(e);
}

SimTime sim_now(const SimEngine *e)
{
    return e->now;
}
uint64_t sim_engine_seed(const SimEngine *e)
{
    return e->seed;
}
uint64_t sim_engine_events(const SimEngine *e)
{
    return e->events;
}

size_t sim_engine_pending(const SimEngine *e)
{
    return sim_evq_len(e->q) - (e->hole ? 1 : 0);
}

/* Bytes per pending event: its record in a queue bucket, with the
 * bucket arrays' doubling slack (sim/core/evq.c). */
#define EVENT_BYTES (2 * sizeof(SimEvKey))

/* Fails the run: the queue cannot double to `cap` pending events. */
static gboolean queue_full(SimEngine *e, uint64_t cap)
{
    char *need = g_format_size_full(cap * EVENT_BYTES, G_FORMAT_SIZE_IEC_UNITS);
    char *have = g_format_size_full(sim_mem_limit(), G_FORMAT_SIZE_IEC_UNITS);
    sim_engine_fail(e, g_error_new(SIM_ERROR, SIM_ERROR_INPUT,
                                   "simulation: found %" G_GUINT64_FORMAT
                                   " pending events needing about %s, "
                                   "expected at most %s (--mem-limit; "
                                   "docs/config.md, Limits)",
                                   cap, need, have));
    g_free(need);
    g_free(have);
    return FALSE;
}

/* Pending events may double past e->cap only within the memory limit,
 * so an overflowing model is a run error, not an abort. */
static gboolean room_for_one(SimEngine *e)
{
    if (G_LIKELY(sim_evq_len(e->q) < e->cap))
        return TRUE;
    uint64_t cap = e->cap ? 2 * e->cap : 1024;
    if ((double)cap * EVENT_BYTES > (double)sim_mem_limit())
        return queue_full(e, cap);
    e->cap = cap;
    return TRUE;
}

gboolean sim_schedule_at(SimEngine *e, SimTime t, SimHandler fn, void *ctx,
                         void *arg)
{
    g_assert(t >= e->now);
    if (G_UNLIKELY(!room_for_one(e)))
        return FALSE; /* the run stops with the error */
    SimEvKey k = {t, e->seq++, fn, ctx, arg};
    if (e->hole) {
        e->hole = FALSE;
        sim_evq_replace_top(e->q, k);
    } else {
        sim_evq_push(e->q, k);
    }
    return TRUE;
}

gboolean sim_schedule_in(SimEngine *e, SimTime delay, SimHandler fn, void *ctx,
                         void *arg)
{
    SimTime t;
    if (G_UNLIKELY(!sim_time_add(e->now, delay, &t))) {
        sim_engine_fail(
            e, g_error_new(SIM_ERROR, SIM_ERROR_OVERFLOW,
                           "simulated time overflow: %" G_GUINT64_FORMAT
                           " ps + %" G_GUINT64_FORMAT
                           " ps exceeds the 64-bit clock",
                           e->now, delay));
        return FALSE;
    }
    return sim_schedule_at(e, t, fn, ctx, arg);
}

void sim_engine_stop(SimEngine *e)
{
    e->stopped = TRUE;
}

void sim_engine_fail(SimEngine *e, GError *err)
{
    if (e->error)
        g_error_free(err); /* keep the first error */
    else
        e->error = err;
    e->stopped = TRUE;
}

void sim_engine_set_dry_run(SimEngine *e, gboolean dry)
{
    e->dry = dry;
}

gboolean sim_engine_run(SimEngine *e, SimTime until, GError **err)
{
    if (e->dry) { /* an error from scheduling (event memory) comes first */
        if (e->error)
            g_propagate_error(err, g_steal_pointer(&e->error));
        else
            g_set_error(err, SIM_ERROR, SIM_ERROR_DRY_RUN,
                        "stopped before the first simulated event (dry run)");
        return FALSE;
    }
    uint64_t next_progress =
        e->progress_every ? e->events + e->progress_every : UINT64_MAX;
    SimTime asked = until;
    until = MIN(until, e->horizon);
    e->stopped = FALSE;
    while (!e->stopped && sim_evq_len(e->q) > 0) {
        SimEvKey ev = *sim_evq_top(e->q);
        if (ev.time > until)
            break;
        e->now = ev.time;
        e->hole = TRUE;
        ev.fn(e, ev.ctx, ev.arg);
        if (e->hole) {
            e->hole = FALSE;
            sim_evq_pop(e->q);
        }
        if (G_UNLIKELY(++e->events >= next_progress)) {
            e->progress_fn(e, e->progress_ctx);
            next_progress = e->events + e->progress_every;
        }
    }
    /* Time passes to `until` when the caller asked for it, or when the
     * horizon cut pending work short; a run that merely ran out of events
     * under the horizon ends at its last event. */
    gboolean pending = sim_evq_len(e->q) > 0;
    gboolean cut = !e->stopped && pending && sim_evq_top(e->q)->time > until &&
                   until == e->horizon && until != SIM_TIME_MAX;
    if (until != SIM_TIME_MAX && !e->stopped && until > e->now &&
        (cut || (asked != SIM_TIME_MAX &&
                 (!pending || sim_evq_top(e->q)->time > until))))
        e->now = until;
    e->cut = e->cut || cut;
    if (e->error) {
        g_propagate_error(err, e->error);
        e->error = NULL;
        return FALSE;
    }
    return TRUE;
}

void sim_engine_set_horizon(SimEngine *e, SimTime t)
{
    e->horizon = t;
}

SimTime sim_engine_horizon(const SimEngine *e)
{
    return e->horizon;
}

gboolean sim_engine_cut(const SimEngine *e)
{
    return e->cut;
}

uint32_t sim_entity_add(SimEngine *e, const char *name)
{
    SimEntity en = {g_strdup(name), NULL};
    g_array_append_val(e->entities, en);
    return e->entities->len - 1;
}

const char *sim_entity_name(const SimEngine *e, uint32_t id)
{
    g_assert(id < e->entities->len);
    return g_array_index(e->entities, SimEntity, id).name;
}

SimRng *sim_entity_rng(SimEngine *e, uint32_t id)
{
    g_assert(id < e->entities->len);
    SimEntity *en = &g_array_index(e->entities, SimEntity, id);
    if (!en->rng) {
        en->rng = g_new(SimRng, 1);
        sim_rng_init(en->rng, e->seed, id);
    }
    return en->rng;
}

unsigned sim_engine_phase(SimEngine *e, const char *name)
{
    gpointer v = g_hash_table_lookup(e->phase_ids, name);
    if (v)
        return GPOINTER_TO_UINT(v) - 1;
    char *copy = g_strdup(name);
    g_ptr_array_add(e->phases, copy);
    g_hash_table_insert(e->phase_ids, copy, GUINT_TO_POINTER(e->phases->len));
    return e->phases->len - 1;
}

const char *sim_engine_phase_name(const SimEngine *e, unsigned id)
{
    g_assert(id < e->phases->len);
    return g_ptr_array_index(e->phases, id);
}

unsigned sim_engine_phase_count(const SimEngine *e)
{
    return e->phases->len;
}

void sim_engine_set_progress(SimEngine *e, uint64_t every, SimProgressFn fn,
                             void *ctx)
{
    e->progress_every = fn ? every : 0;
    e->progress_fn = fn;
    e->progress_ctx = ctx;
}

void sim_engine_set_trace(SimEngine *e, SimTrace *tr)
{
    e->trace = tr;
}
SimTrace *sim_engine_trace(const SimEngine *e)
{
    return e->trace;
}

void sim_engine_set_recorder(SimEngine *e, SimRecorder *r)
{
    e->recorder = r;
}
SimRecorder *sim_engine_recorder(const SimEngine *e)
{
    return e->recorder;
}

void sim_engine_set_node_namer(SimEngine *e, SimNodeNameFn fn, void *ctx)
{
    e->namer = fn;
    e->namer_ctx = fn ? ctx : NULL;
}

const char *sim_engine_node_name(const SimEngine *e, uint32_t node)
{
    return e->namer ? e->namer(e->namer_ctx, node) : NULL;
}
