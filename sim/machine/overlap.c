/* overlap.c — work held for the longest of overlapping terms
 * (overlap.h).  O(terms x counts) per call; no events of its own.
 */
#include "sim/machine/overlap.h"
#include "sim/machine/shmem.h"

void mach_overlap_reset(MachOverlap *o)
{
    o->own.n = 0;
    o->n = 0;
}

static MachTerm *add_term(MachOverlap *o)
{
    g_assert(o->n < MACH_TERMS_MAX);
    MachTerm *t = &o->term[o->n++];
    *t = (MachTerm){0};
    return t;
}

void mach_overlap_ops(MachOverlap *o, const MachProc *on, const MachOps *ops)
{
    MachTerm *t = add_term(o);
    t->on = on;
    t->ops = *ops;
}

void mach_overlap_bus(MachOverlap *o, const MachShmem *bus, const MachProc *to,
                      uint64_t bytes)
{
    MachTerm *t = add_term(o);
    t->on = to;
    t->bus = bus;
    t->bytes = bytes;
}

static SimTime term_cost(const MachTerm *t)
{
    return t->bus ? mach_shmem_time(t->bus, t->bytes)
                  : mach_proc_ops_cost(t->on, &t->ops);
}

SimTime mach_overlap_cost(const MachProc *p, const MachOverlap *o)
{
    SimTime c = mach_proc_ops_cost(p, &o->own);
    for (guint i = 0; i < o->n; i++)
        c = MAX(c, term_cost(&o->term[i]));
    return c;
}

gboolean mach_proc_compute_overlap(MachProc *p, const MachOverlap *o,
                                   unsigned phase, SimHandler done, void *ctx,
                                   void *arg)
{
    g_assert(o->own.n > 0);
    SimOpTerm t[MACH_TERMS_MAX];
    for (guint i = 0; i < o->n; i++) {
        const MachTerm *m = &o->term[i];
        t[i] = (SimOpTerm){.node = mach_proc_id(m->on),
                           .bus = m->bus != NULL,
                           .bytes = m->bytes,
                           .ops = m->ops.op,
                           .n_ops = m->bus ? 0 : m->ops.n};
    }
    SimWork w = {o->own.op, o->own.n, t, o->n};
    return mach_proc_compute_terms(p, mach_overlap_cost(p, o), &w, phase, done,
                                   ctx, arg);
}
