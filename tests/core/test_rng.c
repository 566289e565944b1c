/* test_rng.c — streams and distributions (fixed seeds: deterministic). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim/core/rng.h"
#include "sim/core/stats.h"
#include "tests/support.h"
#include <stdlib.h>

static void test_known_first_values_are_stable(void **state)
{
    (void)state;
    SimRng a, b;
    sim_rng_init(&a, 12345, 7);
    sim_rng_init(&b, 12345, 7);
    for (int i = 0; i < 100; i++)
        assert_true(sim_rng_u64(&a) == sim_rng_u64(&b));
    sim_rng_init(&b, 12345, 8);
    assert_true(sim_rng_u64(&a) != sim_rng_u64(&b));
    sim_rng_init(&b, 12346, 7);
    sim_rng_init(&a, 12345, 7);
    assert_true(sim_rng_u64(&a) != sim_rng_u64(&b));
}

static void test_below_is_in_range_and_unbiased(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 1, 1);
    int hist[6] = {0};
    for (int i = 0; i < 600000; i++) {
        uint64_t v = sim_rng_below(&r, 6);
        assert_true(v < 6);
        hist[v]++;
    }
    for (int i = 0; i < 6; i++) /* 5 sigma of a binomial(600000, 1/6) */
        assert_true(abs(hist[i] - 100000) < 5 * 289);
    assert_int_equal(sim_rng_below(&r, 1), 0);
}

static void test_distribution_moments(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 2, 3);
    SimMoments u = {0}, ex = {0}, nm = {0};
    int n = 400000, hits = 0;
    for (int i = 0; i < n; i++) {
        double x = sim_rng_uniform(&r);
        assert_true(x >= 0.0 && x < 1.0);
        sim_moments_add(&u, x);
        double y = sim_rng_exp(&r, 2.0);
        assert_true(y >= 0.0 && isfinite(y));
        sim_moments_add(&ex, y);
        sim_moments_add(&nm, sim_rng_normal(&r, 10.0, 3.0));
        hits += sim_rng_bernoulli(&r, 0.25);
    }
    assert_true(fabs(u.mean - 0.5) < 0.003);
    assert_true(fabs(sim_moments_var(&u) - 1.0 / 12) < 0.002);
    assert_true(fabs(ex.mean - 2.0) < 0.02);
    assert_true(fabs(nm.mean - 10.0) < 0.03);
    assert_true(fabs(sqrt(sim_moments_var(&nm)) - 3.0) < 0.03);
    assert_true(fabs(hits / (double)n - 0.25) < 0.004);
}

/* Small samples exactly: one value has variance 0 and is min and max;
 * then 3, -1, 1: mean 1, sample variance 4, min -1, max 3. */
static void test_moments_small(void **state)
{
    (void)state;
    SimMoments m = {0};
    assert_true(sim_moments_var(&m) == 0);
    sim_moments_add(&m, 3);
    assert_true(sim_moments_var(&m) == 0);
    assert_true(m.min == 3 && m.max == 3 && m.mean == 3);
    sim_moments_add(&m, -1);
    sim_moments_add(&m, 1);
    assert_true(m.n == 3 && m.mean == 1 && m.min == -1 && m.max == 3);
    assert_true(fabs(sim_moments_var(&m) - 4) < 1e-12);
}

static void test_compensated_sum(void **state)
{
    (void)state;
    SimSum s = {0};
    double naive = 0.0;
    sim_sum_add(&s, 1e16);
    naive += 1e16;
    for (int i = 0; i < 10000; i++) {
        sim_sum_add(&s, 1.0);
        naive += 1.0;
    }
    sim_sum_add(&s, -1e16);
    naive += -1e16;
    assert_true(sim_sum_value(&s) == 10000.0);
    assert_true(naive != 10000.0); /* the case really is hard */
}

