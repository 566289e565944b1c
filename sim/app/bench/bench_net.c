/* bench_net.c — `pgsim bench net`: the transports' speed against error.
 *
 * Runs one traffic pattern (sim/net/traffic.h) on one machine model's
 * network at each fidelity (packet first: it is the reference) and prints,
 * per fidelity, the simulated completion time, the relative error against
 * packet level, the wall seconds and the speed-up over packet level.
 *
 * The machine is models/<--machine>.yaml built by the machine layer, at
 * the partition size --nodes (sim/machine/partition.h); --set
 * machine.KEY=VALUE overrides any model value as in `pgsim run`, and
 * --bandwidth MB/s, --startup us, --per-hop us are shorthands for
 * machine.network.bandwidth / startup / per_hop.  A run whose messages
 * are not all delivered is an error, not a figure.  --repeat K runs each
 * fidelity K times and shows the least wall time (simulated results are
 * identical run to run).
 * Output is deterministic except for the wall-clock columns.
 */
#include "sim/app/bench/bench_net.h"
#include "sim/app/bench/bench.h"
#include "sim/core/cfg.h"
#include "sim/core/units.h"
#include "sim/core/error.h"
#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

struct BenchNet {
    BenchNetSpec spec;
    CfgNode *root; /* run-config tree: machine section with overrides */
    guint nodes;
    char *desc;
};

/* ---- building ---------------------------------------------------------- */

static MachMachine *build(const BenchNet *b, SimEngine *eng, NetFidelity f,
                          GError **err)
{
    MachMachine *m = mach_new_from_cfg(eng, cfg_get(b->root, "machine"),
                                       net_fidelity_name(f), err);
    if (m && !mach_require_net(m, err)) {
        mach_free(m);
        return NULL;
    }
    return m;
}

static const char *switching_name(NetSwitching s)
{
    static const char *const w[] = {"circuit", "cut-through",
                                    "store-and-forward", "ring-slot"};
    return w[s];
}

static char *describe(const BenchNet *b, NetNet *net, const char *part)
{
    const NetParams *p = net_params(net);
    GString *s = g_string_new("");
    char *path = mach_model_path(b->spec.machine, NULL);
    g_string_append_printf(s, "machine %s (%s): %s of %u nodes (%s)\n",
                           b->spec.machine, path, net_topo(net)->ops->name,
                           net_nodes(net), part ? part : "model size");
    g_string_append_printf(s,
                           "network: %s switching, %.4g MB/s per channel "
                           "x %u, start-up %.4g us",
                           switching_name(p->switching), p->bandwidth / 1e6,
                           p->channels, sim_time_to_s(p->startup) * 1e6);
    if (p->startup_long)
        g_string_append_printf(s, " (%.4g us above %" G_GUINT64_FORMAT " B)",
                               sim_time_to_s(p->startup_long) * 1e6,
                               p->long_threshold);
    g_string_append_printf(s, ", %.4g us per hop",
                           sim_time_to_s(p->per_hop) * 1e6);
    g_free(path);
    return g_string_free(s, FALSE);
}

/* Builds the machine once: checks the model, the partition and the
 * pattern's fit, and writes the description. */
static gboolean probe(BenchNet *b, const char *part, GError **err)
{
    SimEngine *eng = sim_engine_new(b->spec.seed);
    MachMachine *m = build(b, eng, NET_ANALYTIC, err);
    gboolean ok = m != NULL;
    if (ok) {
        b->nodes = net_nodes(mach_net(m));
        b->desc = describe(b, mach_net(m), part);
        ok = net_traffic_check(b->spec.pattern, b->nodes, err);
    }
    mach_free(m);
    sim_engine_free(eng);
    return ok;
}

