/* pphigs_costs.c — the costs a PPHIGS frame reads from the machine
 * (pphigs_frame.h: wl_pphigs_needs, wl_pphigs_costs_from_machine): the
 * GP cost table (per element kind, seed 001's traversal and transform),
 * the renderers' expression costs, the frame buffer's and the host's.
 * Values and their sources live in models/pixel-planes-5.yaml.
 */
#include "sim/workload/pphigs/pphigs_frame.h"

/* The costs a frame reads, declared once (`pgsim help run`; the machine
 * prices the named counts the frame hands it). */
static const char *const gp_ops[] = {
    "polygon",       "vertex",  "reject_vertex",  "color", "matrix_replace",
    "matrix_concat", "execute", "send_primitive", "line",  "sphere",
    NULL};
static const char *const renderer_ops[] = {"expression",   "compare",
                                           "region_begin", "region_shade",
                                           "quadratic",    NULL};
static const char *const fb_ops[] = {"store_region", NULL};
static const char *const host_ops[] = {"send_element", "scan_element", NULL};
const MachNeed wl_pphigs_needs[] = {{"gp", gp_ops, NULL},
                                    {"renderer", renderer_ops, NULL},
                                    {"frame_buffer", fb_ops, NULL},
                                    {"host", host_ops, NULL},
                                    {NULL, NULL, NULL}};
static const MachNeed gp_needs[] = {{"gp", gp_ops, NULL}, {NULL, NULL, NULL}};

void wl_pphigs_costs_fill(const MachCosts *set, WlPphigsCosts *c,
                          SimTime *send)
{
    SimTime *const dst[] = {&c->poly,    &c->vertex, &c->reject_vertex,
                            &c->color,   &c->matrix, &c->concat,
                            &c->execute, send,       &c->line,
                            &c->sphere};
    G_STATIC_ASSERT(G_N_ELEMENTS(dst) == G_N_ELEMENTS(gp_ops) - 1);
    mach_costs_fill(set, "gp", gp_ops, dst);
}

gboolean wl_pphigs_costs_from_machine(const MachMachine *m, WlPphigsCosts *c,
                                      SimTime *send, GError **err)
{
    MachCosts *set = mach_costs_new(m, gp_needs, err);
    if (set)
        wl_pphigs_costs_fill(set, c, send);
    mach_costs_free(set);
    return set != NULL;
}

