/* test_machine_edges.c — the error paths and boundaries of sim/machine
 * that mutation testing (make mutate, docs/testing.md) showed no test
 * reached: every located rejection of model.c's checker (message and
 * line:column checked), the network builder's refusals (mnet.c), model
 * names, partitions of a SIMD machine whose widest kind comes first, and
 * the idle count of processors never touched (machine.c fill_kind). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <glib/gstdio.h>

#include "sim/machine/machine.h"
#include "sim/machine/mnet.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include "tests/support.h"

/* A model's lines after the header; "m.yaml" is its file name. */
#define HEAD "schema_version: 1\nname: t\n"
#define NODES "nodes: {cpu: {count: {value: 4, source: s}}}\n"
#define NET_OK "network: {topology: {value: ring, source: s}}\n"

static void fail_unless(const char *msg, const char *prefix, const char *needle)
{
    if (!g_str_has_prefix(msg, prefix) || !strstr(msg, needle))
        fail_msg("got '%s', want prefix '%s' and '%s'", msg, prefix, needle);
}

/* The model text is refused at line:col with a message holding needle. */
static void bad(const char *text, int line, int col, const char *needle)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    if (!root)
        fail_msg("not YAML: %s", err->message);
    gboolean ok = mach_model_check(root, "m.yaml", &err);
    if (ok)
        fail_msg("accepted: %s (err %s)", text, err ? err->message : "none");
    assert_non_null(err);
    char *loc = g_strdup_printf("m.yaml:%d:%d: found ", line, col);
    fail_unless(err->message, loc, needle);
    g_free(loc);
    g_error_free(err);
    cfg_free(root);
}

static void good(const char *text)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "m.yaml", &err);
    assert_non_null(root);
    if (!mach_model_check(root, "m.yaml", &err))
        fail_msg("refused: %s", err->message);
    assert_null(err);
    cfg_free(root);
}

/* Every value type's error names its own example. */
static void test_type_examples(void **state)
{
    (void)state;
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: 5, source: s}}\n",
        5, 20, "'5' without a unit, expected a time with its unit");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  bandwidth: {value: 5, source: s}}\n",
        5, 22, "expected a bandwidth with its unit");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s},\n"
             "  clock: {value: 16, source: s}}}\n" NET_OK,
        4, 18, "expected a frequency with its unit");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s},\n"
             "  memory: {value: 4, source: s}}}\n" NET_OK,
        4, 19, "expected a size with its unit, e.g. '4 MB'");
    bad(HEAD NODES "network: {topology: {value: fat-tree, source: s},\n"
                   "  level_bandwidth: {value: 2 MB/s, source: s}}\n",
        5, 28, "found a non-list value, expected a list of bandwidths");
    bad(HEAD NODES "network: {topology: {value: mesh, source: s},\n"
                   "  extents: {value: 4, source: s}}\n",
        5, 20, "found a non-list value, expected a list of counts");
    bad(HEAD NODES "network: {topology: {value: mesh, source: s},\n"
                   "  extents: {value: [], source: s}}\n",
        5, 20, "a list of counts");
    bad(HEAD NODES "network: {topology: {value: fat-tree, source: s},\n"
                   "  level_bandwidth: {value: [2 MB/s, 3], source: s}}\n",
        5, 37, "'3' without a unit, expected a bandwidth");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: [1 us], source: s}}\n",
        5, 20, "a non-scalar value, expected a time");
}

/* A unit is the last non-blank character not being a digit or '.'. */
static void test_units_required(void **state)
{
    (void)state;
    good(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                    "  startup: {value: 5us, source: s}}\n");
    good(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                    "  startup: {value: 5 s, source: s}}\n");
    good(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                    "  startup: {value: \"5 us  \", source: s}}\n");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: \"5.\", source: s}}\n",
        5, 20, "'5.' without a unit");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: \"5  \", source: s}}\n",
        5, 20, "without a unit");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: \"\", source: s}}\n",
        5, 20, "without a unit");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: \"  \", source: s}}\n",
        5, 20, "without a unit");
    /* a single letter ends in no digit: it has a "unit", then fails to
     * parse as a time */
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: x, source: s}}\n",
        5, 20, "found 'x', expected a non-negative time");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: \"7\", source: s}}\n",
        5, 20, "'7' without a unit");
    /* the unit is there but does not parse as a time */
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: 5 MB, source: s}}\n",
        5, 20, "5 MB");
}

