/* bench_net.c — `pgsim bench net`: the transports' speed against error.
 *
 * Runs one traffic pattern on one machine's network at each fidelity
 * (packet first: it is the reference) and prints, per fidelity, the
 * simulated completion time, the relative error against packet level,
 * the wall seconds and the speed-up over packet level.  Patterns (all
 * through sim/net/collective.h, so they are what workloads run):
 *   all-to-all  naive personalized all-to-all (every node sends to
 *               0, 1, 2 ... in that order), B bytes per pair;
 *   shift       all-to-all, node i sends to i+1, i+2 ... (mod n);
 *   xor         the contention-free XOR all-to-all schedule;
 *   pairwise    recursive-halving exchange, n*B / 2^(s+1) bytes at step s;
 *   random      n-1 messages of B bytes per node to uniform destinations;
 *   hotspot     the same, but a quarter of them go to node 0.
 * Network parameters come from flags (--bandwidth MB/s, --startup us,
 * --per-hop us); scripts/bench.sh passes the values of models/ipsc2.yaml
 * with their sources.  Random draws use sim/core/rng.h (--seed).
 * Output is deterministic except for the wall-clock columns.
 */
#include "sim/app/bench.h"
#include "sim/core/error.h"
#include "sim/net/collective.h"
#include <stdio.h>
#include <string.h>

typedef struct {
    char *machine, *pattern, *fidelity;
    int nodes;
    gint64 bytes;
    gint64 seed;
    double bw_mbs, startup_us, per_hop_us;
} BenchNetOpts;

typedef struct {
    SimTime end;
    double wall;
    uint64_t events, messages;
} BenchNetRun;

static const char *const patterns[] = {"all-to-all", "shift", "xor",
                                       "pairwise", "random", "hotspot",
                                       NULL};

static gboolean input_error(GError **err, const char *found,
                            const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "bench net: found %s, expected %s", found, expected);
    return FALSE;
}

static gboolean parse_opts(BenchNetOpts *o, int *argc, char ***argv,
                           GError **err)
{
    GOptionEntry entries[] = {
        {"machine", 0, 0, G_OPTION_ARG_STRING, &o->machine,
         "network (ipsc2)", "NAME"},
        {"nodes", 0, 0, G_OPTION_ARG_INT, &o->nodes, "node count, 2^d", "N"},
        {"pattern", 0, 0, G_OPTION_ARG_STRING, &o->pattern,
         "all-to-all|shift|xor|pairwise|random|hotspot", "P"},
        {"bytes", 0, 0, G_OPTION_ARG_INT64, &o->bytes, "bytes per message",
         "B"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o->fidelity,
         "all|analytic|flow|packet", "F"},
        {"seed", 0, 0, G_OPTION_ARG_INT64, &o->seed, "random seed", "S"},
        {"bandwidth", 0, 0, G_OPTION_ARG_DOUBLE, &o->bw_mbs,
         "link bandwidth, MB/s", "MBS"},
        {"startup", 0, 0, G_OPTION_ARG_DOUBLE, &o->startup_us,
         "message start-up, us", "US"},
        {"per-hop", 0, 0, G_OPTION_ARG_DOUBLE, &o->per_hop_us,
         "per-hop set-up, us", "US"},
        {NULL, 0, 0, 0, NULL, NULL, NULL},
    };
    return bench_parse_options("net", "- network speed against error",
                               entries, argc, argv, err);
}

static gboolean check_opts(const BenchNetOpts *o, GError **err)
{
    if (strcmp(o->machine, "ipsc2") != 0)
        return input_error(err, o->machine, "--machine ipsc2");
    if (o->nodes < 2 || (o->nodes & (o->nodes - 1)) || o->nodes > 65536)
        return input_error(err, "--nodes not a power of two in [2, 65536]",
                           "--nodes 2^d");
    if (!g_strv_contains(patterns, o->pattern))
        return input_error(err, o->pattern, "a --pattern of all-to-all, "
                                            "shift, xor, pairwise, random, "
                                            "hotspot");
    if (o->bytes < 0)
        return input_error(err, "negative --bytes", "--bytes >= 0");
    if (!(o->bw_mbs > 0.0) || o->startup_us < 0.0 || o->per_hop_us < 0.0)
        return input_error(err, "missing or negative network parameters",
                           "--bandwidth MB/s > 0, --startup us and "
                           "--per-hop us (models/ipsc2.yaml gives them)");
    return TRUE;
}

static NetParams ipsc2_params(const BenchNetOpts *o)
{
    NetParams p = {0};
    p.bandwidth = o->bw_mbs * 1e6;
    p.channels = 1;
    sim_time_from_s(o->startup_us * 1e-6, &p.startup);
    sim_time_from_s(o->per_hop_us * 1e-6, &p.per_hop);
    p.packet_bytes = 1024;
    p.switching = NET_SW_CIRCUIT;
    return p;
}

static void on_done(NetNet *net, void *ctx)
{
    *(SimTime *)ctx = sim_now(net_engine(net));
}

static void launch_lists(NetNet *net, const BenchNetOpts *o, SimRng *rng,
                         gboolean hot)
{
    uint32_t n = (uint32_t)o->nodes, per = n - 1;
    uint32_t *count = g_new(uint32_t, n), *dst = g_new(uint32_t, n * per);
    uint64_t *size = g_new(uint64_t, n * per);
    for (uint32_t i = 0; i < n; i++) {
        count[i] = per;
        for (uint32_t k = 0; k < per; k++) {
            uint32_t d = (uint32_t)sim_rng_below(rng, n - 1);
            d = d >= i ? d + 1 : d; /* never self */
            if (hot && i != 0 && sim_rng_below(rng, 4) == 0)
                d = 0;
            dst[i * per + k] = d;
            size[i * per + k] = (uint64_t)o->bytes;
        }
    }
    net_send_lists(net, count, dst, size, NULL, NULL);
    g_free(count);
    g_free(dst);
    g_free(size);
}

