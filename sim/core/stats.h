/* stats.h — statistics accumulators.
 *
 * SimSum: Neumaier-compensated sum of doubles (error independent of the
 * number of terms to first order).  SimBusy: busy time of one processor,
 * overall and per phase, in exact integer picoseconds.  Phase ids are
 * small integers interned by the engine (sim_engine_phase()).
 */
#ifndef PGSIM_CORE_STATS_H
#define PGSIM_CORE_STATS_H

#include "sim/core/time.h"

typedef struct {
    double sum;
    double comp;
} SimSum;

static inline void sim_sum_add(SimSum *s, double x)
{
    double t = s->sum + x;
    if (fabs(s->sum) >= fabs(x))
        s->comp += (s->sum - t) + x;
    else
        s->comp += (x - t) + s->sum;
    s->sum = t;
}

static inline double sim_sum_value(const SimSum *s)
{
    return s->sum + s->comp;
}

/* Running mean / min / max / variance (Welford). */
typedef struct {
    uint64_t n;
    double mean, m2, min, max;
} SimMoments;

void sim_moments_add(SimMoments *m, double x);
double sim_moments_var(const SimMoments *m);

typedef struct {
    SimTime total;     /* busy time over all phases */
    GArray *per_phase; /* SimTime, indexed by phase id; grows on demand */
} SimBusy;

void sim_busy_init(SimBusy *b);
void sim_busy_clear(SimBusy *b); /* frees per_phase */
/* Adds busy time to a phase; returns FALSE on overflow (then unchanged). */
gboolean sim_busy_add(SimBusy *b, unsigned phase, SimTime t);
SimTime sim_busy_phase(const SimBusy *b, unsigned phase);

/* Traffic carried by one link or channel. */
typedef struct {
    uint64_t bytes;
    uint64_t messages;
    SimTime busy;
} SimLinkStats;

#endif