/* Each check of the tree refuses at the node at fault. */
static void test_sections_refused(void **state)
{
    (void)state;
    bad("- a\n- b\n", 1, 1, "a non-map document");
    bad(HEAD NET_OK, 1, 1, "no nodes section, expected both nodes:");
    bad(HEAD NODES, 1, 1, "no network section");
    bad(HEAD "nodes: []\n" NET_OK, 3, 8, "an empty or non-map nodes section");
    bad(HEAD "nodes: {}\n" NET_OK, 3, 8, "an empty or non-map nodes");
    bad(HEAD "nodes: {cpu: 3}\n" NET_OK, 3, 14, "a non-map node kind");
    bad(HEAD "nodes: {cpu: {clock: {value: 1 MHz, source: s}}}\n" NET_OK, 3,
        14, "a node kind without count");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s}, hue: 3}}\n" NET_OK,
        3, 50, "unknown key 'hue', expected one of: count, processor");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s}, hue: 3}}\n" NET_OK,
        3, 50, "memory_bandwidth, costs, cycles");
    bad(HEAD "nodes: {cpu: {count: {value: 4}}}\n" NET_OK, 3, 22,
        "parameter 'count' without a provenance");
    bad(HEAD "nodes: {cpu: {count: {source: s}}}\n" NET_OK, 3, 22,
        "parameter 'count' without a value");
    bad(HEAD "nodes: {cpu: {count: {value: 4, calibrated: \"\"}}}\n" NET_OK,
        3, 45, "an empty provenance");
    bad(HEAD "nodes: {cpu: {count: {value: 4, assumption: [a]}}}\n" NET_OK,
        3, 45, "an empty provenance");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s},\n"
             "  costs: {op: {value: 1 us, source: s}, op2: 3 us}}}\n" NET_OK,
        4, 46, "bare value for 'op2'");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s},\n"
             "  costs: {op: {value: 1, source: s}}}}\n" NET_OK,
        4, 23, "'1' without a unit");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s}},\n"
             "  gpu: {count: {value: x, source: s}}}\n" NET_OK,
        4, 24, "x");
    bad(HEAD NODES "network: [1]\n", 4, 10, "a network section without "
                                           "topology");
    bad(HEAD NODES "network: {bandwidth: {value: 1 MB/s, source: s}}\n", 4, 10,
        "a network section without topology");
    bad(HEAD NODES "network: {topology: {value: ring, source: s}, hops: 1}\n",
        4, 53, "unknown key 'hops', expected one of: topology, routing");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  channels: 2}\n",
        5, 13, "bare value for 'channels'");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  channels: {value: 2}}\n",
        5, 13, "parameter 'channels' without a provenance");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  channels: {value: two, source: s}}\n",
        5, 21, "two");
    bad(HEAD NODES NET_OK "extra: 3\n", 5, 8, "a non-map top-level section");
    bad(HEAD NODES NET_OK "wl: {k: 3}\n", 5, 9,
        "workload parameter 'k' without a value");
    bad(HEAD NODES NET_OK "wl: {k: {value: 1, source: []}}\n", 5, 28,
        "an empty provenance, expected a citation, an explanation");
    bad(HEAD NODES NET_OK "wl: {k: {value: 1, note: n}}\n", 5, 9,
        "parameter 'k' without a provenance");
    bad(HEAD NODES NET_OK "wl: {a: {value: 1, source: s}, k: {value: 1}}\n", 5,
        35, "parameter 'k' without a provenance");
    good(HEAD NODES NET_OK "wl: {a: {value: 1, source: s}, k: {value: 1, "
                           "assumption: [x]}}\n");
    bad(HEAD "references: [a]\n" NODES NET_OK, 3, 13,
        "a non-map references section");
    bad(HEAD "references: {a: x, b: [1]}\n" NODES NET_OK, 3, 23, "found");
    bad(HEAD "references: {b: [1], a: x}\n" NODES NET_OK, 3, 17, "found a sequence");
    good(HEAD "references: {a: x, b: y}\ndescription: d\nmodel: m\n" NODES
             NET_OK);
    bad(HEAD "description: [d]\n" NODES NET_OK, 3, 14, "found");
    bad("schema_version: 1\n" NODES NET_OK, 1, 1, "'name'");
    bad("schema_version: 2\nname: t\n" NODES NET_OK, 1, 17, "found");
}

/* A later error after an accepted key still fails the whole check. */
static void test_later_keys_checked(void **state)
{
    (void)state;
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s}},\n"
             "  gpu: {count: {value: 4, source: s}, clock: 3}}\n" NET_OK,
        4, 46, "bare value for 'clock'");
    bad(HEAD "nodes: {cpu: {count: {value: 4, source: s}},\n"
             "  gpu: [1]}\n" NET_OK,
        4, 8, "a non-map node kind");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: 1 us, source: s},\n"
                   "  per_hop: {value: 1, source: s}}\n",
        6, 20, "'1' without a unit");
    bad(HEAD NODES "network: {topology: {value: ring, source: s},\n"
                   "  startup: {value: 1 us, source: s}, bogus: 1}\n",
        5, 45, "unknown key 'bogus'");
    bad(HEAD NODES NET_OK "wl: {a: {value: 1, source: s}}\nwm: 4\n", 6, 5,
        "a non-map top-level section");
    bad(HEAD NODES NET_OK "stray: {a: {value: 1, source: s}}\n"
                          "wl: {k: {value: 1, source: \"\"}}\n",
        6, 28, "an empty provenance");
}

/* Plain names pass the name check (then are not found); others fail it. */
static void expect_name(const char *name, gboolean plain)
{
    GError *err = NULL;
    char *p = mach_model_path(name, &err);
    assert_null(p);
    assert_non_null(err);
    const char *want = plain ? "found no model" : "expected a plain name";
    if (!strstr(err->message, want))
        fail_msg("'%s': got '%s', want '%s'", name, err->message, want);
    g_error_free(err);
}

static void test_model_names(void **state)
{
    (void)state;
    expect_name("no_such", TRUE);
    expect_name("no-such", TRUE);
    expect_name("no.such", TRUE);
    expect_name("No9", TRUE);
    expect_name("x", TRUE);
    expect_name("_x", TRUE);
    expect_name("", FALSE);
    expect_name(NULL, FALSE);
    expect_name(".x", FALSE);
    expect_name("a/b", FALSE);
    expect_name("a b", FALSE);
    expect_name("ab!", FALSE);
    expect_name("+", FALSE);
}

/* An inline machine (no model:) of the given sections, built. */
static MachMachine *inline_machine(SimEngine *eng, const char *body,
                                   CfgNode **root, GError **err)
{
    char *text = g_strconcat("machine:\n  provenance: assumption\n  name: t\n", body, NULL);
    *root = cfg_load_string(text, "run.yaml", err);
    g_free(text);
    assert_non_null(*root);
    return mach_new_from_cfg(eng, cfg_get(*root, "machine"), "analytic", err);
}

/* The machine refuses the network at the node at fault (run.yaml). */
static void bad_net(const char *body, int line, int col, const char *needle)
{
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = inline_machine(eng, body, &root, &err);
    if (m)
        fail_msg("built: %s", body);
    assert_non_null(err);
    char *loc = g_strdup_printf("run.yaml:%d:%d: found ", line, col);
    fail_unless(err->message, loc, needle);
    g_free(loc);
    g_error_free(err);
    cfg_free(root);
    sim_engine_free(eng);
}

