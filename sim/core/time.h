/* time.h — simulated time.
 *
 * SimTime is an unsigned 64-bit count of picoseconds: about 213 days of
 * simulated time, far beyond any frame.  No floating point in the clock:
 * conversions from seconds round to the nearest picosecond once, at the
 * edge (config parsing, cost tables).  Adding times goes through
 * sim_time_add(), which reports overflow instead of wrapping; a count
 * times a unit cost goes through sim_time_mul_sat(), the one place that
 * prices "n x cost" (a saturated SIM_TIME_MAX then overflows the engine's
 * clock, a located run error, instead of wrapping to a small time).
 */
#ifndef PGSIM_CORE_TIME_H
#define PGSIM_CORE_TIME_H

#include <glib.h>
#include <math.h>
#include <stdint.h>

typedef uint64_t SimTime;

#define SIM_PS ((SimTime)1)
#define SIM_NS ((SimTime)1000)
#define SIM_US ((SimTime)1000000)
#define SIM_MS ((SimTime)1000000000)
#define SIM_S ((SimTime)1000000000000)
#define SIM_TIME_MAX UINT64_MAX

/* a + b into *out; returns FALSE (and leaves *out alone) on overflow. */
static inline gboolean sim_time_add(SimTime a, SimTime b, SimTime *out)
{
    if (a > SIM_TIME_MAX - b)
        return FALSE;
    *out = a + b;
    return TRUE;
}

/* a + b, saturating at SIM_TIME_MAX (for "until" bounds, never events). */
static inline SimTime sim_time_add_sat(SimTime a, SimTime b)
{
    return a > SIM_TIME_MAX - b ? SIM_TIME_MAX : a + b;
}

/* n x unit, saturating at SIM_TIME_MAX: the price of n operations of one
 * cost.  Every "count x cost" in pgsim goes through here. */
static inline SimTime sim_time_mul_sat(SimTime unit, uint64_t n)
{
    return n != 0 && unit > SIM_TIME_MAX / n ? SIM_TIME_MAX : unit * n;
}

/* Seconds (finite, >= 0) to picoseconds, rounded to nearest; returns FALSE
 * if negative, not finite or too large for SimTime. */
static inline gboolean sim_time_from_s(double s, SimTime *out)
{
    double ps = s * 1e12;
    if (!(ps >= 0.0) || !isfinite(ps) || ps >= 18446744073709549568.0)
        return FALSE;
    *out = (SimTime)llround(ps);
    return TRUE;
}

/* Conversions for reporting: exact enough for printing, never fed back. */
static inline double sim_time_to_s(SimTime t)
{
    return (double)t * 1e-12;
}
static inline double sim_time_to_ms(SimTime t)
{
    return (double)t * 1e-9;
}
static inline double sim_time_to_us(SimTime t)
{
    return (double)t * 1e-6;
}

/* Time to move `bytes` at `bytes_per_s`, rounded up to a whole picosecond
 * so that a non-empty transfer never takes zero time. */
static inline SimTime sim_time_for_bytes(double bytes, double bytes_per_s)
{
    double ps = ceil(bytes / bytes_per_s * 1e12);
    return ps >= 18446744073709549568.0 ? SIM_TIME_MAX : (SimTime)ps;
}

#endif
