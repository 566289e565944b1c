/* record.c — the completion trampoline of recorded work, waits for a
 * display refresh, and joins (record.h).
 *
 * One small record per recorded completion, freed when it runs; nothing
 * is allocated when no recorder is attached.
 */
#include "sim/core/record.h"

typedef struct {
    SimRecorder *r;
    uint64_t id;
    SimHandler done;
    void *ctx, *arg;
} RecDone;

static void rec_done(SimEngine *eng, void *ctx, void *arg)
{
    (void)arg;
    RecDone d = *(RecDone *)ctx;
    g_free(ctx);
    d.r->ops->begin(d.r, d.id, sim_now(eng));
    if (d.done)
        d.done(eng, d.ctx, d.arg);
    d.r->ops->end(d.r, d.id);
}

gboolean sim_record_schedule_done(SimEngine *eng, SimRecorder *r, uint64_t id,
                                  SimTime t, SimHandler done, void *ctx,
                                  void *arg)
{
    RecDone *d = g_new(RecDone, 1);
    *d = (RecDone){r, id, done, ctx, arg};
    if (sim_schedule_at(eng, t, rec_done, d, NULL))
        return TRUE;
    g_free(d);
    return FALSE;
}

SimTime sim_refresh_at(SimTime t, SimTime period)
{
    g_assert(period > 0);
    SimTime q = t / period + (t % period != 0);
    return sim_time_mul_sat(period, q);
}

gboolean sim_wait_refresh(SimEngine *eng, uint32_t node, SimTime period,
                          SimHandler done, void *ctx, void *arg)
{
    SimTime now = sim_now(eng), t = sim_refresh_at(now, period);
    SimRecorder *rec = sim_engine_recorder(eng);
    if (rec)
        return sim_record_schedule_done(
            eng, rec, rec->ops->refresh(rec, now, node, period), t, done, ctx,
            arg);
    return done ? sim_schedule_at(eng, t, done, ctx, arg) : TRUE;
}

uint64_t sim_record_cause(SimEngine *eng)
{
    SimRecorder *rec = sim_engine_recorder(eng);
    return rec && rec->ops->cause ? rec->ops->cause(rec) : SIM_RECORD_NONE;
}

void sim_record_after(SimEngine *eng, uint64_t id)
{
    SimRecorder *rec = sim_engine_recorder(eng);
    if (rec && rec->ops->after && id != SIM_RECORD_NONE)
        rec->ops->after(rec, id);
}