BenchNet *bench_net_new(const BenchNetSpec *spec, GError **err)
{
    BenchNet *b = g_new0(BenchNet, 1);
    char *part = NULL;
    b->spec = *spec;
    b->root = mach_partition_root("bench net", spec->machine, spec->sets,
                                  spec->nodes, &part, err);
    gboolean ok = b->root && probe(b, part, err);
    g_free(part);
    if (!ok) {
        char *n = spec->nodes ? g_strdup_printf(" --nodes %u", spec->nodes)
                              : g_strdup("");
        g_prefix_error(err, "bench net --machine %s%s: ", spec->machine, n);
        g_free(n);
        bench_net_free(b);
        return NULL;
    }
    return b;
}

void bench_net_free(BenchNet *b)
{
    if (!b)
        return;
    cfg_free(b->root);
    g_free(b->desc);
    g_free(b);
}

guint bench_net_nodes(const BenchNet *b)
{
    return b->nodes;
}
const char *bench_net_describe(const BenchNet *b)
{
    return b->desc;
}

/* ---- running ----------------------------------------------------------- */

static void on_done(NetNet *net, void *ctx)
{
    (void)net;
    *(gboolean *)ctx = TRUE;
}

gboolean bench_net_run(const BenchNet *b, NetFidelity fid, BenchNetRun *out,
                       GError **err)
{
    SimEngine *eng = sim_engine_new(b->spec.seed);
    MachMachine *m = build(b, eng, fid, err);
    gboolean done = FALSE, ok = m != NULL;
    if (ok) {
        NetNet *net = mach_net(m);
        gint64 t0 = g_get_monotonic_time();
        net_traffic_start(net, b->spec.pattern, b->spec.bytes, b->spec.seed,
                          on_done, &done);
        ok = sim_engine_run(eng, SIM_TIME_MAX, err);
        out->wall = (double)(g_get_monotonic_time() - t0) * 1e-6;
        out->end = sim_now(eng);
        out->events = sim_engine_events(eng);
        out->messages = net_total_messages(net);
        out->delivered = net_delivered(net);
    }
    if (ok && (!done || out->delivered != out->messages)) {
        g_set_error(err, SIM_ERROR, SIM_ERROR_INTERNAL,
                    "bench net: found %" G_GUINT64_FORMAT
                    " of %" G_GUINT64_FORMAT " messages delivered at %s level, "
                    "expected all",
                    out->delivered, out->messages, net_fidelity_name(fid));
        ok = FALSE;
    }
    mach_free(m);
    sim_engine_free(eng);
    return ok;
}

/* ---- command line ------------------------------------------------------ */

typedef struct {
    char *machine, *pattern, *fidelity;
    char **sets;
    int nodes, repeat;
    gint64 seed;
    uint64_t bytes; /* from bytes_s, after check_opts */
    /* Quantities as given, with units ("10KB", "2.8 MB/s", "350us"); a
     * bare number keeps the old unit (bytes, MB/s, us).  NULL: not given. */
    char *bytes_s, *bandwidth, *startup, *per_hop;
} BenchNetOpts;

static gboolean parse_opts(BenchNetOpts *o, int *argc, char ***argv,
                           GError **err)
{
    GOptionEntry entries[] = {
        {"machine", 0, 0, G_OPTION_ARG_STRING, &o->machine,
         "model name: models/NAME.yaml (default ipsc2)", "NAME"},
        {"nodes", 0, 0, G_OPTION_ARG_INT, &o->nodes,
         "partition size (default: the model's)", "N"},
        {"pattern", 0, 0, G_OPTION_ARG_STRING, &o->pattern,
         "all-to-all|shift|xor|pairwise|random|hotspot", "P"},
        {"bytes", 0, 0, G_OPTION_ARG_STRING, &o->bytes_s,
         "size of a message, e.g. 10KB or 4 KiB (bare: bytes; default 1024)",
         "SIZE"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o->fidelity,
         "all|analytic|flow|packet", "F"},
        {"seed", 0, 0, G_OPTION_ARG_INT64, &o->seed, "random seed", "S"},
        {"repeat", 0, 0, G_OPTION_ARG_INT, &o->repeat,
         "runs per fidelity; the least wall time is shown (default 1)", "K"},
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o->sets,
         "override a model value (repeatable)", "machine.KEY=VALUE"},
        {"bandwidth", 0, 0, G_OPTION_ARG_STRING, &o->bandwidth,
         "override network.bandwidth, e.g. 2.8MB/s or 1 Gbps (bare: MB/s)",
         "BW"},
        {"startup", 0, 0, G_OPTION_ARG_STRING, &o->startup,
         "override network.startup, e.g. 350us (bare: us)", "TIME"},
        {"per-hop", 0, 0, G_OPTION_ARG_STRING, &o->per_hop,
         "override network.per_hop, e.g. 2 us (bare: us)", "TIME"},
        {NULL, 0, 0, 0, NULL, NULL, NULL},
    };
    return bench_parse_options("net", "- network speed against error", entries,
                               argc, argv, err);
}