/* Builds, and the network has n nodes; returns its params' channels. */
static void good_net(const char *body, guint n, NetParams *par)
{
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = inline_machine(eng, body, &root, &err);
    if (!m)
        fail_msg("%s: %s", body, err->message);
    assert_non_null(mach_net(m));
    assert_int_equal(net_nodes(mach_net(m)), n);
    if (par)
        *par = *net_params(mach_net(m));
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

#define CPU4 "  nodes: {cpu: {count: 4}}\n"

static void test_net_params_refused(void **state)
{
    (void)state;
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                 "channels: 0}\n",
            5, 12, "found zero channels, expected channels >= 1");
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                 "channels: 4294967296}\n",
            5, 12, "an oversized channel/packet");
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                 "packet_size: 4294967296 B}\n",
            5, 12, "an oversized channel/packet");
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                 "switching: wormhole}\n",
            5, 59, "switching 'wormhole', expected circuit, cut-through");
    bad_net(CPU4 "  network: {topology: ring}\n", 5, 12,
            "a network without a usable bandwidth");
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 0 MB/s}\n", 5, 12,
            "a network without a usable bandwidth");
    bad_net(CPU4 "  network: {topology: fat-tree, arity: 2, level_bandwidth: "
                 "[1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, "
                 "1 MB/s, 1 MB/s]}\n",
            5, 60, "more levels than sim/net supports");
    NetParams eight;
    good_net(CPU4 "  network: {topology: fat-tree, arity: 2, level_bandwidth: "
                  "[1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, "
                  "8 MB/s]}\n",
             4, &eight);
    assert_true(eight.level_bw[7] == 8e6 && eight.bandwidth == 1e6);
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                 "startup_long: 1 ms}\n",
            5, 62, "startup_long without long_threshold");
    bad_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                 "long_threshold: 1 KB}\n",
            5, 64, "long_threshold without startup_long");
}

/* Bandwidth preference, switching defaults and what channels divide. */
static void test_net_params_read(void **state)
{
    (void)state;
    NetParams p;
    good_net(CPU4 "  network: {topology: ring, total_bandwidth: 8 MB/s, "
                  "channels: 4}\n",
             4, &p);
    assert_int_equal(p.channels, 4);
    assert_true(p.bandwidth == 2e6);
    assert_int_equal(p.switching, NET_SW_RING_SLOTS);
    good_net(CPU4 "  network: {topology: ring, total_bandwidth: 8 MB/s, "
                  "channels: 1, bandwidth: 3 MB/s}\n",
             4, &p);
    assert_true(p.bandwidth == 3e6);
    good_net(CPU4 "  network: {topology: fat-tree, arity: 2, "
                  "level_bandwidth: [5 MB/s, 7 MB/s]}\n",
             4, &p);
    assert_true(p.bandwidth == 5e6);
    assert_true(p.level_bw[0] == 5e6 && p.level_bw[1] == 7e6);
    assert_int_equal(p.switching, NET_SW_CUT_THROUGH);
    good_net(CPU4 "  network: {topology: fat-tree, arity: 2, level_bandwidth: "
                  "[1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, 1 MB/s, "
                  "8 MB/s]}\n",
             4, &p);
    assert_true(p.level_bw[7] == 8e6);
    static const char *const sw[] = {"circuit", "cut-through",
                                     "store-and-forward", "ring-slots"};
    static const NetSwitching want[] = {NET_SW_CIRCUIT, NET_SW_CUT_THROUGH,
                                        NET_SW_STORE_FORWARD,
                                        NET_SW_RING_SLOTS};
    for (guint i = 0; i < G_N_ELEMENTS(sw); i++) {
        char *b = g_strdup_printf(CPU4 "  network: {topology: hypercube, "
                                       "bandwidth: 1 MB/s, switching: %s, "
                                       "packet_size: 1 KB, channels: "
                                       "4294967295}\n",
                                  sw[i]);
        good_net(b, 4, &p);
        assert_int_equal(p.switching, want[i]);
        assert_int_equal(p.packet_bytes, 1000);
        assert_int_equal(p.channels, 4294967295u);
        g_free(b);
    }
    good_net(CPU4 "  network: {topology: ring, bandwidth: 1 MB/s, "
                  "startup: 2 us, per_hop: 3 us, startup_long: 9 us, "
                  "long_threshold: 2 KB}\n",
             4, &p);
    assert_int_equal(p.startup, 2 * SIM_US);
    assert_int_equal(p.per_hop, 3 * SIM_US);
    assert_int_equal(p.startup_long, 9 * SIM_US);
    assert_int_equal(p.long_threshold, 2000);
}

