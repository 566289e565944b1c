/* cmd_replay.c — `pgsim replay TRACE --machine MODEL [--nodes N]
 * [--map block|cyclic|FILE] [--fidelity F] [--set machine.K=V]...
 * [--clock KIND=HZ]... [--costs-from MODEL]
 * [--format text|json|csv] [--out DIR]`.
 *
 * Plays a trace (docs/traces.md) on a machine model and prints the same
 * report as `pgsim run` (rpt_render, docs/output.md).
 */
#include "sim/app/cli/cli.h"
#include "sim/app/cli/commands.h"
#include "sim/app/replay/rpl_replay.h"
#include "sim/app/run/report.h"
#include <string.h>

typedef struct {
    char **sets, **clocks;
    char *machine, *map, *fidelity, *format, *out, *costs_from;
    int nodes;
} ReplayOpts;

static const char summary[] =
    "Replays a trace recorded by `pgsim run --record` (or written by hand, "
    "docs/traces.md) on a machine model: work is priced from its cost "
    "table or scaled by its clocks, messages cross its network.  Prints "
    "the report of `pgsim run`.";

static int replay(const char *trace, const ReplayOpts *o)
{
    RptFormat fmt = RPT_TEXT;
    if (o->format && !rpt_format_parse(o->format, &fmt)) {
        fprintf(stderr, "pgsim replay: --format: found '%s', expected one of: "
                        "text, json, csv\n",
                o->format);
        return 2;
    }
    if (!o->machine || o->nodes < 0) {
        fprintf(stderr, o->machine ? "pgsim replay: --nodes: found %d, "
                                     "expected a positive count\n"
                                   : "pgsim replay: found no --machine, "
                                     "expected --machine MODEL%.0d\n",
                o->nodes);
        return 2;
    }
    RplReplayOpts ro = {.trace = trace,
                        .machine = o->machine,
                        .nodes = (guint)o->nodes,
                        .map = o->map,
                        .fidelity = o->fidelity,
                        .sets = (const char *const *)o->sets,
                        .clocks = (const char *const *)o->clocks,
                        .costs_from = o->costs_from};
    GError *e = NULL;
    SimResult *res = rpl_replay(&ro, &e);
    if (!res)
        return cli_fail(e);
    char *text = rpt_render(res, fmt, fmt == RPT_TEXT);
    fputs(text, stdout);
    g_free(text);
    int status = 0;
    if (o->out && !rpt_write_dir(res, o->out, FALSE, &e))
        status = cli_fail(e);
    sim_result_free(res);
    return status;
}

int cmd_replay(int argc, char **argv)
{
    ReplayOpts o = {0};
    const GOptionEntry entries[] = {
        {"machine", 0, 0, G_OPTION_ARG_STRING, &o.machine,
         "the machine model to replay on (models/MODEL.yaml)", "MODEL"},
        {"nodes", 0, 0, G_OPTION_ARG_INT, &o.nodes,
         "size the machine to N network endpoints (default: the model's)",
         "N"},
        {"map", 0, 0, G_OPTION_ARG_FILENAME, &o.map,
         "trace processors onto the machine: block (default), cyclic, or a "
         "file of 'TRACE_PROC TARGET_PROC' lines",
         "block|cyclic|FILE"},
        {"fidelity", 0, 0, G_OPTION_ARG_STRING, &o.fidelity,
         "network model: analytic, flow, packet or faithful (default: the "
         "fidelity the trace was recorded at, else faithful)",
         "F"},
        {"set", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o.sets,
         "override a machine key (repeatable)", "machine.KEY=VALUE"},
        {"clock", 0, 0, G_OPTION_ARG_STRING_ARRAY, &o.clocks,
         "assume the trace's KIND ran at this clock when recorded (for kinds "
         "the trace gives none; repeatable)",
         "KIND=HZ"},
        {"costs-from", 0, 0, G_OPTION_ARG_STRING, &o.costs_from,
         "price operations the target's cost table lacks from this model's, "
         "scaled by its clock / the target's (an assumption)",
         "MODEL"},
        {"format", 0, 0, G_OPTION_ARG_STRING, &o.format,
         "report on stdout: text (default), json or csv", "FMT"},
        {"out", 0, 0, G_OPTION_ARG_FILENAME, &o.out,
         "also write summary.txt, result.json and result.csv into DIR",
         "DIR"},
        G_OPTION_ENTRY_NULL,
    };
    int status;
    if (cli_parse("replay", "TRACE", summary, entries, &argc, &argv, &status))
        status = cli_want_args("replay", "TRACE", argc, argv, 1)
                     ? replay(argv[1], &o)
                     : 2;
    g_strfreev(o.sets);
    g_strfreev(o.clocks);
    g_free(o.machine);
    g_free(o.map);
    g_free(o.fidelity);
    g_free(o.format);
    g_free(o.out);
    g_free(o.costs_from);
    return status;
}