static gboolean input_error(GError **err, const char *found,
                            const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "bench net: found %s, expected %s", found, expected);
    return FALSE;
}

/* FALSE for a bare number ("350"), which takes the flag's old unit. */
static gboolean with_unit(const char *v)
{
    size_t n = strlen(v);
    while (n > 0 && g_ascii_isspace(v[n - 1]))
        n--;
    return n > 0 && !g_ascii_isdigit(v[n - 1]) && v[n - 1] != '.';
}

/* Checks a quantity flag in its unit (bare numbers in the old unit). */
static gboolean check_quantity(const char *v, const char *flag,
                               const char *bare, CfgUnitKind kind,
                               GError **err)
{
    if (!v)
        return TRUE;
    char *full = with_unit(v) ? g_strdup(v) : g_strconcat(v, bare, NULL);
    SimTime t;
    double d;
    gboolean ok = kind == CFG_UNIT_TIME
                      ? cfg_parse_time(full, flag, &t, err)
                      : cfg_parse_bandwidth(full, flag, &d, err);
    g_free(full);
    return ok;
}

/* The shorthand flags become --set overrides after the user's own. */
static GPtrArray *all_sets(const BenchNetOpts *o)
{
    GPtrArray *a = g_ptr_array_new_with_free_func(g_free);
    for (char **s = o->sets; s && *s; s++)
        g_ptr_array_add(a, g_strdup(*s));
    const char *keys[] = {"bandwidth", "startup", "per_hop"};
    const char *vals[] = {o->bandwidth, o->startup, o->per_hop};
    const char *bare[] = {"MB/s", "us", "us"};
    for (int i = 0; i < 3; i++)
        if (vals[i])
            g_ptr_array_add(a, g_strdup_printf(
                                   "machine.network.%s=%s%s", keys[i], vals[i],
                                   with_unit(vals[i]) ? "" : bare[i]));
    g_ptr_array_add(a, NULL);
    return a;
}

static gboolean check_opts(BenchNetOpts *o, BenchNetSpec *s, GError **err)
{
    if (!net_traffic_parse(o->pattern, &s->pattern))
        return input_error(err, o->pattern, net_traffic_words());
    if (o->nodes < 0 || o->seed < 0 || o->repeat < 1)
        return input_error(err,
                           "a negative --nodes or --seed, "
                           "or --repeat < 1",
                           "values >= 0 and --repeat >= 1");
    if (o->bytes_s) {
        char *full = with_unit(o->bytes_s) ? g_strdup(o->bytes_s)
                                            : g_strconcat(o->bytes_s, " B", NULL);
        gboolean ok = cfg_parse_size(full, "--bytes", &o->bytes, err);
        g_free(full);
        if (!ok)
            return FALSE;
    }
    if (!check_quantity(o->bandwidth, "--bandwidth", " MB/s",
                        CFG_UNIT_BANDWIDTH, err) ||
        !check_quantity(o->startup, "--startup", " us", CFG_UNIT_TIME, err) ||
        !check_quantity(o->per_hop, "--per-hop", " us", CFG_UNIT_TIME, err))
        return FALSE;
    s->machine = o->machine;
    s->nodes = (guint)o->nodes;
    s->bytes = o->bytes;
    s->seed = (uint64_t)o->seed;
    return TRUE;
}

