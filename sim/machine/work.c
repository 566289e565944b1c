/* work.c — the work classes, their software definitions, and pricing an
 * operation's work on a node kind's processor description (work.h).
 *
 * Invariant: a price is either >= 0 picoseconds per unit or unpriced
 * (< 0); a derived time is the rounded sum of count x price, saturating.
 * Cost: O(MACH_W_N) per price.
 */
#include "sim/machine/work.h"
#include "sim/core/error.h"
#include "sim/machine/model_param.h"
#include <math.h>
#include <string.h>

static const char *const class_names[MACH_W_N] = {
    "vertex", "setup", "pixel", "zcmp", "flop", "instr", "miss", "membyte"};

/* A graphics class done in software, in basic classes: the definition of
 * the unit (docs/models.md, "Portable work"), not a measurement.
 * vertex: 4x4 position transform (28 flops), 3x3 normal transform (15),
 *   one diffuse light (~25), perspective divide and viewport (~10),
 *   plus ~30 loads, stores and loop instructions;
 * setup: three edge equations and the z and colour plane equations of a
 *   triangle or span (~60 flops), bounding box and bookkeeping (~40);
 * pixel: step z and three colour interpolants (4 adds), load, compare and
 *   store z, store colour, loop (~8 instructions), cache-resident;
 * zcmp: load two depths, compare, select and store the nearer (~6). */
static const double expansion[MACH_W_FIRST_BASIC][MACH_W_N] = {
    [MACH_W_VERTEX] = {[MACH_W_FLOP] = 80, [MACH_W_INSTR] = 30},
    [MACH_W_SETUP] = {[MACH_W_FLOP] = 60, [MACH_W_INSTR] = 40},
    [MACH_W_PIXEL] = {[MACH_W_FLOP] = 4, [MACH_W_INSTR] = 8},
    [MACH_W_ZCMP] = {[MACH_W_INSTR] = 6},
};

const char *mach_work_class_name(MachWorkClass c)
{
    g_assert(c < MACH_W_N);
    return class_names[c];
}

gboolean mach_work_class_find(const char *name, MachWorkClass *out)
{
    for (guint c = 0; c < MACH_W_N; c++)
        if (!strcmp(class_names[c], name)) {
            *out = (MachWorkClass)c;
            return TRUE;
        }
    return FALSE;
}

const char *mach_work_class_list(void)
{
    return "vertex, setup, pixel, zcmp, flop, instr, miss, membyte";
}

const double *mach_work_expansion(MachWorkClass c)
{
    g_assert(c < MACH_W_FIRST_BASIC);
    return expansion[c];
}

const MachWork *mach_work_find(const MachWork *table, const char *op)
{
    for (const MachWork *w = table; w && w->op; w++)
        if (!strcmp(w->op, op))
            return w;
    return NULL;
}

char *mach_work_describe(const MachWork *w)
{
    GString *s = g_string_new(NULL);
    for (guint c = 0; c < MACH_W_N; c++)
        if (w->n[c] > 0)
            g_string_append_printf(s, "%s%g %s", s->len ? " + " : "",
                                   w->n[c], class_names[c]);
    if (!s->len)
        g_string_append(s, "no work");
    return g_string_free(s, FALSE);
}

/* ---- a kind's processor description ------------------------------------ */

/* cycles.CLASS of a checked kind (model.c checked the class names and
 * that the kind has a clock). */
static gboolean read_cycles(const CfgNode *cycles, double hz, MachProcDesc *d,
                            GError **err)
{
    for (guint i = 0; i < cfg_map_len(cycles); i++) {
        const char *name = cfg_map_key(cycles, i);
        MachWorkClass c;
        double n;
        gboolean known = mach_work_class_find(name, &c);
        g_assert(known && c != MACH_W_MEMBYTE && hz > 0);
        if (!mach_param_number(cycles, name, TRUE, &n, err))
            return FALSE;
        d->ps[c] = n / hz * 1e12;
    }
    return TRUE;
}

gboolean mach_proc_desc_read(const CfgNode *kind, MachProcDesc *d,
                             GError **err)
{
    for (guint c = 0; c < MACH_W_N; c++)
        d->ps[c] = -1;
    const CfgNode *cycles = cfg_get(kind, "cycles");
    d->at = cycles ? cycles : kind;
    d->any = cycles != NULL;
    double hz = 0, bw = 0;
    if (!mach_param_freq(kind, "clock", FALSE, &hz, err) ||
        !mach_param_bandwidth(kind, "memory_bandwidth", FALSE, &bw, err))
        return FALSE;
    if (cycles && !read_cycles(cycles, hz, d, err))
        return FALSE;
    if (bw > 0) {
        d->ps[MACH_W_MEMBYTE] = 1e12 / bw;
        d->any = TRUE;
    }
    return TRUE;
}

double mach_proc_desc_price(const MachProcDesc *d, MachWorkClass c)
{
    if (d->ps[c] >= 0 || c >= MACH_W_FIRST_BASIC)
        return d->ps[c];
    double sum = 0;
    for (guint b = MACH_W_FIRST_BASIC; b < MACH_W_N; b++) {
        double n = expansion[c][b];
        if (n > 0 && d->ps[b] < 0)
            return -1;
        sum += n > 0 ? n * d->ps[b] : 0;
    }
    return sum;
}

gboolean mach_work_price(const MachProcDesc *d, const MachWork *w,
                         SimTime *out, MachWorkClass *missing)
{
    double ps = 0;
    for (guint c = 0; c < MACH_W_N; c++) {
        if (w->n[c] <= 0)
            continue;
        double p = mach_proc_desc_price(d, (MachWorkClass)c);
        if (p < 0) {
            if (missing)
                *missing = (MachWorkClass)c;
            return FALSE;
        }
        ps += w->n[c] * p;
    }
    double r = round(ps);
    *out = r >= (double)SIM_TIME_MAX ? SIM_TIME_MAX : (SimTime)r;
    return TRUE;
}
