/* bench_phold.c — the PHOLD benchmark of the event engine.
 *
 * PHOLD (R. M. Fujimoto, "Performance of time warp under synthetic
 * workloads", Proc. SCS Multiconference on Distributed Simulation, 1990):
 * N logical processes start with M events each; every event, when run,
 * schedules one successor at now + lookahead + Exp(mean), sent to a
 * uniformly chosen LP with probability `remote` and to itself otherwise.
 * The population of pending events stays N x M, so the run measures the
 * engine's steady-state cost per event at that queue size.  Each LP draws
 * from its own stream (sim_entity_rng semantics, kept in the LP record).
 * Then the same hold loop with nothing but a bare implicit 4-ary min-heap
 * of times (the near-limit of a heap-based engine: no pool, no tie order,
 * no handler call; the same random draws per event) runs for as many
 * events, and the ratio engine / bare heap is printed.  Both sides are
 * timed in process CPU seconds (CLOCK_PROCESS_CPUTIME_ID): on the shared
 * machine wall time also counts the time other jobs held the core, which
 * moved the ratio by +-40 % between identical runs; wall_s is printed too.
 * Prints `events_per_s: <number>` (per CPU second) as its last line.
 */
#include "sim/app/bench/bench.h"
#include "sim/core/cfg.h"
#include "sim/core/engine.h"
#include "sim/core/evq.h"
#include "sim/core/memlimit.h"
#include "sim/core/rng.h"
#include <stdio.h>
#include <time.h>

/* Seconds of CPU this process has used. */
static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

typedef struct {
    SimRng rng;
    uint64_t events;
} PholdLp;

typedef struct {
    PholdLp *lps;
    uint64_t n_lps;
    double remote;
    SimTime lookahead;
    double mean_ps;
    uint64_t done, target;
} Phold;

static void phold_event(SimEngine *e, void *ctx, void *arg)
{
    Phold *ph = ctx;
    PholdLp *lp = arg;
    lp->events++;
    if (++ph->done >= ph->target) {
        sim_engine_stop(e);
        return;
    }
    PholdLp *dst = lp;
    if (sim_rng_uniform(&lp->rng) < ph->remote)
        dst = &ph->lps[sim_rng_below(&lp->rng, ph->n_lps)];
    SimTime d = ph->lookahead + (SimTime)sim_rng_exp(&lp->rng, ph->mean_ps);
    sim_schedule_in(e, d, phold_event, ph, dst);
}

static void phold_seed(SimEngine *e, Phold *ph, uint64_t per_lp)
{
    for (uint64_t i = 0; i < ph->n_lps; i++) {
        sim_rng_init(&ph->lps[i].rng, sim_engine_seed(e), i);
        for (uint64_t j = 0; j < per_lp; j++) {
            SimTime t = (SimTime)sim_rng_exp(&ph->lps[i].rng, ph->mean_ps);
            sim_schedule_at(e, t, phold_event, ph, &ph->lps[i]);
        }
    }
}

/* ---- the bare 4-ary heap hold loop ---- */

static void bare_sift_down(SimTime *h, size_t n, SimTime e)
{
    size_t i = 0;
    for (;;) {
        size_t c = 4 * i + 1, m = c;
        if (c >= n)
            break;
        for (size_t j = c + 1; j < c + 4 && j < n; j++)
            m = h[j] < h[m] ? j : m;
        if (h[m] >= e)
            break;
        h[i] = h[m];
        i = m;
    }
    h[i] = e;
}

static void bare_push(SimTime *h, size_t i, SimTime e)
{
    while (i > 0 && h[(i - 1) / 4] > e) {
        h[i] = h[(i - 1) / 4];
        i = (i - 1) / 4;
    }
    h[i] = e;
}

/* Events per second of the bare loop: pending times, `events` holds. */
static double bare_heap_rate(const Phold *ph, uint64_t pending, uint64_t seed)
{
    SimTime *h = g_new(SimTime, pending);
    SimRng rng;
    sim_rng_init(&rng, seed, 0);
    for (uint64_t i = 0; i < pending; i++)
        bare_push(h, i, (SimTime)sim_rng_exp(&rng, ph->mean_ps));
    volatile uint64_t sink = 0;
    double t0 = cpu_s();
    for (uint64_t k = 0; k < ph->target; k++) {
        if (sim_rng_uniform(&rng) < ph->remote)
            sink += sim_rng_below(&rng, ph->n_lps);
        SimTime d = ph->lookahead + (SimTime)sim_rng_exp(&rng, ph->mean_ps);
        bare_sift_down(h, pending, h[0] + d);
    }
    double cpu = cpu_s() - t0;
    (void)sink; /* read only to keep the draw in the loop (clang -Wall) */
    g_free(h);
    return (double)ph->target / cpu;
}

/* Bytes of one pending event in the engine (its queue keeps up to two
 * records per event while growing) and in the bare heap. */
#define PHOLD_EVENT_BYTES (2.0 * sizeof(SimEvKey) + sizeof(SimTime))

/* The LPs and n x m pending events (engine, then the bare heap) fit the
 * memory limit: checked before anything is allocated or seeded (doubles:
 * the product of two counts cannot wrap). */
