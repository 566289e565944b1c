/* test_model_clusters.c — the shipped cluster models as loaded: the GPU
 * cluster (models/dgx-a100-hdr.yaml: NVSwitch inside a DGX node, one HDR
 * adapter per GPU into a fat tree) and the 2000s PC graphics cluster
 * (models/pc-myrinet.yaml: Myrinet-2000).  Each checks figures that
 * follow from its sources: NVLink against InfiniBand bandwidth (12x),
 * hop counts inside and between nodes, the Myrinet MPI latency through
 * one switch (3.2 us), and the graphics card's rates as costs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim/machine/machine.h"
#include "sim/machine/model.h"
#include "sim/machine/partition.h"
#include "tests/support.h"

typedef struct {
    CfgNode *root;
    SimEngine *eng;
    MachMachine *m;
} Clu;

/* `model` partitioned to n endpoints (0: its own size). */
static NetNet *open_ok(Clu *c, const char *model, guint n)
{
    GError *err = NULL;
    *c = (Clu){.eng = sim_engine_new(1)};
    c->root = mach_partition_root("test", model, NULL, n, NULL, &err);
    if (c->root)
        c->m = mach_new_from_cfg(c->eng, cfg_get(c->root, "machine"),
                                 "analytic", &err);
    if (!c->m)
        fail_msg("%s --nodes %u: %s", model, n, err->message);
    return mach_net(c->m);
}

static void clu_close(Clu *c)
{
    mach_free(c->m);
    sim_engine_free(c->eng);
    cfg_free(c->root);
}

static guint hops(NetNet *net, uint32_t a, uint32_t b)
{
    const NetTopo *t = net_topo(net);
    NetLinkId r[64];
    g_assert(t->ops->max_hops(t->state) <= G_N_ELEMENTS(r));
    return t->ops->route(t->state, a, b, r);
}

/* Every network parameter and every value of every kind carries a
 * provenance. */
static void assert_all_sourced(const MachMachine *m)
{
    const CfgNode *root = mach_model_cfg(m);
    const CfgNode *net = cfg_get(root, "network");
    for (guint i = 0; i < cfg_map_len(net); i++)
        assert_int_not_equal(
            mach_param_provenance(net, cfg_map_key(net, i), NULL),
            MACH_PROV_NONE);
    const CfgNode *nodes = cfg_get(root, "nodes");
    for (guint k = 0; k < cfg_map_len(nodes); k++) {
        const CfgNode *kind = cfg_map_value(nodes, k);
        for (guint i = 0; i < cfg_map_len(kind); i++) {
            const char *key = cfg_map_key(kind, i);
            const CfgNode *sub = cfg_map_value(kind, i);
            if (cfg_kind(sub) == CFG_MAP && !cfg_get(sub, "value")) {
                for (guint j = 0; j < cfg_map_len(sub); j++)
                    assert_int_not_equal(
                        mach_param_provenance(sub, cfg_map_key(sub, j), NULL),
                        MACH_PROV_NONE);
            } else {
                assert_int_not_equal(mach_param_provenance(kind, key, NULL),
                                     MACH_PROV_NONE);
            }
        }
    }
}

/* DGX A100: GPUs 0..7 share node 0's NVSwitch (2 hops at 300 GB/s);
 * GPU 8 (node 1) is on the same 20-port leaf (2 hops at 25 GB/s); GPU 200
 * is under another leaf (4 hops).  1 GB takes 12x longer over HDR than
 * over NVLink, start-up and hops aside. */
static void test_dgx(void **state)
{
    (void)state;
    Clu c;
    NetNet *net = open_ok(&c, "dgx-a100-hdr", 0);
    assert_int_equal(net_nodes(net), 256);
    assert_string_equal(net_topo(net)->ops->name, "group");
    assert_int_equal(hops(net, 0, 7), 2);
    assert_int_equal(hops(net, 0, 8), 2);
    assert_int_equal(hops(net, 0, 200), 4);
    const NetParams *p = net_params(net);
    assert_true(p->node_bw == 300e9);
    const uint64_t gb = 1000000000;
    SimTime lat2 = p->startup + 2 * p->per_hop;
    SimTime nv = net_ideal_time(net, 0, 7, gb) - lat2;
    SimTime ib = net_ideal_time(net, 0, 8, gb) - lat2;
    assert_int_equal(nv, sim_time_for_bytes(1e9, 300e9));
    assert_int_equal(ib, sim_time_for_bytes(1e9, 25e9));
    assert_true(fabs((double)ib / (double)nv - 12.0) < 1e-6);
    const MachKindInfo *k = mach_kind(c.m, "gpu");
    assert_int_equal(k->count, 256);
    assert_all_sourced(c.m);
    clu_close(&c);
    net = open_ok(&c, "dgx-a100-hdr", 64); /* 8 nodes */
    assert_int_equal(net_nodes(net), 64);
    clu_close(&c);
    net = open_ok(&c, "dgx-a100-hdr", 4); /* half of one node */
    assert_int_equal(hops(net, 0, 3), 2);
    assert_true(net_ideal_time(net, 0, 3, gb) - lat2 ==
                sim_time_for_bytes(1e9, 300e9));
    clu_close(&c);
}

/* Myrinet-2000: a message through one crossbar pays the 3.2 us MPI
 * latency Myricom measured (2.7 us + 2 x 0.25 us), then 250 MB/s; node
 * 9 is under another crossbar (4 hops).  The card's geometry and fill
 * rates are the node's costs. */
static void test_pc_myrinet(void **state)
{
    (void)state;
    Clu c;
    NetNet *net = open_ok(&c, "pc-myrinet", 0);
    assert_int_equal(net_nodes(net), 32);
    assert_int_equal(hops(net, 0, 7), 2);
    assert_int_equal(hops(net, 0, 9), 4);
    assert_int_equal(net_ideal_time(net, 0, 7, 0), 3200 * SIM_NS);
    assert_int_equal(net_ideal_time(net, 0, 7, 250000) - 3200 * SIM_NS,
                     SIM_MS);
    const CfgNode *costs = cfg_path(mach_model_cfg(c.m), "nodes.node.costs");
    SimTime tv = 0, pz = 0;
    assert_true(mach_param_time(costs, "transform_vertex", TRUE, &tv, NULL));
    assert_true(mach_param_time(costs, "pixel_zbuffer", TRUE, &pz, NULL));
    /* 90 M triangles/s and 8 pixels x 400 MHz. */
    assert_true(fabs((double)tv * 90e6 / (double)SIM_S - 1.0) < 0.002);
    assert_true(llabs((long long)(pz * 8 * 400) - (long long)SIM_US) <= 8 * 400); /* 312.5 ps, to 1 ps */
    assert_all_sourced(c.m);
    clu_close(&c);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dgx),
        cmocka_unit_test(test_pc_myrinet),
    };
    return cmocka_run_group_tests_name("model_clusters", tests, NULL, NULL);
}
