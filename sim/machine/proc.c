/* proc.c — processors with FIFO work and busy-time accounting.
 *
 * Invariant: free_at is the completion time of the last submitted work
 * (0 before any).  A request submitted at `now` starts at max(now,
 * free_at) and ends at start + cost; ends are non-decreasing in
 * submission order and the engine orders equal times by schedule order,
 * so done handlers run in FIFO order.  Busy time is the sum of submitted
 * costs, charged on submission.  Cost: O(1) + one event per request.
 */
#include "sim/machine/proc.h"
#include "sim/machine/costs.h"
#include "sim/core/record.h"
#include "sim/core/trace.h"
#include <string.h>

void mach_proc_init(MachProc *p, MachMachine *m, SimEngine *eng,
                    const MachKindInfo *info, guint id, guint16 kind)
{
    *p = (MachProc){.m = m,
                    .eng = eng,
                    .info = info,
                    .id = id,
                    .kind = kind,
                    .entity = UINT32_MAX};
}

void mach_proc_clear(MachProc *p)
{
    if (p->busy.per_phase)
        sim_busy_clear(&p->busy);
    g_free(p->name);
    p->name = NULL;
}

static void charge(MachProc *p, unsigned phase, SimTime cost,
                   gboolean *overflow)
{
    if (!p->busy.per_phase)
        sim_busy_init(&p->busy);
    *overflow = !sim_busy_add(&p->busy, phase, cost);
}

static void trace_span(MachProc *p, unsigned phase, SimTime start, SimTime end)
{
    SimEngine *eng = p->eng;
    SimTrace *tr = sim_engine_trace(eng);
    if (!tr)
        return;
    sim_trace_span(tr, mach_proc_id(p), mach_proc_name(p),
                   sim_engine_phase_name(eng, phase), start, end);
}

static void fail_overflow(SimEngine *eng, MachProc *p, const char *what)
{
    sim_engine_fail(eng, g_error_new(SIM_ERROR, SIM_ERROR_OVERFLOW,
                                     "%s of processor %s overflows the "
                                     "64-bit picosecond clock",
                                     what, mach_proc_name(p)));
}

/* Submits `cost`; its counts w (none: n_ops 0) go to a recorder. */
static gboolean submit_terms(MachProc *p, SimTime cost, const SimWork *w,
                             unsigned phase, SimHandler done, void *ctx,
                             void *arg)
{
    SimEngine *eng = p->eng;
    g_assert(phase < sim_engine_phase_count(eng));
    SimTime now = sim_now(eng);
    SimTime start = MAX(p->free_at, now), end;
    gboolean overflow;
    if (!sim_time_add(start, cost, &end)) {
        fail_overflow(eng, p, "completion time");
        return FALSE;
    }
    /* busy time counts only within the run's horizon (run.until): work
     * cut short by it is busy up to the horizon, then no more */
    SimTime h = sim_engine_horizon(eng);
    charge(p, phase, end <= h ? cost : start >= h ? 0 : h - start, &overflow);
    if (overflow) {
        fail_overflow(eng, p, "busy time");
        return FALSE;
    }
    p->free_at = end;
    p->requests++;
    trace_span(p, phase, start, end);
    SimRecorder *rec = sim_engine_recorder(eng);
    if (rec) /* `pgsim run --record`: the trace hears of it (record.h) */
        return sim_record_schedule_done(eng, rec,
                                        rec->ops->compute(rec, now, p->id,
                                                          phase, cost, end, w,
                                                          done != NULL),
                                        end, done, ctx, arg);
    return done ? sim_schedule_at(eng, end, done, ctx, arg) : TRUE;
}

static gboolean submit(MachProc *p, SimTime cost, const MachOp *ops,
                       guint n_ops, unsigned phase, SimHandler done, void *ctx,
                       void *arg)
{
    SimWork w = {ops, n_ops, NULL, 0};
    return submit_terms(p, cost, &w, phase, done, ctx, arg);
}

