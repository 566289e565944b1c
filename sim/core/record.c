/* record.c — the completion trampoline of recorded work (record.h).
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
