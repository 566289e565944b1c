/* test_model_values.c — mach_model_check() on one parameter at a time
 * (sim/machine/model.c): each type's unit rule (a value ending in a digit
 * or '.' or made of blanks has no unit; trailing blanks are ignored), list
 * values, provenance maps and bare values, the key tables of node kinds
 * and the network, with every refusal at its file:line:column. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/machine/model.h"
#include "tests/support.h"

/* A model whose node kind has `kind` extra keys and whose network has
 * `net` extra keys (YAML flow-map bodies on line 3 and 4). */
static char *check(const char *kind, const char *net)
{
    char *text = g_strdup_printf(
        "schema_version: 1\nname: t\n"
        "nodes: {node: {count: {value: 2, source: s}%s%s}}\n"
        "network: {topology: {value: ring, source: s}, bandwidth: "
        "{value: 1 MB/s, source: s}%s%s}\n",
        *kind ? ", " : "", kind, *net ? ", " : "", net);
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    assert_non_null(root);
    gboolean ok = mach_model_check(root, "m.yaml", &err);
    assert_true(ok == (err == NULL));
    char *msg = err ? g_strdup(err->message) : NULL;
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    return msg;
}

static void expect(const char *kind, const char *net, const char *want)
{
    char *msg = check(kind, net);
    if (g_strcmp0(msg, want) != 0)
        fail_msg("%s | %s:\n got '%s'\nwant '%s'", kind, net,
                 msg ? msg : "(accepted)", want ? want : "(accepted)");
    g_free(msg);
}

static void test_units(void **state)
{
    (void)state;
    expect("", "startup: {value: '5 us  ', source: s}", NULL);
    expect("", "startup: {value: '5 us', source: s}", NULL);
    expect("", "startup: {value: '  ', source: s}",
           "m.yaml:4:103: found '  ' without a unit, expected a time with its "
           "unit, e.g. '350 us'");
    expect("", "startup: {value: '5.', source: s}",
           "m.yaml:4:103: found '5.' without a unit, expected a time with its "
           "unit, e.g. '350 us'");
    expect("", "startup: {value: '5', source: s}",
           "m.yaml:4:103: found '5' without a unit, expected a time with its "
           "unit, e.g. '350 us'");
    expect("", "startup: {value: 5 ', source: s}",
           "m.yaml:4:103: found '5 '', expected a non-negative time with a "
           "unit (ps, ns, us, \xc2\xb5s, ms, s, min, h)");
    expect("clock: {value: 16, source: s}", "",
           "m.yaml:3:61: found '16' without a unit, expected a frequency with "
           "its unit, e.g. '16 MHz'");
    expect("memory: {value: 4, source: s}", "",
           "m.yaml:3:62: found '4' without a unit, expected a size with its "
           "unit, e.g. '4 MB'");
    expect("", "packet_size: {value: 64, source: s}",
           "m.yaml:4:107: found '64' without a unit, expected a size with its "
           "unit, e.g. '4 MB'");
    expect("", "level_bandwidth: {value: [1 MB/s, 2], source: s}",
           "m.yaml:4:120: found '2' without a unit, expected a bandwidth with "
           "its unit, e.g. '2.8 MB/s'");
    expect("", "level_bandwidth: {value: [], source: s}",
           "m.yaml:4:111: found a non-list value, expected a list of "
           "bandwidths, e.g. [20 MB/s, 10 MB/s]");
    expect("", "level_bandwidth: {value: 1 MB/s, source: s}",
           "m.yaml:4:111: found a non-list value, expected a list of "
           "bandwidths, e.g. [20 MB/s, 10 MB/s]");
    expect("", "extents: {value: [2], source: s}", NULL);
    expect("", "extents: {value: [2, x], source: s}",
           "m.yaml:4:107: found 'x', expected a non-negative integer, "
           "optionally with K (1e3) or M (1e6)");
    expect("", "channels: {value: 2x, source: s}",
           "m.yaml:4:104: found '2x', expected a non-negative integer, "
           "optionally with K (1e3) or M (1e6)");
    expect("", "switching: {value: [a], source: s}",
           "m.yaml:4:105: found a sequence, expected a string");
}

static void test_params_and_keys(void **state)
{
    (void)state;
    expect("", "startup: 5 us",
           "m.yaml:4:95: found bare value for 'startup', expected {value: ..., "
           "source|calibrated|assumption: ...} (or provenance: assumption at "
           "the top of your own model)");
    expect("", "startup: {source: s}",
           "m.yaml:4:95: found parameter 'startup' without a value, expected "
           "value: <number with unit>");
    expect("", "startup: {value: 5 us}",
           "m.yaml:4:95: found parameter 'startup' without a provenance, "
           "expected one of source:, calibrated: or assumption: (or, in your "
           "own model, provenance: assumption at the top)");
    expect("", "startup: {value: 5 us, source: ''}",
           "m.yaml:4:117: found an empty provenance, expected a citation or an "
           "explanation in words");
    expect("", "startup: {value: 5 us, calibrated: fit, note: n}", NULL);
    expect("", "startup: {value: 5 us, assumption: a}", NULL);
    expect(
        "", "wormhole: {value: 1, source: s}",
        "m.yaml:4:96: found unknown key 'wormhole', expected one of: topology, "
        "routing, switching, fidelity, duplex, bandwidth, total_bandwidth, "
        "aggregate_bandwidth, level_bandwidth, startup, startup_long, "
        "long_threshold, per_hop, word_time, router_cycle, control_latency, "
        "packet_size, channels, arity, dimension, extents, shapes, torus_min, "
        "node_size, node_bandwidth, node_ports, procs_per_router, "
        "router_nodes, router_link_bandwidth, news_bandwidth");
    expect("speed: {value: 1, source: s}", "",
           "m.yaml:3:53: found unknown key 'speed', expected one of: count, "
           "processor, clock, memory, lanes, lane_memory, fpa_lanes, cores, "
           "peak_flops, memory_bandwidth, costs, cycles");
    expect("costs: 5", "",
           "m.yaml:3:53: found a non-map costs section, expected a map of "
           "operation: {value: <time>, source: ...}");
    expect("costs: {op: 5 us}", "",
           "m.yaml:3:58: found bare value for 'op', expected {value: ..., "
           "source|calibrated|assumption: ...} (or provenance: assumption at "
           "the top of your own model)");
    expect("costs: {op: {value: 5, source: s}}", "",
           "m.yaml:3:66: found '5' without a unit, expected a time with its "
           "unit, e.g. '350 us'");
    expect("costs: {op: {value: 5 us, source: s}}", "", NULL);
    expect("lanes: {value: 64K, source: s}, cores: {value: 2, source: s}", "",
           NULL);
    expect("processor: {value: i860, source: s}", "", NULL);
    expect("",
           "aggregate_bandwidth: {value: 1 GB/s, source: s}, "
           "word_time: {value: 1 ns, source: s}, "
           "router_cycle: {value: 1 ns, source: s}, "
           "control_latency: {value: 1 us, source: s}, "
           "duplex: {value: full, source: s}",
           NULL);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_units),
        cmocka_unit_test(test_params_and_keys),
    };
    return cmocka_run_group_tests_name("model_values", tests, NULL, NULL);
}