gboolean mach_proc_compute_terms(MachProc *p, SimTime cost, const SimWork *w,
                                 unsigned phase, SimHandler done, void *ctx,
                                 void *arg)
{
    g_assert(w->n_ops > 0);
    return submit_terms(p, cost, w, phase, done, ctx, arg);
}

gboolean mach_proc_compute(MachProc *p, SimTime cost, unsigned phase,
                           SimHandler done, void *ctx, void *arg)
{
    return submit(p, cost, NULL, 0, phase, done, ctx, arg);
}

/* count x the kind's cost of op, saturating; an op counted 0 times
 * costs nothing, priced or not (a kind that lacks a cost the work never
 * spends, as compositing's scatter and gather). */
static SimTime op_cost(const MachProc *p, const MachOp *op)
{
    if (op->count == 0)
        return 0;
    const MachCost *unit =
        p->info->costs ? g_hash_table_lookup(p->info->costs, op->name) : NULL;
    g_assert(unit); /* the workload checked with mach_costs_new() */
    return sim_time_mul_sat(unit->value, op->count);
}

static SimTime ops_cost(const MachProc *p, const MachOp *ops, guint n_ops)
{
    SimTime cost = 0;
    for (guint i = 0; i < n_ops; i++)
        cost = sim_time_add_sat(cost, op_cost(p, &ops[i]));
    return cost;
}

gboolean mach_proc_compute_ops(MachProc *p, const MachOp *ops, guint n_ops,
                               unsigned phase, SimHandler done, void *ctx,
                               void *arg)
{
    g_assert(n_ops > 0); /* none: a time, mach_proc_compute() */
    return submit(p, ops_cost(p, ops, n_ops), ops, n_ops, phase, done, ctx,
                  arg);
}

gboolean mach_proc_compute_priced(MachProc *p, SimTime cost, const MachOp *ops,
                                  guint n_ops, unsigned phase, SimHandler done,
                                  void *ctx, void *arg)
{
    g_assert(n_ops > 0);
    return submit(p, cost, ops, n_ops, phase, done, ctx, arg);
}

void mach_ops_add(MachOps *o, const char *name, uint64_t count)
{
    for (guint i = 0; i < o->n; i++)
        if (o->op[i].name == name || !strcmp(o->op[i].name, name)) {
            o->op[i].count += count;
            return;
        }
    g_assert(o->n < MACH_OPS_MAX);
    o->op[o->n++] = (MachOp){name, count};
}

SimTime mach_proc_ops_cost(const MachProc *p, const MachOps *o)
{
    return ops_cost(p, o->op, o->n);
}

gboolean mach_proc_compute_list(MachProc *p, const MachOps *o, unsigned phase,
                                SimHandler done, void *ctx, void *arg)
{
    return o->n ? mach_proc_compute_ops(p, o->op, o->n, phase, done, ctx, arg)
                : mach_proc_compute(p, 0, phase, done, ctx, arg);
}

SimTime mach_proc_free_at(const MachProc *p)
{
    return p->free_at;
}

gboolean mach_proc_idle(const MachProc *p)
{
    return p->free_at <= sim_now(p->eng);
}

SimTime mach_proc_busy(const MachProc *p)
{
    return p->busy.total;
}

SimTime mach_proc_busy_phase(const MachProc *p, unsigned phase)
{
    return sim_busy_phase(&p->busy, phase);
}

uint64_t mach_proc_requests(const MachProc *p)
{
    return p->requests;
}

guint mach_proc_id(const MachProc *p)
{
    return p->id;
}

guint mach_proc_index(const MachProc *p)
{
    return p->id - p->info->first;
}

const char *mach_proc_kind(const MachProc *p)
{
    return p->info->name;
}

const char *mach_proc_name(MachProc *p)
{
    if (!p->name)
        p->name =
            g_strdup_printf("%s%u", mach_proc_kind(p), mach_proc_index(p));
    return p->name;
}

uint32_t mach_proc_entity(MachProc *p)
{
    if (p->entity == UINT32_MAX)
        p->entity = sim_entity_add(p->eng, mach_proc_name(p));
    return p->entity;
}

MachMachine *mach_proc_machine(const MachProc *p)
{
    return p->m;
}