static void test_busy_per_phase(void **state)
{
    (void)state;
    SimBusy b;
    sim_busy_init(&b);
    assert_true(sim_busy_add(&b, 3, 100));
    assert_true(sim_busy_add(&b, 0, 50));
    assert_true(sim_busy_add(&b, 3, 1));
    assert_int_equal(sim_busy_phase(&b, 3), 101);
    assert_int_equal(sim_busy_phase(&b, 0), 50);
    assert_int_equal(sim_busy_phase(&b, 9), 0);
    assert_int_equal(b.total, 151);
    assert_false(sim_busy_add(&b, 1, SIM_TIME_MAX));
    assert_int_equal(b.total, 151);
    sim_busy_clear(&b);
}

/* Reference values of the published algorithms, computed independently
 * (a direct Python transcription of splitmix64 and xoshiro256** from the
 * papers cited in rng.c): mix(0) is splitmix64's well-known first output. */
static void test_reference_values(void **state)
{
    (void)state;
    assert_true(sim_rng_mix(0) == 0xe220a8397b1dcdafULL);
    assert_true(sim_rng_mix(1) == 0x910a2dec89025cc1ULL);
    SimRng r;
    sim_rng_init(&r, 12345, 7);
    const uint64_t want[] = {0xad8a4308a6583b9fULL, 0x73d9d488d4a5e9d0ULL,
                             0xf5014c52f76eb572ULL, 0xb29ba18c63cf458aULL};
    for (int i = 0; i < 4; i++)
        assert_true(sim_rng_u64(&r) == want[i]);
    sim_rng_init(&r, 3, 4);
    assert_true(sim_rng_uniform(&r) == 0.6035144609353897);
    assert_true(sim_rng_uniform(&r) == 0.38903616270786034);
    assert_true(fabs(sim_rng_exp(&r, 2.0) - 1.1633723888167098) < 1e-13);
    /* eight normals take 20 uniforms: the sixth rejects two pairs */
    const double nm[] = {10.738784857393812, 9.259054422943594,
                         10.334891166125775, 13.630522006191164,
                         11.497375902079495, 10.622685762460758,
                         13.466882390710905, 13.125056221301081};
    for (int i = 0; i < 8; i++)
        assert_true(fabs(sim_rng_normal(&r, 10.0, 3.0) - nm[i]) < 1e-12);
}

/* n = 2^63 + 1 rejects about half the draws (threshold 2^63 - 1): the
 * eight values take 20 draws in the reference. */
static void test_below_rejection_reference(void **state)
{
    (void)state;
    SimRng r;
    sim_rng_init(&r, 1, 2);
    const uint64_t want[] = {1381868078914345435ULL, 9202356868409158563ULL,
                             2601916470229181230ULL, 5559805447233235304ULL,
                             3725117600180909818ULL, 265239456687484441ULL,
                             2424903339762140729ULL, 3578577075245689539ULL};
    for (int i = 0; i < 8; i++)
        assert_true(sim_rng_below(&r, (1ULL << 63) + 1) == want[i]);
}

/* Lemire keeps a product whose low word equals the threshold exactly:
 * for n = 3 the threshold is 2^64 mod 3 = 1, and a state whose output is
 * 3^-1 mod 2^64 (0xaaaaaaaaaaaaaaab) gives low word 1 and value 2; a
 * rejection would draw again and give 0. */
static void test_below_keeps_threshold_tie(void **state)
{
    (void)state;
    SimRng r = {{0x0f0f0f0f0f0f0f0fULL, 0x07ceb240795ceb24ULL, 0, 0}};
    SimRng c = r;
    assert_true(sim_rng_u64(&c) == 0xaaaaaaaaaaaaaaabULL);
    assert_int_equal(sim_rng_below(&r, 3), 2);
}

/* bernoulli(p) is true exactly when the uniform draw u is below p, so it
 * is true with probability p: false at p = u (and so never at p = 0),
 * true just above u. */