/* The topology builders' refusals, each at the count or the key. */
static void test_topologies_refused(void **state)
{
    (void)state;
    bad_net("  nodes: {cpu: {count: 6}}\n  network: {topology: hypercube, "
            "bandwidth: 1 MB/s}\n",
            4, 24, "6 processors on a hypercube, expected a power of two");
    bad_net(CPU4 "  network: {topology: hypercube, bandwidth: 1 MB/s, "
                 "dimension: 3}\n",
            4, 24, "4 processors on a hypercube");
    good_net(CPU4 "  network: {topology: hypercube, bandwidth: 1 MB/s, "
                  "dimension: 2}\n",
             4, NULL);
    bad_net("  nodes: {cpu: {count: 0}}\n  network: {topology: hypercube, "
            "bandwidth: 1 MB/s}\n",
            4, 24, "0 processors on a hypercube");
    good_net("  nodes: {cpu: {count: 1}}\n  network: {topology: hypercube, "
             "bandwidth: 1 MB/s}\n",
             1, NULL);
    bad_net("  nodes: {cpu: {count: 1}}\n  network: {topology: ring, "
            "bandwidth: 1 MB/s}\n",
            4, 24, "fewer than 2 stations on a ring");
    good_net("  nodes: {cpu: {count: 2}}\n  network: {topology: ring, "
             "bandwidth: 1 MB/s}\n",
             2, NULL);
    bad_net(CPU4 "  network: {topology: fat-tree, bandwidth: 1 MB/s}\n", 5,
            12, "no parameter 'arity'");
    bad_net(CPU4 "  network: {topology: fat-tree, bandwidth: 1 MB/s, "
                 "arity: 1}\n",
            5, 59, "an unusable fat-tree arity");
    good_net(CPU4 "  network: {topology: fat-tree, bandwidth: 1 MB/s, "
                  "arity: 2}\n",
             4, NULL);
    bad_net("  nodes: {cpu: {count: 1}}\n  network: {topology: fat-tree, "
            "bandwidth: 1 MB/s, arity: 4}\n",
            4, 24, "fewer than 2 leaves");
    good_net("  nodes: {cpu: {count: 2}}\n  network: {topology: fat-tree, "
             "bandwidth: 1 MB/s, arity: 4}\n",
             2, NULL);
    bad_net(CPU4 "  network: {topology: mesh, bandwidth: 1 MB/s, "
                 "extents: [2, 3]}\n",
            4, 24, "4 processors on a mesh of 6 nodes, expected the product");
    bad_net(CPU4 "  network: {topology: mesh, bandwidth: 1 MB/s, "
                 "extents: [1, 1, 2, 2]}\n",
            5, 57, "unusable mesh extents, expected 1 to 3 extents");
    bad_net(CPU4 "  network: {topology: torus, bandwidth: 1 MB/s, "
                 "extents: [4, 0]}\n",
            5, 58, "unusable mesh extents");
    bad_net("  nodes: {cpu: {count: 16777217}}\n  network: {topology: mesh, "
            "bandwidth: 1 MB/s, extents: [16777217]}\n",
            4, 24, "more than 16M processors");
    good_net(CPU4 "  network: {topology: torus, bandwidth: 1 MB/s, "
                  "extents: [1, 4, 1]}\n",
             4, NULL);
    good_net(CPU4 "  network: {topology: mesh, bandwidth: 1 MB/s, "
                  "extents: [4]}\n",
             4, NULL);
    good_net(CPU4 "  network: {topology: crossbar, bandwidth: 1 MB/s}\n", 4,
             NULL);
    good_net(CPU4 "  network: {topology: bus, bandwidth: 1 MB/s}\n", 4, NULL);
}

#define SIMD(lanes, group, routers)                                            \
    "  nodes: {array: {count: 1, lanes: " lanes "}, fe: {count: 1}}\n"          \
    "  network: {topology: cm-router, bandwidth: 1 MB/s, "                     \
    "procs_per_router: " group routers "}\n"

static void test_cm_router(void **state)
{
    (void)state;
    good_net(SIMD("64", "16", ", router_nodes: 4"), 64, NULL);
    good_net(SIMD("16", "16", ""), 16, NULL);
    bad_net(SIMD("64", "16", ", router_nodes: 8"), 4, 36,
            "64 lanes for router_nodes x procs_per_router");
    bad_net(SIMD("64", "0", ""), 4, 36, "64 lanes for router_nodes");
    bad_net(SIMD("48", "16", ""), 4, 36, "48 lanes");
    bad_net(SIMD("40", "8", ""), 4, 36, "40 lanes");
    bad_net(SIMD("0", "16", ""), 4, 36, "zero lanes");
    /* two kinds equally widest: the first one's lanes are the endpoints */
    bad_net("  nodes: {array: {count: 1, lanes: 48}, b: {count: 1, lanes: "
            "48}, fe: {count: 1}}\n  network: {topology: cm-router, "
            "bandwidth: 1 MB/s, procs_per_router: 16}\n",
            4, 36, "48 lanes");
    bad_net("  nodes: {array: {count: 1, lanes: 64}}\n  network: {topology: "
            "cm-router, bandwidth: 1 MB/s}\n",
            5, 12, "no parameter 'procs_per_router'");
}

/* The partition of a SIMD machine resizes its widest kind, even when
 * that kind comes first in the model. */
static void test_partition_lanes_first_kind(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine:\n  provenance: assumption\n  name: t\n" SIMD("64", "16", ", "
                                                               "router_nodes: "
                                                               "4"),
        "run.yaml", &err);
    char *desc = NULL;
    if (!mach_partition(root, 32, &desc, &err))
        fail_msg("%s", err->message);
    assert_string_equal(desc, "array lanes 32 = 2 routers x 16");
    assert_string_equal(cfg_scalar(cfg_path(root, "machine.nodes.array.lanes")),
                        "32");
    assert_string_equal(
        cfg_scalar(cfg_path(root, "machine.network.router_nodes")), "2");
    g_free(desc);
    desc = NULL;
    assert_false(mach_partition(root, 48, &desc, &err));
    assert_null(desc);
    assert_string_equal(err->message, "found 48 lanes for a cm-router of 16 "
                                      "per router, expected procs_per_router "
                                      "x a power of two");
    g_clear_error(&err);
    assert_false(mach_partition(root, 8, NULL, &err));
    assert_non_null(strstr(err->message, "8 lanes"));
    g_clear_error(&err);
    assert_true(mach_partition(root, 16, NULL, &err));
    assert_string_equal(
        cfg_scalar(cfg_path(root, "machine.network.router_nodes")), "1");
    cfg_free(root);
    root = cfg_load_string("other: 1\n", "run.yaml", &err);
    assert_false(mach_partition(root, 4, &desc, &err));
    assert_string_equal(err->message, "found a config without machine:, "
                                      "expected machine: {model: NAME}");
    g_clear_error(&err);
    cfg_free(root);
}

static void count_idle(const MachMachine *m, const char *kind, uint64_t *n)
{
    SimResult *r = sim_result_new("w", "m");
    mach_fill_result(m, r);
    *n = 0;
    for (guint i = 0; i < r->idle->len; i++) {
        const SimIdleResult *e = g_ptr_array_index(r->idle, i);
        if (strcmp(e->kind, kind) == 0)
            *n = e->count;
    }
    assert_int_equal(sim_result_n_idle(r) + r->nodes->len,
                     mach_proc_total(m));
    sim_result_free(r);
}

/* Idle processors are counted whether their page was ever made or not:
 * 3 + 200 processors, the page of 64 holding processor 100 made. */
