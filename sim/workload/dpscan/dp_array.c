/* dp_array.c — data-parallel arrays over virtual processors (dp_array.h).
 *
 * Every operation does its real work once and charges each target the
 * cost of dp_cost.h for that target's partition.  Invariants: a
 * target's per-processor counters are zero between sends; the stamp of
 * a destination element equals the current send's number iff it has
 * received a message of this send.  O(messages x targets) per send.
 */
#include "sim/workload/dpscan/dp_array.h"
#include <stdlib.h>
#include <string.h>

struct WlDpVm {
    WlDpTarget *t;
    guint nt;
    uint32_t width, height;
    WlDpVmCounts c;
    uint32_t *stamp, *depth; /* per destination element */
    uint64_t n_stamp;
    uint32_t send_no;
    /* per message of the current send: a screen destination's x and y
     * (the same on every target), then one target's source and
     * destination processors (so its counters are reset without
     * recomputing them) */
    uint32_t *mx, *my, *sp, *dp;
    uint64_t n_msg; /* length of the four */
};

static const char *const phase_names[WL_DP_N_PHASES] = {
    "transform", "scan", "pixel", "router", "display",
};

const char *wl_dp_phase_name(WlDpPhase ph)
{
    g_assert(ph < WL_DP_N_PHASES);
    return phase_names[ph];
}

WlDpVm *wl_dp_vm_new(const WlDpMachine *ms, guint n_targets, uint32_t width,
                     uint32_t height)
{
    g_assert(n_targets >= 1 && width > 0 && height > 0);
    WlDpVm *vm = g_new0(WlDpVm, 1);
    vm->t = g_new0(WlDpTarget, n_targets);
    vm->nt = n_targets;
    vm->width = width;
    vm->height = height;
    for (guint i = 0; i < n_targets; i++) {
        g_assert(ms[i].procs > 0 && ms[i].procs <= G_MAXUINT32);
        vm->t[i].m = ms[i];
        vm->t[i].inj = g_new0(uint32_t, ms[i].procs);
        vm->t[i].recv = g_new0(uint32_t, ms[i].procs);
    }
    return vm;
}

void wl_dp_vm_free(WlDpVm *vm)
{
    if (!vm)
        return;
    for (guint i = 0; i < vm->nt; i++) {
        wl_dp_layout_free(vm->t[i].screen);
        g_free(vm->t[i].inj);
        g_free(vm->t[i].recv);
    }
    g_free(vm->t);
    g_free(vm->stamp);
    g_free(vm->depth);
    g_free(vm->mx), g_free(vm->my), g_free(vm->sp), g_free(vm->dp);
    g_free(vm);
}

guint wl_dp_vm_n_targets(const WlDpVm *vm)
{
    return vm->nt;
}

const WlDpTarget *wl_dp_vm_target(const WlDpVm *vm, guint i)
{
    g_assert(i < vm->nt);
    return &vm->t[i];
}

const WlDpVmCounts *wl_dp_vm_counts(const WlDpVm *vm)
{
    return &vm->c;
}

uint64_t wl_dp_vm_screen_elems(const WlDpVm *vm)
{
    return (uint64_t)vm->width * vm->height;
}

static void charge(WlDpTarget *t, WlDpPhase ph, SimTime cost)
{
    gboolean ok = sim_time_add(t->phase[ph], cost, &t->phase[ph]) &&
                  sim_time_add(t->total, cost, &t->total);
    g_assert(ok);
}

void wl_dp_ew(WlDpVm *vm, WlDpPhase ph, uint64_t n, uint64_t active,
              uint32_t ops)
{
    g_assert(active <= n);
    if (n == 0 || ops == 0)
        return;
    vm->c.steps++;
    vm->c.ew_elems += n * ops;
    vm->c.ew_active += active * ops;
    for (guint i = 0; i < vm->nt; i++) {
        WlDpTarget *t = &vm->t[i];
        charge(t, ph, wl_dp_step_cost(&t->m, n, ops, &t->coef));
        wl_dp_count_step(&t->m, n, ops, &t->count[ph]);
    }
}

static void charge_scan(WlDpVm *vm, WlDpPhase ph, uint64_t n)
{
    vm->c.steps++;
    for (guint i = 0; i < vm->nt; i++) {
        WlDpTarget *t = &vm->t[i];
        charge(t, ph, wl_dp_scan_cost(&t->m, MAX(n, 1), &t->coef));
        wl_dp_count_slices(&t->m, MAX(n, 1), WL_DP_C_SCAN_SLICE,
                           &t->count[ph]);
    }
}

uint64_t wl_dp_scan_add(WlDpVm *vm, WlDpPhase ph, uint64_t n,
                        const uint32_t *in, uint32_t *out, uint64_t m)
{
    g_assert(m <= n);
    uint64_t sum = 0;
    for (uint64_t k = 0; k < m; k++) {
        out[k] = (uint32_t)sum;
        sum += in[k];
        g_assert(sum <= G_MAXUINT32);
    }
    charge_scan(vm, ph, n);
    return sum;
}

