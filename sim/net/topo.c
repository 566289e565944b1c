/* topo.c — NetTopo wrapping shared by the topology constructors. */
#include "sim/net/topology.h"

NetTopo *net_topo_wrap(const NetTopologyOps *ops, void *state,
                       size_t state_bytes)
{
    NetTopo *t = g_new0(NetTopo, 1);
    t->ops = ops;
    t->state = state;
    t->state_bytes = state_bytes;
    return t;
}

void net_topo_free(NetTopo *t)
{
    if (!t)
        return;
    if (t->ops->free)
        t->ops->free(t->state);
    else
        g_free(t->state);
    g_free(t);
}