static void test_idle_counts(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = inline_machine(
        eng, "  nodes: {host: {count: 3}, cpu: {count: 200}}\n"
             "  network: {topology: bus, bandwidth: 1 MB/s}\n",
        &root, &err);
    assert_non_null(m);
    uint64_t n;
    count_idle(m, "cpu", &n);
    assert_int_equal(n, 200);
    mach_proc_compute(mach_proc(m, "cpu", 100), SIM_US, 0, NULL, NULL, NULL);
    mach_proc_compute(mach_proc(m, "cpu", 199), SIM_US, 0, NULL, NULL, NULL);
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    count_idle(m, "cpu", &n);
    assert_int_equal(n, 198);
    count_idle(m, "host", &n);
    assert_int_equal(n, 3);
    SimResult *r = sim_result_new("w", "m");
    mach_fill_result(m, r);
    assert_int_equal(r->nodes->len, 2);
    const SimNodeResult *a = g_ptr_array_index(r->nodes, 0);
    const SimNodeResult *b = g_ptr_array_index(r->nodes, 1);
    assert_string_equal(a->name, "cpu100");
    assert_string_equal(b->name, "cpu199");
    sim_result_free(r);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}


/* Runs fn with stderr sent to a file; returns what it wrote (g_free). */
static char *capture_stderr(void (*fn)(void *), void *arg)
{
    char *path = NULL;
    int fd = g_file_open_tmp("pgsim-stderr-XXXXXX", &path, NULL);
    assert_true(fd >= 0);
    fflush(stderr);
    int saved = dup(2);
    dup2(fd, 2);
    fn(arg);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    close(fd);
    char *text = NULL;
    assert_true(g_file_get_contents(path, &text, NULL, NULL));
    g_unlink(path);
    g_free(path);
    return text;
}

static void check_text(void *arg)
{
    const char *const *a = arg; /* text, file name */
    GError *err = NULL;
    CfgNode *root = cfg_load_string(a[0], a[1] ? a[1] : "x.yaml", &err);
    assert_non_null(root);
    if (!mach_model_check(root, a[1], &err))
        fail_msg("%s", err->message);
    cfg_free(root);
}

/* provenance: assumption warns once per model file, listing the values
 * taken without a source; a model whose values all have one is silent;
 * a model given without a file name is never taken as shipped. */
static void test_assumption_warning(void **state)
{
    (void)state;
    const char *all_sourced[] = {"provenance: assumption\n" HEAD NODES NET_OK,
                                 "sourced.yaml"};
    char *out = capture_stderr(check_text, all_sourced);
    assert_string_equal(out, "");
    g_free(out);
    const char *two[] = {"provenance: assumption\n" HEAD
                         "nodes: {cpu: {count: 4}}\n"
                         "network: {topology: ring, bandwidth: {value: 1 "
                         "MB/s, source: s}}\n",
                         "two.yaml"};
    out = capture_stderr(check_text, two);
    assert_string_equal(out, "pgsim: warning: two.yaml: 2 values without a "
                             "source, taken as assumptions (provenance: "
                             "assumption): count, topology\n");
    g_free(out);
    out = capture_stderr(check_text, two); /* once per file */
    assert_string_equal(out, "");
    g_free(out);
    const char *inl[] = {two[0], NULL};
    out = capture_stderr(check_text, inl);
    assert_non_null(strstr(out, "warning: <inline machine>: 2 values"));
    g_free(out);
}

/* The typed getters on a tree the checker never saw. */
static void test_getters_unchecked(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "a: [[1]]\nb: {value: 3 MB/s}\nc: [2, 3]\nd: {value: [1 MB/s, x]}\n"
        "e: 5\nf: {value: 4, source: s}\n",
        "u.yaml", &err);
    GArray *l = NULL;
    assert_false(mach_param_bw_list(root, "a", TRUE, &l, &err));
    assert_string_equal(err->message, "u.yaml:1:5: found a non-scalar list "
                                      "item, expected a bandwidth");
    g_clear_error(&err);
    assert_false(mach_param_count_list(root, "a", TRUE, &l, &err));
    assert_string_equal(err->message, "u.yaml:1:5: found a non-scalar list "
                                      "item, expected a count");
    g_clear_error(&err);
    assert_false(mach_param_bw_list(root, "b", TRUE, &l, &err));
    assert_string_equal(err->message,
                        "u.yaml:2:12: found a non-list value, expected a "
                        "list of bandwidths, e.g. [20 MB/s, 10 MB/s]");
    g_clear_error(&err);
    assert_false(mach_param_count_list(root, "e", TRUE, &l, &err));
    assert_non_null(strstr(err->message, "u.yaml:5:4: found a non-list value, "
                                         "expected a list of counts"));
    g_clear_error(&err);
    assert_false(mach_param_bw_list(root, "d", TRUE, &l, &err));
    assert_non_null(strstr(err->message, "x"));
    g_clear_error(&err);
    assert_null(l);
    assert_true(mach_param_count_list(root, "c", TRUE, &l, &err));
    assert_int_equal(l->len, 2);
    assert_int_equal(g_array_index(l, uint64_t, 1), 3);
    g_array_unref(l);
    l = NULL;
    assert_true(mach_param_count_list(root, "zz", FALSE, &l, &err));
    assert_null(l);
    assert_false(mach_param_count_list(root, "zz", TRUE, &l, &err));
    assert_string_equal(err->message, "u.yaml:1:1: found no parameter 'zz', "
                                      "expected it in the machine model");
    g_clear_error(&err);
    double bw = 0;
    assert_true(mach_param_bandwidth(root, "b", TRUE, &bw, &err));
    assert_true(bw == 3e6);
    /* a map without a provenance of its own: an override */
    assert_int_equal(mach_param_provenance(root, "b", NULL), MACH_PROV_OVERRIDE);
    const char *text = "x";
    assert_int_equal(mach_param_provenance(root, "e", &text),
                     MACH_PROV_OVERRIDE);
    assert_null(text);
    assert_int_equal(mach_param_provenance(root, "f", &text), MACH_PROV_SOURCE);
    assert_string_equal(text, "s");
    assert_string_equal(mach_param_word(root, "e"), "5");
    assert_string_equal(mach_param_word(root, "f"), "4");
    assert_null(mach_param_word(root, "zz"));
    cfg_free(root);
}

