/* dp_cost.c — cost of data-parallel steps, scans and sends (dp_cost.h).
 *
 * See dp_cost.h for the formulas and their sources.  Invariant: every
 * cost is a sum of machine constants times integer counts, so the same
 * inputs give the same picoseconds on every platform.  O(1) per call
 * (O(levels) for the fat tree), O(pixels) for a z-buffer send's load.
 */
#include "sim/workload/dpscan/dp_cost.h"
#include <string.h>

static SimTime add_time(SimTime a, SimTime b)
{
    SimTime s;
    gboolean ok = sim_time_add(a, b, &s);
    g_assert(ok);
    return s;
}

static uint64_t pow2_ceil(uint64_t v)
{
    uint64_t r = 1;
    while (r < v)
        r <<= 1;
    return r;
}

uint64_t wl_dp_vp_ratio(const WlDpMachine *m, uint64_t n)
{
    g_assert(m->procs > 0);
    uint64_t v = n / m->procs + (n % m->procs != 0);
    return m->vp_pow2 && v > 0 ? pow2_ceil(v) : v;
}

SimTime wl_dp_step_cost(const WlDpMachine *m, uint64_t n, uint32_t ops,
                        WlDpCoef *k)
{
    uint64_t v = wl_dp_vp_ratio(m, n);
    if (k) {
        k->steps += 1.0;
        k->op_slices += (double)v * (double)ops;
    }
    return add_time(m->step, sim_time_mul_sat(m->op, v * (uint64_t)ops));
}

SimTime wl_dp_scan_cost(const WlDpMachine *m, uint64_t n, WlDpCoef *k)
{
    uint64_t v = wl_dp_vp_ratio(m, n);
    if (k) {
        k->steps += 1.0;
        k->scan_slices += (double)v;
    }
    return add_time(m->step, sim_time_mul_sat(m->scan_slice, v));
}

double wl_dp_fattree_escape(unsigned arity, uint64_t p, unsigned level)
{
    g_assert(arity >= 2 && p >= 1);
    double sub = 1.0;
    for (unsigned i = 0; i < level; i++)
        sub *= (double)arity;
    return sub >= (double)p ? 0.0 : 1.0 - sub / (double)p;
}

SimTime wl_dp_fattree_wire(const WlDpMachine *m, uint64_t load)
{
    double bytes = (double)load * (double)m->msg_bytes, worst = 0.0;
    g_assert(m->levels > 0);
    for (unsigned l = 0; l < NET_MAX_LEVELS; l++) {
        double bw = m->level_bw[MIN(l, m->levels - 1)];
        g_assert(bw > 0.0);
        double f = wl_dp_fattree_escape(m->arity, m->procs, l);
        worst = MAX(worst, f * bytes / bw);
    }
    return sim_time_for_bytes(worst, 1.0);
}

/* Counts a send into k (either wire model). */
static void count_send(const WlDpMachine *m, uint32_t words, uint64_t n,
                       uint64_t active, uint64_t load, WlDpCoef *k)
{
    if (!k)
        return;
    uint64_t mean = active / m->procs + (active % m->procs != 0);
    k->msg_slices += (double)words * (double)mean;
    k->steps += words;
    k->sends += words;
    k->slices += (double)words * (double)load;
    k->vp_slices += (double)words * (double)wl_dp_vp_ratio(m, n);
}

/* One SPMD array sent: issue, the send phase's latency, then the slower
 * of the per-message software and the wire. */
static SimTime spmd_one(const WlDpMachine *m, uint64_t load, SimTime wire)
{
    SimTime soft = sim_time_mul_sat(m->msg_overhead, load);
    return add_time(add_time(m->step, m->net_latency), MAX(soft, wire));
}

SimTime wl_dp_send_cost(const WlDpMachine *m, uint32_t words, uint64_t n,
                        uint64_t active, uint64_t load, WlDpCoef *k)
{
    if (load == 0 || words == 0 || active == 0)
        return 0;
    count_send(m, words, n, active, load, k);
    if (m->arch == WL_DP_SPMD)
        return sim_time_mul_sat(spmd_one(m, load, wl_dp_fattree_wire(m, load)),
                                words);
    /* Slices holding a message: the messages are spread over the array. */
    uint64_t vps = wl_dp_vp_ratio(m, n);
    uint64_t mean = active / m->procs + (active % m->procs != 0);
    SimTime one = add_time(
        add_time(m->step, m->send_setup),
        add_time(add_time(sim_time_mul_sat(m->send_vp, vps),
                          sim_time_mul_sat(m->send_msg, mean)),
                 sim_time_mul_sat(m->send_slice, load)));
    return sim_time_mul_sat(one, words);
}

SimTime wl_dp_send_cost_wired(const WlDpMachine *m, uint32_t words,
                              uint64_t n, uint64_t active, uint64_t load,
                              SimTime wire, WlDpCoef *k)
{
    g_assert(m->arch == WL_DP_SPMD);
    if (load == 0 || words == 0 || active == 0)
        return 0;
    count_send(m, words, n, active, load, k);
    return sim_time_mul_sat(spmd_one(m, load, wire), words);
}

static unsigned log2u(uint64_t v)
{
    unsigned r = 0;
    while ((1ull << (r + 1)) <= v)
        r++;
    return r;
}

