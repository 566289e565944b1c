/* cmd_bench.c — `pgsim bench NAME [options]`: dispatch to benchmarks. */
#include "sim/app/bench/bench.h"
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/core/error.h"
#include <stdio.h>
#include <string.h>

typedef struct {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *summary;
} BenchEntry;

static const BenchEntry benches[] = {
    {"phold", bench_phold_main, "PHOLD: events/s of the event engine"},
    {"net", bench_net_main, "network fidelities: speed against error"},
    {"raster", bench_raster_main, "rendering: triangles/s, pixels/s"},
    {"composite", bench_composite_main,
     "compositing image rungs: speed against error"},
    {NULL, NULL, NULL},
};

static void bench_usage(FILE *f)
{
    fprintf(f, "usage: pgsim bench NAME [options]   (NAME --help for "
               "options)\n\nbenchmarks:\n");
    for (int i = 0; benches[i].name; i++)
        fprintf(f, "  %-8s %s\n", benches[i].name, benches[i].summary);
}

gboolean bench_parse_options(const char *name, const char *summary,
                             GOptionEntry *entries, int *argc, char ***argv,
                             GError **err)
{
    char *title = g_strdup_printf("%s %s", name, summary);
    GOptionContext *ctx = g_option_context_new(title);
    g_option_context_add_main_entries(ctx, entries, NULL);
    cli_add_common(ctx); /* --mem-limit */
    GError *e = NULL;
    gboolean ok = g_option_context_parse(ctx, argc, argv, &e);
    if (ok && *argc > 1) {
        g_set_error(&e, SIM_ERROR, SIM_ERROR_INPUT,
                    "bench %s: found unexpected argument '%s', expected "
                    "options only",
                    name, (*argv)[1]);
        ok = FALSE;
    } else if (!ok) {
        e->domain = SIM_ERROR;
        e->code = SIM_ERROR_INPUT;
    }
    if (!ok)
        g_propagate_error(err, e);
    g_option_context_free(ctx);
    g_free(title);
    return ok;
}

int bench_fail(GError *err)
{
    int status = sim_error_exit_status(err);
    fprintf(stderr, "pgsim: %s\n", err->message);
    g_error_free(err);
    return status;
}

int cmd_bench(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "-h") == 0) {
        bench_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    for (int i = 0; benches[i].name; i++)
        if (strcmp(argv[1], benches[i].name) == 0)
            return benches[i].fn(argc - 1, argv + 1);
    fprintf(stderr,
            "pgsim bench: found '%s', expected one of the "
            "benchmarks below\n",
            argv[1]);
    bench_usage(stderr);
    return 2;
}