/* mach_net_params / mach_topo_new on networks the checker never saw. */
static void net_refused(const char *text, const char *want)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "n.yaml", &err);
    assert_non_null(root);
    NetParams p;
    NetTopo *t = NULL;
    gboolean ok = mach_net_params(root, &p, &err);
    if (ok) {
        t = mach_topo_new(root, 4, NULL, &err);
        ok = t != NULL;
    }
    if (ok)
        fail_msg("accepted %s", text);
    if (!g_str_has_prefix(err->message, want))
        fail_msg("got '%s', want '%s'", err->message, want);
    g_error_free(err);
    cfg_free(root);
}

static void test_net_unchecked(void **state)
{
    (void)state;
    net_refused("topology: ring\nbandwidth: 1 MB/s\nlevel_bandwidth: [x]\n",
                "n.yaml:3:19: found 'x', expected a non-negative bandwidth");
    net_refused("topology: ring\nbandwidth: 1 MB/s\nnews_bandwidth: q\n",
                "n.yaml:3:17: found 'q', expected a non-negative bandwidth");
    net_refused("topology: ring\nbandwidth: 1 MB/s\ntotal_bandwidth: q\n",
                "n.yaml:3:18: found 'q', expected a non-negative bandwidth");
    net_refused("topology: hypercube\nbandwidth: 1 MB/s\ndimension: two\n",
                "n.yaml:3:12: found 'two', expected a non-negative integer, "
                "optionally with K (1e3) or M (1e6)");
    net_refused("topology: mesh\nbandwidth: 1 MB/s\nextents: 4\n",
                "n.yaml:3:10: found a non-list value, expected a list of "
                "counts, e.g. [8, 8]");
    net_refused("topology: star\nbandwidth: 1 MB/s\n",
                "n.yaml:1:11: found topology 'star' (not built by the machine "
                "layer), expected hypercube, ring, fat-tree, cm-router, mesh, "
                "torus, crossbar or bus");
    assert_true(mach_topo_supported("torus"));
    assert_true(mach_topo_supported("bus"));
    assert_false(mach_topo_supported("star"));
    assert_false(mach_topo_supported(NULL));
}

/* Section-level refusals of the machine builder. */
static void test_machine_sections(void **state)
{
    (void)state;
    GError *err = NULL;
    CfgNode *root = cfg_load_string("machine: [1]\nm2: {model: [x]}\n"
                                    "m3: {model: missing-unit}\n",
                                    "run.yaml", &err);
    assert_false(mach_check_section(cfg_get(root, "machine"), &err));
    assert_string_equal(err->message,
                        "run.yaml:1:10: found a non-map machine section, "
                        "expected a map with model: <name> and overrides");
    g_clear_error(&err);
    assert_false(mach_check_section(cfg_get(root, "m2"), &err));
    assert_non_null(strstr(err->message, "run.yaml:2:13: found a sequence"));
    g_clear_error(&err);
    /* a model that does not pass the checker, found on $PGSIM_MODELS */
    g_setenv("PGSIM_MODELS", "tests/data/bad/models", TRUE);
    assert_null(mach_load_model("missing-unit", &err));
    assert_non_null(strstr(err->message, "without a unit"));
    g_clear_error(&err);
    assert_false(mach_check_section(cfg_get(root, "m3"), &err));
    assert_true(g_str_has_prefix(err->message, "run.yaml:3:5: "
                                               "tests/data/bad/models/"
                                               "missing-unit.yaml:7:"));
    g_clear_error(&err);
    g_unsetenv("PGSIM_MODELS");
    cfg_free(root);
    SimEngine *eng = sim_engine_new(1);
    assert_null(mach_new_from_model(eng, "no-such-model", "flow", &err));
    assert_non_null(strstr(err->message, "found no model 'no-such-model'"));
    g_clear_error(&err);
    sim_engine_free(eng);
}

/* A cm-router machine whose kinds have no lanes: one lane, refused at
 * the widest kind's count. */
static void test_cm_router_without_lanes(void **state)
{
    (void)state;
    bad_net("  nodes: {fe: {count: 1}, array: {count: 1}}\n"
            "  network: {topology: cm-router, bandwidth: 1 MB/s, "
            "procs_per_router: 16}\n",
            4, 42, "1 lanes for router_nodes x procs_per_router");
}

/* Partitions of a model whose kinds all have one processor: the first
 * largest kind scales, the others stay. */
static void partition_desc(const char *kinds, guint n, const char *want)
{
    GError *err = NULL;
    char *text = g_strdup_printf("machine:\n  provenance: assumption\n"
                                 "  name: t\n  nodes: %s\n  network: "
                                 "{topology: bus, bandwidth: 1 MB/s}\n",
                                 kinds);
    CfgNode *root = cfg_load_string(text, "run.yaml", &err);
    char *desc = NULL;
    if (!mach_partition(root, n, &desc, &err))
        fail_msg("%s: %s", kinds, err->message);
    assert_string_equal(desc, want);
    g_free(desc);
    cfg_free(root);
    g_free(text);
}

