/* stats.c — moments and busy-time accumulators. */
#include "sim/core/stats.h"

void sim_moments_add(SimMoments *m, double x)
{
    if (m->n == 0 || x < m->min)
        m->min = x;
    if (m->n == 0 || x > m->max)
        m->max = x;
    m->n++;
    double d = x - m->mean;
    m->mean += d / (double)m->n;
    m->m2 += d * (x - m->mean);
}

double sim_moments_var(const SimMoments *m)
{
    return m->n > 1 ? m->m2 / (double)(m->n - 1) : 0.0;
}

void sim_busy_init(SimBusy *b)
{
    b->total = 0;
    b->per_phase = g_array_new(FALSE, TRUE, sizeof(SimTime));
}

void sim_busy_clear(SimBusy *b)
{
    if (b->per_phase)
        g_array_free(b->per_phase, TRUE);
    b->per_phase = NULL;
    b->total = 0;
}

gboolean sim_busy_add(SimBusy *b, unsigned phase, SimTime t)
{
    if (phase >= b->per_phase->len)
        g_array_set_size(b->per_phase, phase + 1);
    SimTime *p = &g_array_index(b->per_phase, SimTime, phase);
    SimTime np, nt;
    if (!sim_time_add(*p, t, &np) || !sim_time_add(b->total, t, &nt))
        return FALSE;
    *p = np;
    b->total = nt;
    return TRUE;
}

SimTime sim_busy_phase(const SimBusy *b, unsigned phase)
{
    if (!b->per_phase || phase >= b->per_phase->len)
        return 0;
    return g_array_index(b->per_phase, SimTime, phase);
}