uint32_t wl_dp_reduce_max(WlDpVm *vm, WlDpPhase ph, uint64_t n,
                          const uint32_t *v, uint64_t m)
{
    g_assert(m <= n);
    uint32_t best = 0;
    for (uint64_t k = 0; k < m; k++)
        best = MAX(best, v[k]);
    charge_scan(vm, ph, n);
    return best;
}

/* Counts collisions and the deepest destination; combines values. */
static uint64_t deliver(WlDpVm *vm, const WlDpSend *s)
{
    if (s->n_dst > vm->n_stamp) {
        g_free(vm->stamp);
        g_free(vm->depth);
        vm->stamp = g_new0(uint32_t, s->n_dst);
        vm->depth = g_new0(uint32_t, s->n_dst);
        vm->n_stamp = s->n_dst;
        vm->send_no = 0;
    }
    uint32_t no = ++vm->send_no;
    uint64_t coll = 0;
    for (uint64_t k = 0; k < s->count; k++) {
        uint64_t d = s->dst[k];
        g_assert(d < s->n_dst);
        gboolean first = vm->stamp[d] != no;
        vm->depth[d] = first ? 1 : vm->depth[d] + 1;
        vm->stamp[d] = no;
        coll += !first;
        vm->c.max_depth = MAX(vm->c.max_depth, vm->depth[d]);
        if (!s->dest)
            continue;
        uint64_t v = s->val[k], *o = &s->dest[d];
        if (s->comb == WL_DP_COMBINE_MAX)
            *o = MAX(*o, v);
        else if (s->comb == WL_DP_COMBINE_ADD)
            *o += v;
        else
            *o = v;
    }
    return coll;
}

static WlDpLayout *screen_of(WlDpVm *vm, WlDpTarget *t)
{
    if (!t->screen)
        t->screen = wl_dp_layout_new(t->m.procs, vm->width, vm->height);
    return t->screen;
}

/* Processor of destination element d on target t. */
static uint64_t dst_proc(WlDpVm *vm, WlDpTarget *t, const WlDpSend *s,
                         uint64_t vd, uint64_t d)
{
    if (s->lay == WL_DP_LAYOUT_LINEAR)
        return d / vd;
    WlDpLayout *l = screen_of(vm, t);
    return wl_dp_layout_owner(l, (uint32_t)(d % vm->width),
                              (uint32_t)(d / vm->width));
}

/* The per-message buffers for a send of s->count messages, with a
 * screen destination's x and y filled (target-independent). */
static void msg_buffers(WlDpVm *vm, const WlDpSend *s)
{
    if (s->count > vm->n_msg) {
        vm->n_msg = s->count;
        vm->mx = g_renew(uint32_t, vm->mx, s->count);
        vm->my = g_renew(uint32_t, vm->my, s->count);
        vm->sp = g_renew(uint32_t, vm->sp, s->count);
        vm->dp = g_renew(uint32_t, vm->dp, s->count);
    }
    if (s->lay == WL_DP_LAYOUT_SCREEN)
        for (uint64_t k = 0; k < s->count; k++) {
            vm->mx[k] = (uint32_t)(s->dst[k] % vm->width);
            vm->my[k] = (uint32_t)(s->dst[k] / vm->width);
        }
}

/* Most messages one processor injects or receives in this send
 * (msg_buffers() filled for it).  floor(floor(e / v) / g) is
 * floor(e / (v g)): one division a message and end. */
static uint64_t target_load(WlDpVm *vm, WlDpTarget *t, const WlDpSend *s)
{
    uint64_t vs = wl_dp_vp_ratio(&t->m, s->n_src) * MAX(t->m.router_procs, 1);
    uint64_t vd = wl_dp_vp_ratio(&t->m, s->n_dst), load = 0;
    uint64_t g = MAX(t->m.router_procs, 1);
    WlDpLayout *l = s->lay == WL_DP_LAYOUT_SCREEN ? screen_of(vm, t) : NULL;
    for (uint64_t k = 0; k < s->count; k++) {
        uint64_t sp = (s->src ? s->src[k] : k) / vs;
        uint64_t dp = l ? wl_dp_layout_owner(l, vm->mx[k], vm->my[k]) / g
                        : s->dst[k] / (vd * g);
        g_assert(sp < t->m.procs && dp < t->m.procs);
        vm->sp[k] = (uint32_t)sp;
        vm->dp[k] = (uint32_t)dp;
        uint32_t a = ++t->inj[sp], b = ++t->recv[dp];
        load = MAX(load, MAX(a, b));
    }
    for (uint64_t k = 0; k < s->count; k++) {
        t->inj[vm->sp[k]] = 0;
        t->recv[vm->dp[k]] = 0;
    }
    return load;
}

void wl_dp_vm_set_wire(WlDpVm *vm, guint i, WlDpWireFn fn, void *ctx)
{
    g_assert(i < vm->nt && vm->t[i].m.arch == WL_DP_SPMD);
    vm->t[i].wire = fn;
    vm->t[i].wire_ctx = ctx;
}