static void test_partition_single_kinds(void **state)
{
    (void)state;
    partition_desc("{a: {count: 1}, b: {count: 1}}", 5, "a 4, b 1");
    partition_desc("{a: {count: 0}, b: {count: 1}}", 5, "a 0, b 5");
    partition_desc("{a: {count: 1}, b: {count: 1}, c: {count: 1}}", 3,
                   "a 1, b 1, c 1");
    partition_desc("{a: {count: 3}, b: {count: 1}}", 2, "a 1, b 1");
    partition_desc("{a: {count: 2}, b: {count: 1}, c: {count: 6}}", 9,
                   "a 3, b 1, c 5");
    partition_desc("{a: {count: 2}, b: {count: 1}, c: {count: 6}}", 4,
                   "a 1, b 1, c 2");
    /* largest remainder; ties go to the earlier kind */
    partition_desc("{a: {count: 3}, b: {count: 5}}", 5, "a 2, b 3");
    partition_desc("{a: {count: 3}, b: {count: 5}}", 8, "a 3, b 5");
    partition_desc("{a: {count: 2}, b: {count: 2}}", 5, "a 3, b 2");
    partition_desc("{a: {count: 2}, b: {count: 2}, c: {count: 2}}", 8,
                   "a 3, b 3, c 2");
    partition_desc("{a: {count: 2}, b: {count: 2}, c: {count: 2}}", 3,
                   "a 1, b 1, c 1");
    partition_desc("{a: {count: 5}, b: {count: 3}}", 2, "a 1, b 1");
    partition_desc("{a: {count: 5}, b: {count: 3}}", 1000, "a 625, b 375");
    GError *err = NULL;
    CfgNode *root = cfg_load_string(
        "machine:\n  provenance: assumption\n  name: t\n  nodes: {a: {count: "
        "2}, b: {count: 1}, c: {count: 6}}\n  network: {topology: bus, "
        "bandwidth: 1 MB/s}\n",
        "run.yaml", &err);
    assert_false(mach_partition(root, 2, NULL, &err));
    assert_string_equal(err->message,
                        "found 2 nodes for a bus, expected at least 3 (the "
                        "single-processor kinds plus one of each other kind)");
    g_clear_error(&err);
    assert_true(mach_partition(root, 3, NULL, &err));
    cfg_free(root);
    root = cfg_load_string("machine:\n  provenance: assumption\n  name: t\n"
                           "  nodes: {a: {count: 4}}\n  network: {topology: "
                           "mesh, bandwidth: 1 MB/s}\n",
                           "run.yaml", &err);
    assert_false(mach_partition(root, 4, NULL, &err));
    assert_non_null(strstr(err->message, "no parameter 'extents'"));
    g_clear_error(&err);
    cfg_free(root);
}

/* mach_topo_new on `endpoints`: NULL when built, else the message. */
static char *topo_try(const char *text, guint endpoints)
{
    GError *err = NULL;
    CfgNode *root = cfg_load_string(text, "n.yaml", &err);
    assert_non_null(root);
    NetTopo *t = mach_topo_new(root, endpoints, NULL, &err);
    char *msg = NULL;
    if (t) {
        assert_int_equal(net_topo_nodes(t), endpoints);
        net_topo_free(t);
    } else {
        msg = g_strdup(err->message);
        g_error_free(err);
    }
    cfg_free(root);
    return msg;
}

static void expect_topo(const char *text, guint endpoints, const char *want)
{
    char *msg = topo_try(text, endpoints);
    if (want && (!msg || !strstr(msg, want)))
        fail_msg("%u on %s: got '%s', want '%s'", endpoints, text,
                 msg ? msg : "built", want);
    if (!want && msg)
        fail_msg("%u on %s: %s", endpoints, text, msg);
    g_free(msg);
}

/* The largest shapes each builder takes, and one past them. */
static void test_topology_limits(void **state)
{
    (void)state;
    expect_topo("topology: hypercube\n", 1u << 24, NULL);
    expect_topo("topology: hypercube\n", 1u << 25,
                "33554432 processors on a hypercube");
    expect_topo("topology: hypercube\ndimension: 24\n", 1u << 24, NULL);
    expect_topo("topology: hypercube\ndimension: 23\n", 1u << 24,
                "on a hypercube");
    expect_topo("topology: cm-router\nprocs_per_router: 1\n", 1u << 20, NULL);
    expect_topo("topology: cm-router\nprocs_per_router: 1\n", 1u << 21,
                "2097152 lanes");
    expect_topo("topology: cm-router\nprocs_per_router: 4\n", 1u << 22, NULL);
    expect_topo("topology: cm-router\nprocs_per_router: 4\n", 6,
                "6 lanes");
    expect_topo("topology: cm-router\nprocs_per_router: 4\n", 12,
                "12 lanes");
    expect_topo("topology: cm-router\nprocs_per_router: 4\n"
                "router_nodes: 2\n",
                8, NULL);
    expect_topo("topology: cm-router\nprocs_per_router: 4\n"
                "router_nodes: 4\n",
                8, "8 lanes");
    expect_topo("topology: mesh\nextents: [16777216]\n", 1u << 24, NULL);
    expect_topo("topology: mesh\nextents: [16777217]\n", 16777217,
                "unusable mesh extents");
    expect_topo("topology: torus\nextents: [2, 2, 2]\n", 8, NULL);
    expect_topo("topology: torus\nextents: []\n", 1, "unusable mesh extents");
    expect_topo("topology: fat-tree\narity: 64\n", 2, NULL);
    expect_topo("topology: fat-tree\narity: 65\n", 2, "fat-tree arity");
    expect_topo("topology: ring\n", 2, NULL);
    expect_topo("topology: hypercube\n", 1, NULL);
    expect_topo("topology: hypercube\n", 3, "3 processors on a hypercube");
    expect_topo("topology: fat-tree\narity: 64\n", 1,
                "n.yaml:1:1: found fewer than 2 leaves");
    expect_topo("topology: fat-tree\narity: 65\n", 1,
                "n.yaml:2:8: found an unusable fat-tree arity");
    expect_topo("topology: fat-tree\narity: 1\n", 1, "fat-tree arity");
}

/* Processor ids run through the kinds in model order, pages of 64
 * straddling kind boundaries; the cm-router's endpoints are the widest
 * kind's lanes wherever it stands; a model naming no fidelity is
 * "analytic (faithful)"; an unknown fidelity word is refused. */
