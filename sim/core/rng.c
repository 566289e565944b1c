/* rng.c — xoshiro256** streams and distributions.
 *
 * Generator: D. Blackman and S. Vigna, "Scrambled linear pseudorandom
 * number generators", ACM TOMS 47(4), 2021.  Seeding: splitmix64 (Steele,
 * Lea, Flood, OOPSLA 2014).  Bounded integers: D. Lemire, "Fast random
 * integer generation in an interval", ACM TOMACS 29(1), 2019.
 */
#include "sim/core/rng.h"
#include <math.h>

uint64_t sim_rng_mix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

void sim_rng_init(SimRng *r, uint64_t seed, uint64_t stream)
{
    uint64_t x =
        sim_rng_mix(seed) ^ sim_rng_mix(stream + 0x632be59bd9b4e019ULL);
    /* s[i + 1] = mix(s[i]) and mix is a bijection with mix(0) != 0, so
     * s[0] and s[1] are never both zero: the all-zero state (a fixed
     * point of xoshiro) cannot arise. */
    for (int i = 0; i < 4; i++) {
        x = sim_rng_mix(x);
        r->s[i] = x;
    }
}

static inline uint64_t rotl(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

uint64_t sim_rng_u64(SimRng *r)
{
    uint64_t *s = r->s;
    uint64_t out = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return out;
}

double sim_rng_uniform(SimRng *r)
{
    return (double)(sim_rng_u64(r) >> 11) * 0x1.0p-53;
}

uint64_t sim_rng_below(SimRng *r, uint64_t n)
{
    g_assert(n > 0);
    unsigned __int128 m = (unsigned __int128)sim_rng_u64(r) * n;
    uint64_t lo = (uint64_t)m;
    if (lo < n) {
        uint64_t thresh = -n % n;
        while (lo < thresh) {
            m = (unsigned __int128)sim_rng_u64(r) * n;
            lo = (uint64_t)m;
        }
    }
    return (uint64_t)(m >> 64);
}

double sim_rng_exp(SimRng *r, double mean)
{
    /* 1 - u is in (0, 1], so the log is finite. */
    return -mean * log(1.0 - sim_rng_uniform(r));
}

double sim_rng_normal(SimRng *r, double mean, double sd)
{
    double u, v, s;
    do {
        u = 2.0 * sim_rng_uniform(r) - 1.0;
        v = 2.0 * sim_rng_uniform(r) - 1.0;
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    return mean + sd * u * sqrt(-2.0 * log(s) / s);
}

gboolean sim_rng_bernoulli(SimRng *r, double p)
{
    return sim_rng_uniform(r) < p;
}