/* The node pairs of this send on target t, priced by t->wire. */
static SimTime wire_time(WlDpVm *vm, WlDpTarget *t, const WlDpSend *s)
{
    uint64_t vs = wl_dp_vp_ratio(&t->m, s->n_src);
    uint64_t vd = wl_dp_vp_ratio(&t->m, s->n_dst);
    GHashTable *at = g_hash_table_new(g_int64_hash, g_int64_equal);
    GArray *keys = g_array_new(FALSE, FALSE, sizeof(gint64));
    GArray *src = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    GArray *dst = g_array_new(FALSE, FALSE, sizeof(uint32_t));
    GArray *msgs = g_array_new(FALSE, FALSE, sizeof(uint64_t));
    g_array_set_size(keys, s->count); /* stable addresses for the keys */
    for (uint64_t k = 0; k < s->count; k++) {
        uint32_t a = (uint32_t)((s->src ? s->src[k] : k) / vs);
        uint32_t b = (uint32_t)dst_proc(vm, t, s, vd, s->dst[k]);
        gint64 *key = &g_array_index(keys, gint64, k);
        *key = (gint64)a * (gint64)t->m.procs + b;
        gpointer v = g_hash_table_lookup(at, key);
        if (v) {
            g_array_index(msgs, uint64_t, GPOINTER_TO_SIZE(v) - 1)++;
            continue;
        }
        uint64_t one = 1;
        g_array_append_val(src, a);
        g_array_append_val(dst, b);
        g_array_append_val(msgs, one);
        g_hash_table_insert(at, key, GSIZE_TO_POINTER(msgs->len));
    }
    WlDpTraffic tr = {(const uint32_t *)src->data, (const uint32_t *)dst->data,
                      (const uint64_t *)msgs->data, msgs->len};
    SimTime w = t->wire(t->wire_ctx, &tr);
    g_hash_table_destroy(at);
    g_array_free(keys, TRUE);
    g_array_free(src, TRUE);
    g_array_free(dst, TRUE);
    g_array_free(msgs, TRUE);
    return w;
}

/* The cost of this send on target t, by the formula or its network. */
static SimTime target_send_cost(WlDpVm *vm, WlDpTarget *t, const WlDpSend *s,
                                uint64_t load)
{
    WlDpCounts *k = &t->count[s->phase];
    if (t->m.arch != WL_DP_SPMD) {
        wl_dp_count_send(&t->m, s->words, s->n_src, s->count, load, 0, k);
        return wl_dp_send_cost(&t->m, s->words, s->n_src, s->count, load,
                               &t->coef);
    }
    SimTime w = t->wire ? wire_time(vm, t, s) : wl_dp_fattree_wire(&t->m, load);
    wl_dp_count_send(&t->m, s->words, s->n_src, s->count, load, w, k);
    t->wire_total += sim_time_mul_sat(w, s->words);
    t->soft_total += sim_time_mul_sat(t->m.msg_overhead, load * s->words);
    return wl_dp_send_cost_wired(&t->m, s->words, s->n_src, s->count, load, w,
                                 &t->coef);
}

uint64_t wl_dp_send(WlDpVm *vm, const WlDpSend *s)
{
    g_assert(s->words > 0 && s->n_src > 0 && s->n_dst > 0);
    g_assert(s->lay == WL_DP_LAYOUT_LINEAR ||
             s->n_dst == wl_dp_vm_screen_elems(vm));
    g_assert(!s->dest || s->val);
    uint64_t coll = s->count ? deliver(vm, s) : 0;
    vm->c.steps += s->words;
    vm->c.sends += s->words;
    vm->c.messages += s->count;
    vm->c.words += s->count * s->words;
    vm->c.collisions += coll;
    if (s->count > 0)
        msg_buffers(vm, s);
    for (guint i = 0; i < vm->nt && s->count > 0; i++) {
        WlDpTarget *t = &vm->t[i];
        uint64_t load = target_load(vm, t, s);
        t->max_load = MAX(t->max_load, load);
        charge(t, s->phase, target_send_cost(vm, t, s, load));
    }
    return coll;
}

void wl_dp_news(WlDpVm *vm, WlDpPhase ph, const uint64_t *in, uint64_t *out,
                int dx, int dy, uint64_t fill)
{
    g_assert(abs(dx) + abs(dy) == 1 && in != out);
    int64_t w = vm->width, h = vm->height;
    for (int64_t y = 0; y < h; y++)
        for (int64_t x = 0; x < w; x++) {
            int64_t sx = x - dx, sy = y - dy;
            gboolean in_grid = sx >= 0 && sx < w && sy >= 0 && sy < h;
            out[y * w + x] = in_grid ? in[sy * w + sx] : fill;
        }
    vm->c.steps++;
    vm->c.news_moves++;
    for (guint i = 0; i < vm->nt; i++) {
        WlDpTarget *t = &vm->t[i];
        charge(t, ph, wl_dp_news_cost(&t->m, (uint64_t)(w * h), &t->coef));
        wl_dp_count_slices(&t->m, (uint64_t)(w * h), WL_DP_C_NEWS_SLICE,
                           &t->count[ph]);
    }
}