static void test_kinds_and_fidelity(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    char *text = g_strdup(
        "machine:\n  provenance: assumption\n  name: t\n"
        "  nodes: {a: {count: 63}, b: {count: 2}, c: {count: 64}}\n"
        "  network: {topology: bus, bandwidth: 1 MB/s}\n");
    root = cfg_load_string(text, "run.yaml", &err);
    MachMachine *m =
        mach_new_from_cfg(eng, cfg_get(root, "machine"), "faithful", &err);
    assert_non_null(m);
    assert_string_equal(mach_fidelity(m), "analytic (faithful)");
    assert_int_equal(mach_proc_total(m), 129);
    static const guint ids[] = {0, 62, 63, 64, 65, 127, 128};
    static const char *const kinds[] = {"a", "a", "b", "b", "c", "c", "c"};
    static const guint index[] = {0, 62, 0, 1, 0, 62, 63};
    for (guint i = 0; i < G_N_ELEMENTS(ids); i++) {
        MachProc *p = mach_proc_at(m, ids[i]);
        assert_int_equal(mach_proc_id(p), ids[i]);
        assert_string_equal(mach_proc_kind(p), kinds[i]);
        assert_int_equal(mach_proc_index(p), index[i]);
        char *want = g_strdup_printf("%s%u", kinds[i], index[i]);
        assert_string_equal(mach_proc_name(p), want);
        g_free(want);
    }
    assert_int_equal(mach_kind(m, "c")->first, 65);
    assert_int_equal(mach_kind_at(m, 1)->first, 63);
    assert_null(mach_kind(m, "d"));
    mach_free(m);
    m = mach_new_from_cfg(eng, cfg_get(root, "machine"), "exact", &err);
    assert_null(m);
    assert_string_equal(err->message, "found fidelity 'exact', expected "
                                      "analytic, flow, packet or faithful");
    g_clear_error(&err);
    cfg_free(root);
    g_free(text);
    /* widest SIMD kind first, a narrower one after it */
    root = cfg_load_string(
        "machine:\n  provenance: assumption\n  name: t\n"
        "  nodes: {array: {count: 1, lanes: 32}, fe: {count: 1, lanes: 2}}\n"
        "  network: {topology: cm-router, bandwidth: 1 MB/s, "
        "procs_per_router: 8}\n",
        "run.yaml", &err);
    m = mach_new_from_cfg(eng, cfg_get(root, "machine"), "flow", &err);
    if (!m)
        fail_msg("%s", err->message);
    assert_int_equal(net_nodes(mach_net(m)), 32);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

/* The model folders: ./models first, then $PGSIM_MODELS in order with
 * empty entries skipped, then each data root's models; a folder named
 * twice (even spelt differently) is listed once. */
static void test_model_dirs(void **state)
{
    (void)state;
    g_setenv("PGSIM_MODELS", ":tests/data/models::models:tests/data/models/:"
                             "tests/data/bad/models",
             TRUE);
    GPtrArray *d = mach_model_dirs();
    assert_true(d->len >= 3);
    assert_string_equal(d->pdata[0], "models");
    assert_string_equal(d->pdata[1], "tests/data/models");
    assert_string_equal(d->pdata[2], "tests/data/bad/models");
    for (guint i = 0; i < d->len; i++) {
        assert_true(((const char *)d->pdata[i])[0] != '\0');
        char *ci = g_canonicalize_filename(d->pdata[i], NULL);
        for (guint j = 0; j < i; j++) {
            char *cj = g_canonicalize_filename(d->pdata[j], NULL);
            assert_string_not_equal(ci, cj);
            g_free(cj);
        }
        g_free(ci);
    }
    g_ptr_array_free(d, TRUE);
    g_unsetenv("PGSIM_MODELS");
    d = mach_model_dirs();
    assert_string_equal(d->pdata[0], "models");
    for (guint i = 1; i < d->len; i++)
        assert_true(g_str_has_suffix(d->pdata[i], "models"));
    g_ptr_array_free(d, TRUE);
}

static void count_done(SimEngine *e, void *ctx, void *arg)
{
    (void)arg;
    *(SimTime *)ctx = sim_now(e);
}

/* An empty operation list takes no time (its completion runs at once)
 * but is one request; a list prices its counts by the kind's costs. */
static void test_empty_op_list(void **state)
{
    (void)state;
    SimEngine *eng = sim_engine_new(1);
    CfgNode *root;
    GError *err = NULL;
    MachMachine *m = inline_machine(
        eng, "  nodes: {cpu: {count: 2, costs: {add: 3 us, mul: 5 us}}}\n"
             "  network: {topology: bus, bandwidth: 1 MB/s}\n",
        &root, &err);
    assert_non_null(m);
    MachProc *p = mach_proc(m, "cpu", 1);
    MachOps o = {0};
    SimTime at = 99;
    assert_true(mach_proc_compute_list(p, &o, 0, count_done, &at, NULL));
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(at, 0);
    assert_int_equal(mach_proc_busy(p), 0);
    assert_int_equal(mach_proc_free_at(p), 0);
    assert_int_equal(mach_proc_requests(p), 1);
    mach_ops_add(&o, "add", 2);
    mach_ops_add(&o, "mul", 1);
    assert_int_equal(mach_proc_ops_cost(p, &o), 11 * SIM_US);
    assert_true(mach_proc_compute_list(p, &o, 0, count_done, &at, NULL));
    assert_true(sim_engine_run(eng, SIM_TIME_MAX, NULL));
    assert_int_equal(at, 11 * SIM_US);
    assert_int_equal(mach_proc_busy(p), 11 * SIM_US);
    assert_int_equal(mach_proc_requests(p), 2);
    mach_free(m);
    cfg_free(root);
    sim_engine_free(eng);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_type_examples),
        cmocka_unit_test(test_units_required),
        cmocka_unit_test(test_sections_refused),
        cmocka_unit_test(test_later_keys_checked),
        cmocka_unit_test(test_model_names),
        cmocka_unit_test(test_net_params_refused),
        cmocka_unit_test(test_net_params_read),
        cmocka_unit_test(test_topologies_refused),
        cmocka_unit_test(test_cm_router),
        cmocka_unit_test(test_partition_lanes_first_kind),
        cmocka_unit_test(test_idle_counts),
        cmocka_unit_test(test_assumption_warning),
        cmocka_unit_test(test_getters_unchecked),
        cmocka_unit_test(test_net_unchecked),
        cmocka_unit_test(test_machine_sections),
        cmocka_unit_test(test_cm_router_without_lanes),
        cmocka_unit_test(test_partition_single_kinds),
        cmocka_unit_test(test_topology_limits),
        cmocka_unit_test(test_kinds_and_fidelity),
        cmocka_unit_test(test_model_dirs),
        cmocka_unit_test(test_empty_op_list),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