static void launch(NetNet *net, const BenchNetOpts *o, SimTime *end)
{
    uint32_t n = (uint32_t)o->nodes;
    const char *p = o->pattern;
    if (strcmp(p, "all-to-all") == 0 || strcmp(p, "xor") == 0 ||
        strcmp(p, "shift") == 0) {
        uint64_t *b = g_new(uint64_t, (gsize)n * n);
        for (gsize i = 0; i < (gsize)n * n; i++)
            b[i] = i / n == i % n ? 0 : (uint64_t)o->bytes;
        NetA2ASchedule s = p[0] == 'x'   ? NET_A2A_XOR
                           : p[0] == 's' ? NET_A2A_SHIFT
                                         : NET_A2A_NAIVE;
        net_alltoall(net, b, s, on_done, end);
        g_free(b);
    } else if (strcmp(p, "pairwise") == 0) {
        unsigned d = (unsigned)g_bit_storage(n) - 1;
        uint64_t *b = g_new(uint64_t, (gsize)n * d);
        for (uint32_t i = 0; i < n; i++)
            for (unsigned s = 0; s < d; s++)
                b[i * d + s] = (uint64_t)o->bytes * (n >> (s + 1));
        net_pairwise_exchange(net, b, on_done, end);
        g_free(b);
    } else {
        SimRng rng;
        sim_rng_init(&rng, (uint64_t)o->seed, 0);
        launch_lists(net, o, &rng, p[0] == 'h');
    }
}

static BenchNetRun run_one(const BenchNetOpts *o, NetFidelity fid)
{
    BenchNetRun r = {0};
    unsigned d = (unsigned)g_bit_storage((gulong)o->nodes) - 1;
    NetTopo *t = net_hypercube_new(d);
    NetParams par = ipsc2_params(o);
    SimEngine *eng = sim_engine_new((uint64_t)o->seed);
    NetNet *net = net_new(eng, t, &par, fid);
    gint64 t0 = g_get_monotonic_time();
    launch(net, o, &r.end);
    sim_engine_run(eng, SIM_TIME_MAX, NULL);
    r.wall = (double)(g_get_monotonic_time() - t0) * 1e-6;
    r.end = sim_now(eng); /* last delivery, also for send lists */
    r.events = sim_engine_events(eng);
    r.messages = net_total_messages(net);
    net_free(net);
    sim_engine_free(eng);
    net_topo_free(t);
    return r;
}

static void print_row(NetFidelity f, const BenchNetRun *r,
                      const BenchNetRun *ref)
{
    double err = ref ? ((double)r->end - (double)ref->end) / (double)ref->end
                     : 0.0;
    double wall = r->wall > 1e-6 ? r->wall : 1e-6;
    printf("%-9s %14.6f %+10.4f %10.4f %9.2f %10" G_GUINT64_FORMAT "\n",
           net_fidelity_name(f), sim_time_to_s(r->end), ref ? err : 0.0,
           r->wall, ref ? ref->wall / wall : 1.0, r->events);
}

static int run_all(const BenchNetOpts *o)
{
    NetFidelity order[3] = {NET_PACKET, NET_FLOW, NET_ANALYTIC}, only;
    gboolean all = strcmp(o->fidelity, "all") == 0;
    if (!all && !net_fidelity_parse(o->fidelity, &only)) {
        fprintf(stderr, "pgsim: bench net: found --fidelity %s, expected "
                        "all, analytic, flow or packet\n", o->fidelity);
        return 2;
    }
    BenchNetRun ref = {0}, r;
    printf("bench net: machine %s, %d nodes, pattern %s, %" G_GINT64_FORMAT
           " B\n", o->machine, o->nodes, o->pattern, o->bytes);
    printf("%-9s %14s %10s %10s %9s %10s\n", "fidelity", "sim_time_s",
           "rel_err", "wall_s", "speedup", "events");
    for (int i = 0; i < 3; i++) {
        if (!all && order[i] != only)
            continue;
        r = run_one(o, order[i]);
        gboolean is_ref = all && order[i] == NET_PACKET;
        print_row(order[i], &r, all && !is_ref ? &ref : NULL);
        if (is_ref)
            ref = r;
        if (order[i] == NET_FLOW || !all)
            printf("# messages %" G_GUINT64_FORMAT "\n", r.messages);
    }
    return 0;
}

int bench_net_main(int argc, char **argv)
{
    BenchNetOpts o = {.nodes = 16, .bytes = 1024, .seed = 1, .bw_mbs = 0,
                      .startup_us = -1, .per_hop_us = -1};
    GError *err = NULL;
    gboolean ok = parse_opts(&o, &argc, &argv, &err);
    if (ok) {
        o.machine = o.machine ? o.machine : g_strdup("ipsc2");
        o.pattern = o.pattern ? o.pattern : g_strdup("all-to-all");
        o.fidelity = o.fidelity ? o.fidelity : g_strdup("all");
        ok = check_opts(&o, &err);
    }
    int status = ok ? run_all(&o) : bench_fail(err);
    g_free(o.machine);
    g_free(o.pattern);
    g_free(o.fidelity);
    return status;
}
