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
/* Each op's portable work (sim/machine/work.h; the instruction counts of
 * models/pixel-planes-5.yaml): a cost the model lacks is derived from it
 * on the kind's processor description.  A renderer op works on every
 * pixel of a 128 x 128 region, as the SIMD array does. */
#define PPHIGS_REGION 16384.0
static const MachWork gp_work[] = {
    /* fetch and dispatch (~40), clip test, the renderer's coefficients */
    {"polygon", {[MACH_W_SETUP] = 1, [MACH_W_FLOP] = 40, [MACH_W_INSTR] = 60}},
    {"vertex", {[MACH_W_VERTEX] = 1}},
    {"reject_vertex", {[MACH_W_FLOP] = 28, [MACH_W_INSTR] = 15}},
    {"color", {[MACH_W_INSTR] = 20}},
    {"matrix_replace", {[MACH_W_INSTR] = 40, [MACH_W_MEMBYTE] = 128}},
    {"matrix_concat", {[MACH_W_FLOP] = 128, [MACH_W_INSTR] = 30}},
    {"execute", {[MACH_W_INSTR] = 60}},
    {"send_primitive", {[MACH_W_INSTR] = 20, [MACH_W_MEMBYTE] = 200}},
    /* a one-pixel-wide quad's 4 expressions; a sphere's radius and 5
     * quadratic expressions */
    {"line", {[MACH_W_FLOP] = 60, [MACH_W_INSTR] = 40}},
    {"sphere", {[MACH_W_FLOP] = 110, [MACH_W_INSTR] = 40}},
    {NULL, {0}}};
static const MachWork renderer_work[] = {
    {"expression", {[MACH_W_FLOP] = PPHIGS_REGION}},
    {"compare", {[MACH_W_ZCMP] = PPHIGS_REGION}},
    {"region_begin", {[MACH_W_MEMBYTE] = 8 * PPHIGS_REGION}},
    /* deferred Phong shading: normalise and two dot products a pixel */
    {"region_shade", {[MACH_W_FLOP] = 30 * PPHIGS_REGION,
                      [MACH_W_INSTR] = 8 * PPHIGS_REGION}},
    {"quadratic", {[MACH_W_FLOP] = 2 * PPHIGS_REGION}}, /* forward diff. */
    {NULL, {0}}};
static const MachWork fb_work[] = {
    {"store_region", {[MACH_W_MEMBYTE] = 8 * PPHIGS_REGION}}, {NULL, {0}}};
static const MachWork host_work[] = {
    {"send_element", {[MACH_W_INSTR] = 80, [MACH_W_MEMBYTE] = 200}},
    {"scan_element", {[MACH_W_INSTR] = 20}},
    {NULL, {0}}};
const MachNeed wl_pphigs_needs[] = {{"gp", gp_ops, gp_work},
                                    {"renderer", renderer_ops, renderer_work},
                                    {"frame_buffer", fb_ops, fb_work},
                                    {"host", host_ops, host_work},
                                    {NULL, NULL, NULL}};
static const MachNeed gp_needs[] = {{"gp", gp_ops, gp_work},
                                    {NULL, NULL, NULL}};

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

