/* units.h — numbers with units, as written in configs and on the CLI.
 *
 * "<number>[ ]<unit>": a non-negative decimal number (digits, optional
 * fraction, optional exponent) followed by an optional space and a unit
 * from the kind's table (see cfg.h for the lists).  Decimal numbers are
 * scaled exactly in integer arithmetic where the result is an integer
 * (times in picoseconds, sizes in bytes, counts), so "2.8 KB" is exactly
 * 2800 and "350us" exactly 350,000,000 ps; times round to the nearest
 * picosecond.  Bandwidths and frequencies are doubles, converted once by
 * a correctly rounded decimal conversion.  A bare 0 needs no unit.
 *
 * Errors return FALSE with *expected set to a static phrase for the
 * "found ..., expected ..." message.  All functions are O(length).
 */
#ifndef PGSIM_CORE_UNITS_H
#define PGSIM_CORE_UNITS_H

#include "sim/core/time.h"
#include <stdint.h>

typedef enum {
    CFG_UNIT_TIME,      /* picoseconds */
    CFG_UNIT_BANDWIDTH, /* bytes per second */
    CFG_UNIT_FREQ,      /* hertz */
    CFG_UNIT_SIZE,      /* bytes */
    CFG_UNIT_COUNT      /* plain count, optional K or M */
} CfgUnitKind;

/* Integer kinds (TIME, SIZE, COUNT): the value in base units. */
gboolean cfg_units_u64(const char *s, CfgUnitKind kind, uint64_t *out,
                       const char **expected);
/* Any kind, as a double in base units (BANDWIDTH, FREQ). */
gboolean cfg_units_double(const char *s, CfgUnitKind kind, double *out,
                          const char **expected);
/* What a value of this kind looks like, for error messages. */
const char *cfg_units_expected(CfgUnitKind kind);

#endif