static void test_bernoulli_is_strict(void **state)
{
    (void)state;
    SimRng r, c;
    sim_rng_init(&r, 8, 9);
    for (int i = 0; i < 50; i++) {
        c = r;
        double u = sim_rng_uniform(&c);
        SimRng d = r;
        assert_false(sim_rng_bernoulli(&d, u));
        d = r;
        assert_true(sim_rng_bernoulli(&d, nextafter(u, 2.0)));
        assert_false(sim_rng_bernoulli(&r, 0.0));
        assert_true(sim_rng_bernoulli(&c, 1.0));
        r = c;
    }
}

/* The polar method rejects a pair on the unit circle (s = 1) and at the
 * centre (s = 0) and draws two more uniforms.  States built by inverting
 * the output function: s[1] = 0xcd00000000000000 outputs 2^63 (u = 0);
 * with s[0] = s[1], s[2] = 0 the next output is 0 (v = -1, s = 1), with
 * s[0] = s[2] = 0 it is 2^63 again (u = v = 0, s = 0). */
static void test_normal_rejects_circle_and_centre(void **state)
{
    (void)state;
    const uint64_t a = 0xcd00000000000000ULL;
    SimRng circle = {{a, a, 0, 5}}, centre = {{0, a, 0, 5}};
    SimRng *cases[] = {&circle, &centre};
    for (int i = 0; i < 2; i++) {
        SimRng r = *cases[i], skip = *cases[i];
        assert_true(sim_rng_u64(&skip) == 1ULL << 63);
        uint64_t second = sim_rng_u64(&skip);
        assert_true(second == (i == 0 ? 0 : 1ULL << 63));
        double want = sim_rng_normal(&skip, 10.0, 3.0);
        assert_true(isfinite(want) && want != 10.0);
        assert_true(sim_rng_normal(&r, 10.0, 3.0) == want);
    }
}

/* Phases in increasing order, each one past the end of the array: every
 * add grows it by one; a phase at or past the end reads 0; a cleared
 * accumulator reads 0 everywhere. */
static void test_busy_growth(void **state)
{
    (void)state;
    SimBusy b;
    sim_busy_init(&b);
    assert_int_equal(sim_busy_phase(&b, 0), 0);
    for (unsigned ph = 0; ph < 5; ph++) {
        assert_true(sim_busy_add(&b, ph, 10 + ph));
        assert_int_equal(b.per_phase->len, ph + 1);
        assert_int_equal(sim_busy_phase(&b, ph + 1), 0);
    }
    for (unsigned ph = 0; ph < 5; ph++)
        assert_int_equal(sim_busy_phase(&b, ph), 10 + ph);
    assert_int_equal(b.total, 60);
    assert_true(sim_busy_add(&b, 2, SIM_TIME_MAX - 60));
    assert_int_equal(b.total, SIM_TIME_MAX);
    assert_false(sim_busy_add(&b, 0, 1)); /* the total would overflow */
    assert_int_equal(sim_busy_phase(&b, 0), 10);
    sim_busy_clear(&b);
    assert_null(b.per_phase);
    assert_int_equal(b.total, 0);
    assert_int_equal(sim_busy_phase(&b, 0), 0);
    sim_busy_clear(&b);
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_known_first_values_are_stable),
        cmocka_unit_test(test_below_is_in_range_and_unbiased),
        cmocka_unit_test(test_distribution_moments),
        cmocka_unit_test(test_moments_small),
        cmocka_unit_test(test_compensated_sum),
        cmocka_unit_test(test_busy_per_phase),
        cmocka_unit_test(test_busy_growth),
        cmocka_unit_test(test_reference_values),
        cmocka_unit_test(test_below_rejection_reference),
        cmocka_unit_test(test_below_keeps_threshold_tie),
        cmocka_unit_test(test_bernoulli_is_strict),
        cmocka_unit_test(test_normal_rejects_circle_and_centre),
    };
    return cmocka_run_group_tests_name("rng_stats", tests, NULL, NULL);
}