WlDpLayout *wl_dp_layout_new(uint64_t procs, uint32_t width, uint32_t height)
{
    g_assert(procs > 0 && width > 0 && height > 0);
    WlDpLayout *l = g_new0(WlDpLayout, 1);
    l->procs = procs;
    l->px = (uint32_t)MIN(procs, G_MAXUINT32);
    l->py = 1;
    if ((procs & (procs - 1)) == 0) {
        unsigned d = log2u(procs);
        l->px = 1u << ((d + 1) / 2);
        l->py = 1u << (d / 2);
    }
    l->bw = MAX((width + l->px - 1) / l->px, 1);
    l->bh = MAX((height + l->py - 1) / l->py, 1);
    l->width = width;
    l->height = height;
    l->col = g_new(uint32_t, width);
    l->row = g_new(uint32_t, height);
    for (uint32_t x = 0; x < width; x++)
        l->col[x] = x / l->bw;
    for (uint32_t y = 0; y < height; y++)
        l->row[y] = (y / l->bh) * l->px;
    l->count = g_new0(uint32_t, procs);
    return l;
}

void wl_dp_layout_free(WlDpLayout *l)
{
    if (!l)
        return;
    g_free(l->col);
    g_free(l->row);
    g_free(l->count);
    g_free(l);
}

SimTime wl_dp_news_cost(const WlDpMachine *m, uint64_t n, WlDpCoef *k)
{
    uint64_t v = wl_dp_vp_ratio(m, n);
    if (k) {
        k->steps += 1.0;
        k->news_slices += (double)v;
    }
    return add_time(m->step, sim_time_mul_sat(m->news_slice, v));
}

/* Named counts (dp_cost.h WlDpCounts): what the functions above charge,
 * as counts of the model's constants. */
#define DP_SECTION "dpscan."
static const char *const cost_paths[WL_DP_N_COSTS] = {
    DP_SECTION "step",        DP_SECTION "op",
    DP_SECTION "scan_slice",  DP_SECTION "news_slice",
    DP_SECTION "send_setup",  DP_SECTION "send_vp",
    DP_SECTION "send_msg",    DP_SECTION "send_slice",
    DP_SECTION "net_latency", DP_SECTION "msg_overhead",
};

const char *wl_dp_cost_path(WlDpCost c)
{
    g_assert(c < WL_DP_N_COSTS);
    return cost_paths[c];
}

const char *wl_dp_cost_name(WlDpCost c)
{
    return wl_dp_cost_path(c) + strlen(DP_SECTION);
}

SimTime wl_dp_cost_value(const WlDpMachine *m, WlDpCost c)
{
    const SimTime v[WL_DP_N_COSTS] = {
        m->step,       m->op,       m->scan_slice, m->news_slice,
        m->send_setup, m->send_vp,  m->send_msg,   m->send_slice,
        m->net_latency, m->msg_overhead,
    };
    g_assert(c < WL_DP_N_COSTS);
    return v[c];
}

SimTime wl_dp_counts_price(const WlDpMachine *m, const WlDpCounts *k)
{
    SimTime t = k->wire;
    for (int c = 0; c < WL_DP_N_COSTS; c++)
        t = add_time(t, sim_time_mul_sat(wl_dp_cost_value(m, (WlDpCost)c),
                                         k->n[c]));
    return t;
}

void wl_dp_count_step(const WlDpMachine *m, uint64_t n, uint32_t ops,
                      WlDpCounts *k)
{
    if (!k)
        return;
    k->n[WL_DP_C_STEP]++;
    k->n[WL_DP_C_OP] += wl_dp_vp_ratio(m, n) * (uint64_t)ops;
}

void wl_dp_count_slices(const WlDpMachine *m, uint64_t n, WlDpCost c,
                        WlDpCounts *k)
{
    g_assert(c == WL_DP_C_SCAN_SLICE || c == WL_DP_C_NEWS_SLICE);
    if (!k)
        return;
    k->n[WL_DP_C_STEP]++;
    k->n[c] += wl_dp_vp_ratio(m, n);
}

void wl_dp_count_send(const WlDpMachine *m, uint32_t words, uint64_t n,
                      uint64_t active, uint64_t load, SimTime wire,
                      WlDpCounts *k)
{
    if (!k || load == 0 || words == 0 || active == 0)
        return;
    k->n[WL_DP_C_STEP] += words;
    if (m->arch == WL_DP_SIMD) {
        uint64_t mean = active / m->procs + (active % m->procs != 0);
        k->n[WL_DP_C_SEND_SETUP] += words;
        k->n[WL_DP_C_SEND_VP] += words * wl_dp_vp_ratio(m, n);
        k->n[WL_DP_C_SEND_MSG] += words * mean;
        k->n[WL_DP_C_SEND_SLICE] += words * load;
        return;
    }
    /* spmd_one(): the slower of the software and the wire. */
    k->n[WL_DP_C_NET_LATENCY] += words;
    if (sim_time_mul_sat(m->msg_overhead, load) >= wire)
        k->n[WL_DP_C_MSG_OVERHEAD] += words * load;
    else
        k->wire = add_time(k->wire, sim_time_mul_sat(wire, words));
}