static void print_row(NetFidelity f, const BenchNetRun *r,
                      const BenchNetRun *ref)
{
    double err =
        ref ? ((double)r->end - (double)ref->end) / (double)ref->end : 0.0;
    double wall = r->wall > 1e-6 ? r->wall : 1e-6;
    printf("%-9s %14.6f %+10.4f %10.4f %9.2f %10" G_GUINT64_FORMAT "\n",
           net_fidelity_name(f), sim_time_to_s(r->end), ref ? err : 0.0,
           r->wall, ref ? ref->wall / wall : 1.0, r->events);
}

/* K runs: the same simulated run each time (checked); the least wall. */
static gboolean run_best(const BenchNet *b, NetFidelity f, int k,
                         BenchNetRun *best, GError **err)
{
    BenchNetRun r;
    for (int i = 0; i < k; i++) {
        if (!bench_net_run(b, f, &r, err))
            return FALSE;
        g_assert(i == 0 || (r.end == best->end && r.events == best->events));
        if (i == 0 || r.wall < best->wall)
            *best = r;
    }
    return TRUE;
}

static int run_all(const BenchNet *b, const BenchNetOpts *o)
{
    NetFidelity order[3] = {NET_PACKET, NET_FLOW, NET_ANALYTIC}, only;
    gboolean all = strcmp(o->fidelity, "all") == 0;
    GError *err = NULL;
    if (!all && !net_fidelity_parse(o->fidelity, &only)) {
        input_error(&err, o->fidelity,
                    "--fidelity all, analytic, flow or "
                    "packet");
        return bench_fail(err);
    }
    printf("bench net: %s\n", bench_net_describe(b));
    printf("pattern %s, %" G_GUINT64_FORMAT " B, %" G_GUINT64_FORMAT
           " messages\n",
           o->pattern, o->bytes,
           net_traffic_messages(b->spec.pattern, bench_net_nodes(b)));
    printf("%-9s %14s %10s %10s %9s %10s\n", "fidelity", "sim_time_s",
           "rel_err", "wall_s", "speedup", "events");
    BenchNetRun ref = {0}, r = {0};
    for (int i = 0; i < 3; i++) {
        if (!all && order[i] != only)
            continue;
        if (!run_best(b, order[i], o->repeat, &r, &err))
            return bench_fail(err);
        gboolean is_ref = all && order[i] == NET_PACKET;
        print_row(order[i], &r, all && !is_ref ? &ref : NULL);
        if (is_ref)
            ref = r;
    }
    return 0;
}

int bench_net_main(int argc, char **argv)
{
    BenchNetOpts o = {.bytes = 1024, .seed = 1, .repeat = 1};
    BenchNetSpec s = {0};
    GError *err = NULL;
    BenchNet *b = NULL;
    GPtrArray *sets = NULL;
    gboolean ok = parse_opts(&o, &argc, &argv, &err);
    if (ok) {
        o.machine = o.machine ? o.machine : g_strdup("ipsc2");
        o.pattern = o.pattern ? o.pattern : g_strdup("all-to-all");
        o.fidelity = o.fidelity ? o.fidelity : g_strdup("all");
        ok = check_opts(&o, &s, &err);
    }
    if (ok) {
        sets = all_sets(&o);
        s.sets = (const char *const *)sets->pdata;
        b = bench_net_new(&s, &err);
    }
    int status = b ? run_all(b, &o) : bench_fail(err);
    bench_net_free(b);
    if (sets)
        g_ptr_array_free(sets, TRUE);
    g_free(o.machine);
    g_free(o.pattern);
    g_free(o.fidelity);
    g_free(o.bytes_s);
    g_free(o.bandwidth);
    g_free(o.startup);
    g_free(o.per_hop);
    g_strfreev(o.sets);
    return status;
}
