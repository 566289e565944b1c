/* rng.h — deterministic random streams and distributions.
 *
 * xoshiro256** (Blackman & Vigna, 2018) seeded through splitmix64.  Each
 * entity draws from its own stream, seeded from (run seed, entity id), so
 * adding an entity or reordering draws in one entity never changes another
 * entity's numbers.  The project's own distributions: libc rand() is never
 * used.  All functions are O(1).
 */
#ifndef PGSIM_CORE_RNG_H
#define PGSIM_CORE_RNG_H

#include <glib.h>
#include <stdint.h>

typedef struct {
    uint64_t s[4];
} SimRng;

/* Seeds the stream for (seed, stream id). */
void sim_rng_init(SimRng *r, uint64_t seed, uint64_t stream);
uint64_t sim_rng_u64(SimRng *r);
/* Uniform in [0, 1) with 53 random bits. */
double sim_rng_uniform(SimRng *r);
/* Uniform integer in [0, n), unbiased (Lemire's method); n > 0. */
uint64_t sim_rng_below(SimRng *r, uint64_t n);
/* Exponential with the given mean (> 0). */
double sim_rng_exp(SimRng *r, double mean);
/* Normal(mean, sd) by the Marsaglia polar method. */
double sim_rng_normal(SimRng *r, double mean, double sd);
gboolean sim_rng_bernoulli(SimRng *r, double p);
/* splitmix64 step, exposed for deriving seeds (sweep repetitions ...). */
uint64_t sim_rng_mix(uint64_t x);

#endif
