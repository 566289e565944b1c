/* work.h — portable work: a small fixed set of machine-independent work
 * classes, the work a workload's operation stands for in them, and a
 * node kind's processor description that prices the classes (issue 34,
 * point 1; docs/models.md "Portable work").
 *
 * A workload states each operation it prices (the op names of its
 * MachNeed table, costs.h) as counts of these classes, in a MachWork
 * table beside the MachNeed (machine independent: the same table on
 * every machine).  A node kind may carry a processor description: its
 * `clock`, `cycles: {CLASS: cycles of one processor per unit}` and
 * `memory_bandwidth` (membyte is priced by bandwidth, not cycles).  A
 * cost the model does not give explicitly is then derived:
 *
 *     time(op) = sum over classes c of  n_c x price(c)
 *     price(c) = cycles.c / clock          (c != membyte)
 *     price(membyte) = 1 / memory_bandwidth
 *
 * A graphics class (vertex, setup, pixel, zcmp) the description does not
 * price is expanded into the basic classes (flop, instr, miss, membyte)
 * by its software definition (mach_work_expansion, work.c), so a CPU
 * needs only its basic figures and a graphics pipe or GPU may give its
 * published rates for the graphics classes.  An explicit cost always
 * wins (costs.h).  Cost: O(classes) per derived cost.
 */
#ifndef PGSIM_MACHINE_WORK_H
#define PGSIM_MACHINE_WORK_H

#include "sim/core/cfg.h"
#include "sim/core/time.h"

/* The work classes, machine independent.  Order is the report order. */
typedef enum {
    MACH_W_VERTEX,  /* transform and light one vertex */
    MACH_W_SETUP,   /* set up one triangle or span: edge and
                       interpolant equations */
    MACH_W_PIXEL,   /* fill one pixel: interpolate, z test, write */
    MACH_W_ZCMP,    /* compare two depths, keep the nearer pixel */
    MACH_W_FLOP,    /* one floating-point add or multiply */
    MACH_W_INSTR,   /* one other instruction (integer, load/store hit,
                       branch) */
    MACH_W_MISS,    /* one dependent access to main memory (a cache
                       miss, a lock's remote transaction) */
    MACH_W_MEMBYTE, /* one byte streamed through main memory */
    MACH_W_N
} MachWorkClass;

/* The first class that is basic (has no software expansion). */
#define MACH_W_FIRST_BASIC MACH_W_FLOP

/* The class's name as a model and a report write it ("vertex" ...). */
const char *mach_work_class_name(MachWorkClass c);
/* The class named `name`; FALSE if none. */
gboolean mach_work_class_find(const char *name, MachWorkClass *out);
/* "vertex, setup, ..., membyte" (static). */
const char *mach_work_class_list(void);
/* A graphics class's software definition in basic classes (n[] over
 * MACH_W_N, zero for graphics classes); asserts c is a graphics class. */
const double *mach_work_expansion(MachWorkClass c);

/* One operation's work: counts of each class per operation. */
typedef struct {
    const char *op;
    double n[MACH_W_N];
} MachWork;

/* The entry of `op` in a table ended by a NULL op, or NULL. */
const MachWork *mach_work_find(const MachWork *table, const char *op);
/* "1 setup + 40 instr" (g_free). */
char *mach_work_describe(const MachWork *w);

/* A node kind's processor description: price per unit of each class in
 * picoseconds as a double (< 0: not priced), with where it came from. */
typedef struct {
    double ps[MACH_W_N];
    gboolean any;       /* the kind has a cycles: map or a bandwidth */
    const CfgNode *at;  /* the kind's cycles: map, else the kind */
} MachProcDesc;

/* Reads a checked kind's description (clock, cycles, memory_bandwidth);
 * FALSE with *err on a malformed value.  A class without a figure is
 * left unpriced (< 0); a cycles map without a clock is an error. */
gboolean mach_proc_desc_read(const CfgNode *kind, MachProcDesc *d,
                             GError **err);
/* The price of class c (ps per unit): its own figure, else its
 * expansion when every basic class of it is priced; < 0 when unpriced. */
double mach_proc_desc_price(const MachProcDesc *d, MachWorkClass c);
/* The derived time of w on d; FALSE (and *out untouched) when some class
 * w uses is unpriced; *missing (may be NULL) is then that class. */
gboolean mach_work_price(const MachProcDesc *d, const MachWork *w,
                         SimTime *out, MachWorkClass *missing);

#endif