static gboolean phold_fits(uint64_t n, uint64_t m, GError **err)
{
    double bytes = (double)n * sizeof(PholdLp) +
                   (double)n * (double)m * PHOLD_EVENT_BYTES;
    char *what = g_strdup_printf("%" G_GUINT64_FORMAT " LPs with %"
                                 G_GUINT64_FORMAT " pending events each",
                                 n, m);
    gboolean ok = sim_mem_check(bytes, "phold: --lps, --pending-per-lp",
                                what, err);
    g_free(what);
    return ok;
}

typedef struct {
    char *lps, *pending, *lookahead, *mean, *events;
    double remote;
    gint64 seed;
} PholdArgs;

static gboolean phold_parse(int *argc, char ***argv, PholdArgs *a, Phold *ph,
                            uint64_t *per_lp, GError **err)
{
    GOptionEntry entries[] = {
        {"lps", 0, 0, G_OPTION_ARG_STRING, &a->lps,
         "logical processes "
         "(default 1024; K and M suffixes)",
         "N"},
        {"pending-per-lp", 0, 0, G_OPTION_ARG_STRING, &a->pending,
         "initial events per LP (default 1)", "M"},
        {"remote", 0, 0, G_OPTION_ARG_DOUBLE, &a->remote,
         "probability an event goes to a random LP (default 0.25)", "P"},
        {"lookahead", 0, 0, G_OPTION_ARG_STRING, &a->lookahead,
         "minimum delay (default 1us)", "T"},
        {"mean", 0, 0, G_OPTION_ARG_STRING, &a->mean,
         "mean of the exponential extra delay (default 1us)", "T"},
        {"events", 0, 0, G_OPTION_ARG_STRING, &a->events,
         "events to run (default 10M)", "E"},
        {"seed", 0, 0, G_OPTION_ARG_INT64, &a->seed, "run seed", "S"},
        {NULL, 0, 0, 0, NULL, NULL, NULL}};
    if (!bench_parse_options("phold", "- PHOLD engine benchmark", entries, argc,
                             argv, err))
        return FALSE;
    uint64_t n = 1024, m = 1, ev = 10000000;
    SimTime la = SIM_US, mean = SIM_US;
    if ((a->lps && !cfg_parse_count(a->lps, "--lps", &n, err)) ||
        (a->pending &&
         !cfg_parse_count(a->pending, "--pending-per-lp", &m, err)) ||
        (a->lookahead &&
         !cfg_parse_time(a->lookahead, "--lookahead", &la, err)) ||
        (a->mean && !cfg_parse_time(a->mean, "--mean", &mean, err)) ||
        (a->events && !cfg_parse_count(a->events, "--events", &ev, err)))
        return FALSE;
    if (n == 0 || m == 0 || ev == 0 || !(a->remote >= 0 && a->remote <= 1) ||
        a->seed < 0) { /* NaN is outside [0, 1] too */
        g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                    "phold: found a zero count, a negative seed or --remote "
                    "outside [0, 1], expected --lps, --pending-per-lp and "
                    "--events >= 1");
        return FALSE;
    }
    if (!phold_fits(n, m, err))
        return FALSE;
    *ph = (Phold){.n_lps = n,
                  .remote = a->remote,
                  .lookahead = la,
                  .mean_ps = (double)mean,
                  .target = ev};
    *per_lp = m;
    return TRUE;
}

int bench_phold_main(int argc, char **argv)
{
    PholdArgs a = {.remote = 0.25, .seed = 1};
    Phold ph;
    uint64_t per_lp;
    GError *err = NULL;
    if (!phold_parse(&argc, &argv, &a, &ph, &per_lp, &err))
        return bench_fail(err);
    ph.lps = g_new0(PholdLp, ph.n_lps);
    SimEngine *e = sim_engine_new((uint64_t)a.seed);
    phold_seed(e, &ph, per_lp);
    gint64 t0 = g_get_monotonic_time();
    double c0 = cpu_s();
    gboolean ok = sim_engine_run(e, SIM_TIME_MAX, &err);
    double cpu = cpu_s() - c0;
    double wall = (double)(g_get_monotonic_time() - t0) * 1e-6;
    if (ok) {
        printf("phold: lps=%" G_GUINT64_FORMAT " pending=%" G_GUINT64_FORMAT
               " remote=%.3g lookahead=%.6gus\n",
               ph.n_lps, ph.n_lps * per_lp, ph.remote,
               sim_time_to_us(ph.lookahead));
        printf("events: %" G_GUINT64_FORMAT "\n", sim_engine_events(e));
        printf("sim_time_s: %.9g\n", sim_time_to_s(sim_now(e)));
        printf("wall_s: %.4f\n", wall);
        printf("cpu_s: %.4f\n", cpu);
        double rate = (double)sim_engine_events(e) / cpu;
        double bare = bare_heap_rate(&ph, ph.n_lps * per_lp, (uint64_t)a.seed);
        printf("bare_4ary_heap_events_per_s: %.0f\n", bare);
        printf("engine_over_bare_heap: %.2f\n", rate / bare);
        printf("events_per_s: %.0f\n", rate);
    }
    sim_engine_free(e);
    g_free(ph.lps);
    g_free(a.lps);
    g_free(a.pending);
    g_free(a.lookahead);
    g_free(a.mean);
    g_free(a.events);
    return ok ? 0 : bench_fail(err);
}
