/* dp_cost.c — cost of data-parallel steps and router sends (seed 004).
 *
 * See dp_cost.h for the formulas and their sources.  Invariant: every
 * cost is a sum of machine constants times integer counts, so the same
 * inputs give the same picoseconds on every platform.  O(1) per call
 * (O(levels) for the fat tree).
 */
#include "sim/workload/dpscan/dp_cost.h"

static SimTime mul_time(SimTime t, uint64_t n)
{
    g_assert(n == 0 || t <= SIM_TIME_MAX / n);
    return t * n;
}

static SimTime add_time(SimTime a, SimTime b)
{
    SimTime s;
    gboolean ok = sim_time_add(a, b, &s);
    g_assert(ok);
    return s;
}

uint64_t wl_dp_vp_ratio(uint64_t n, uint64_t procs)
{
    g_assert(procs > 0);
    return n / procs + (n % procs != 0);
}

SimTime wl_dp_step_cost(const WlDpMachine *m, uint64_t n, uint32_t ops,
                        WlDpCoef *k)
{
    uint64_t v = wl_dp_vp_ratio(n, m->procs);
    if (k) {
        k->steps += 1.0;
        k->op_slices += (double)v * (double)ops;
    }
    return add_time(m->step, mul_time(m->op, v * (uint64_t)ops));
}

double wl_dp_fattree_escape(unsigned arity, uint64_t p, unsigned level)
{
    g_assert(arity >= 2 && p >= 1);
    double sub = 1.0;
    for (unsigned i = 0; i < level; i++)
        sub *= (double)arity;
    return sub >= (double)p ? 0.0 : 1.0 - sub / (double)p;
}

/* Wire time of one node's k messages through the fat tree. */
static SimTime fattree_wire(const WlDpMachine *m, uint64_t k)
{
    double bytes = (double)k * (double)m->msg_bytes, worst = 0.0;
    for (unsigned l = 0; l < m->levels; l++) {
        g_assert(m->level_bw[l] > 0.0);
        double f = wl_dp_fattree_escape(m->arity, m->procs, l);
        worst = MAX(worst, f * bytes / m->level_bw[l]);
    }
    /* Levels above the listed ones run at the last listed bandwidth. */
    for (unsigned l = m->levels; l < NET_MAX_LEVELS && m->levels > 0; l++) {
        double f = wl_dp_fattree_escape(m->arity, m->procs, l);
        worst = MAX(worst, f * bytes / m->level_bw[m->levels - 1]);
    }
    return sim_time_for_bytes(worst, 1.0);
}

SimTime wl_dp_send_cost(const WlDpMachine *m, uint64_t active, WlDpCoef *k)
{
    if (active == 0)
        return 0;
    uint64_t slices = wl_dp_vp_ratio(active, m->procs);
    if (k) {
        k->sends += 1.0;
        k->slices += (double)slices;
    }
    if (m->arch == WL_DP_SIMD)
        return add_time(m->send_setup, mul_time(m->send_slice, slices));
    SimTime soft = mul_time(m->msg_overhead, slices);
    SimTime wire = fattree_wire(m, slices);
    return add_time(m->net_latency, MAX(soft, wire));
}
