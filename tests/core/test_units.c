/* test_units.c — numbers with units: good values, exact scaling, and every
 * class of bad input (negative, missing number, unknown unit, overflow). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <string.h>

#include "sim/core/cfg.h"
#include "sim/core/units.h"
#include "tests/support.h"

static uint64_t u64_ok(const char *s, CfgUnitKind k)
{
    uint64_t v = 12345;
    const char *exp = NULL;
    if (!cfg_units_u64(s, k, &v, &exp))
        fail_msg("'%s' rejected: expected %s", s, exp);
    return v;
}

static double dbl_ok(const char *s, CfgUnitKind k)
{
    double v = -1;
    const char *exp = NULL;
    if (!cfg_units_double(s, k, &v, &exp))
        fail_msg("'%s' rejected: expected %s", s, exp);
    return v;
}

static const char *u64_bad(const char *s, CfgUnitKind k)
{
    uint64_t v = 7;
    const char *exp = NULL;
    assert_false(cfg_units_u64(s, k, &v, &exp));
    assert_non_null(exp);
    return exp;
}

static const char *dbl_bad(const char *s, CfgUnitKind k)
{
    double v = 7;
    const char *exp = NULL;
    assert_false(cfg_units_double(s, k, &v, &exp));
    assert_non_null(exp);
    return exp;
}

static void test_times(void **state)
{
    (void)state;
    assert_int_equal(u64_ok("350us", CFG_UNIT_TIME), 350 * SIM_US);
    assert_int_equal(u64_ok("350 us", CFG_UNIT_TIME), 350 * SIM_US);
    assert_int_equal(u64_ok("350 \xc2\xb5s", CFG_UNIT_TIME), 350 * SIM_US);
    assert_int_equal(u64_ok("1.5 ns", CFG_UNIT_TIME), 1500);
    assert_int_equal(u64_ok("2 s", CFG_UNIT_TIME), 2 * SIM_S);
    assert_int_equal(u64_ok("0.25ms", CFG_UNIT_TIME), 250 * SIM_US);
    assert_int_equal(u64_ok("1e3 ps", CFG_UNIT_TIME), 1000);
    assert_int_equal(u64_ok("0", CFG_UNIT_TIME), 0);
    /* rounds to the nearest picosecond, half up */
    assert_int_equal(u64_ok("1.4 ps", CFG_UNIT_TIME), 1);
    assert_int_equal(u64_ok("1.5 ps", CFG_UNIT_TIME), 2);
    assert_int_equal(u64_ok("0.0000001 ps", CFG_UNIT_TIME), 0);
    /* exact: 0.1 s is not 0.1 in binary, but it is 1e11 ps here */
    assert_int_equal(u64_ok("0.1 s", CFG_UNIT_TIME), 100000000000ULL);
}

static void test_sizes_counts(void **state)
{
    (void)state;
    assert_int_equal(u64_ok("64KiB", CFG_UNIT_SIZE), 65536);
    assert_int_equal(u64_ok("64 KB", CFG_UNIT_SIZE), 64000);
    assert_int_equal(u64_ok("2.8 KB", CFG_UNIT_SIZE), 2800);
    assert_int_equal(u64_ok("1.5 MiB", CFG_UNIT_SIZE), 1572864);
    assert_int_equal(u64_ok("16K", CFG_UNIT_COUNT), 16000);
    assert_int_equal(u64_ok("16", CFG_UNIT_COUNT), 16);
    assert_int_equal(u64_ok("2M", CFG_UNIT_COUNT), 2000000);
    assert_int_equal(u64_ok("18446744073709551615", CFG_UNIT_COUNT),
                     UINT64_MAX);
    assert_string_equal(u64_bad("1.5 B", CFG_UNIT_SIZE),
                        "a whole number of bytes");
    assert_string_equal(u64_bad("1.0001K", CFG_UNIT_COUNT), "a whole number");
    assert_non_null(strstr(u64_bad("16k", CFG_UNIT_COUNT), "K (1e3)"));
}

static void test_bandwidth_freq(void **state)
{
    (void)state;
    assert_true(dbl_ok("640 MB/s", CFG_UNIT_BANDWIDTH) == 640e6);
    assert_true(dbl_ok("2.8MB/s", CFG_UNIT_BANDWIDTH) == 2.8e6);
    assert_true(dbl_ok("1 Gbit/s", CFG_UNIT_BANDWIDTH) == 125e6);
    assert_true(dbl_ok("1 KiB/s", CFG_UNIT_BANDWIDTH) == 1024.0);
    assert_true(dbl_ok("1.5 GHz", CFG_UNIT_FREQ) == 1.5e9);
    assert_true(dbl_ok("40MHz", CFG_UNIT_FREQ) == 40e6);
    assert_true(dbl_ok("0", CFG_UNIT_FREQ) == 0.0);
}

static void test_bad(void **state)
{
    (void)state;
    const char *t = cfg_units_expected(CFG_UNIT_TIME);
    assert_string_equal(u64_bad("-5 us", CFG_UNIT_TIME), t); /* negative */
    assert_string_equal(u64_bad("us", CFG_UNIT_TIME), t);    /* no number */
    assert_string_equal(u64_bad("", CFG_UNIT_TIME), t);
    assert_string_equal(u64_bad(".", CFG_UNIT_TIME), t);
    assert_string_equal(u64_bad("5 furlongs", CFG_UNIT_TIME), t);
    assert_string_equal(u64_bad("5", CFG_UNIT_TIME), t);      /* no unit */
    assert_string_equal(u64_bad("5 US", CFG_UNIT_TIME), t);   /* case */
    assert_string_equal(u64_bad("5 us x", CFG_UNIT_TIME), t); /* junk */
    assert_string_equal(u64_bad("1e30 s", CFG_UNIT_TIME),
                        "a time below 2^64 ps (about 213 days)");
    assert_string_equal(u64_bad("18446744073709551616", CFG_UNIT_COUNT),
                        "a count below 2^64");
    assert_string_equal(u64_bad("20000000000 GiB", CFG_UNIT_SIZE),
                        "a size below 2^64 bytes");
    assert_string_equal(u64_bad("12345678901234567891 s", CFG_UNIT_TIME),
                        "a time below 2^64 ps (about 213 days)");
    assert_string_equal(u64_bad("1.234567890123456789012 s", CFG_UNIT_TIME),
                        "a number with at most 20 significant digits");
    assert_non_null(strstr(dbl_bad("640 MB", CFG_UNIT_BANDWIDTH), "MB/s"));
    assert_non_null(strstr(dbl_bad("-1 GHz", CFG_UNIT_FREQ), "GHz"));
    assert_string_equal(dbl_bad("1e999 B/s", CFG_UNIT_BANDWIDTH),
                        "a finite bandwidth");
    assert_non_null(dbl_bad("inf Hz", CFG_UNIT_FREQ));
    assert_non_null(dbl_bad("0x10 Hz", CFG_UNIT_FREQ));
}

/* The common spellings a user types (issue 18): SI kB, bits per second
 * as b/s and bps, bytes per second as MBps, minutes and hours; and the
 * look-alikes that stay wrong (a unit of the wrong kind, wrong case). */
static void test_common_spellings(void **state)
{
    (void)state;
    assert_int_equal(u64_ok("10kB", CFG_UNIT_SIZE), 10000);
    assert_int_equal(u64_ok("10 KB", CFG_UNIT_SIZE), 10000);
    assert_int_equal(u64_ok("2min", CFG_UNIT_TIME), 120 * SIM_S);
    assert_int_equal(u64_ok("1.5 h", CFG_UNIT_TIME), 5400 * SIM_S);
    assert_int_equal(u64_ok("0.5 min", CFG_UNIT_TIME), 30 * SIM_S);
    assert_true(dbl_ok("1 Gbps", CFG_UNIT_BANDWIDTH) == 125e6);
    assert_true(dbl_ok("1 Gb/s", CFG_UNIT_BANDWIDTH) == 125e6);
    assert_true(dbl_ok("8 Mbps", CFG_UNIT_BANDWIDTH) == 1e6);
    assert_true(dbl_ok("2.8MBps", CFG_UNIT_BANDWIDTH) == 2.8e6);
    assert_true(dbl_ok("2.8 MB/s", CFG_UNIT_BANDWIDTH) == 2.8e6);
    assert_true(dbl_ok("10 kB/s", CFG_UNIT_BANDWIDTH) == 1e4);
    assert_true(dbl_ok("20 KHz", CFG_UNIT_FREQ) == 2e4);
    u64_bad("10 kb", CFG_UNIT_SIZE);   /* bits are not a size */
    u64_bad("2 mins", CFG_UNIT_TIME);  /* not a unit */
    u64_bad("2 m", CFG_UNIT_TIME);     /* metres or minutes: refused */
    dbl_bad("1 GBit/s", CFG_UNIT_BANDWIDTH);
    dbl_bad("1 Gbps/s", CFG_UNIT_BANDWIDTH);
    assert_non_null(strstr(u64_bad("1 parsec", CFG_UNIT_TIME), "min"));
}

static void test_flag_parsers(void **state)
{
    (void)state;
    GError *e = NULL;
    SimTime t = 0;
    assert_true(cfg_parse_time("1us", "--lookahead", &t, &e));
    assert_int_equal(t, SIM_US);
    assert_false(cfg_parse_time("1", "--lookahead", &t, &e));
    assert_int_equal(sim_error_exit_status(e), 2);
    assert_non_null(strstr(e->message, "--lookahead: found '1', expected a "
                                       "non-negative time"));
    g_clear_error(&e);
    uint64_t n = 0;
    assert_false(cfg_parse_count("x", "--lps", &n, &e));
    assert_non_null(strstr(e->message, "--lps: found 'x', expected"));
    g_clear_error(&e);
    assert_true(cfg_parse_size("1 MiB", "--bytes", &n, &e));
    assert_int_equal(n, 1048576);
    double bw = 0;
    assert_true(cfg_parse_bandwidth("40 MB/s", "--bw", &bw, &e));
    assert_true(bw == 40e6);
}

static void test_units_edges(void **state)
{
    (void)state;
    assert_int_equal(u64_ok("  5 us", CFG_UNIT_TIME), 5 * SIM_US);
    assert_int_equal(u64_ok("+5 us", CFG_UNIT_TIME), 5 * SIM_US);
    assert_int_equal(u64_ok("1.50 us", CFG_UNIT_TIME), 1500000);
    assert_int_equal(u64_ok("1.500000 ns", CFG_UNIT_TIME), 1500);
    assert_int_equal(u64_ok("0.000 s", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_ok("2e3 ps", CFG_UNIT_TIME), 2000);
    assert_int_equal(u64_ok("2e+3 ps", CFG_UNIT_TIME), 2000);
    assert_int_equal(u64_ok("2000e-3 ns", CFG_UNIT_TIME), 2000);
    assert_true(dbl_ok("1 B/s", CFG_UNIT_BANDWIDTH) == 1.0);
    assert_true(dbl_ok("0 B/s", CFG_UNIT_BANDWIDTH) == 0.0);
    assert_true(dbl_ok("1 Hz", CFG_UNIT_FREQ) == 1.0);
    assert_string_equal(dbl_bad("0.5 B/s", CFG_UNIT_BANDWIDTH),
                        "0 or at least 1 B/s");
    assert_string_equal(dbl_bad("0.5 Hz", CFG_UNIT_FREQ),
                        "0 or at least 1 Hz");
    assert_string_equal(dbl_bad("0.999 B/s", CFG_UNIT_BANDWIDTH),
                        "0 or at least 1 B/s");
    /* more than 20 significant digits: fine for a rate, not a time */
    assert_true(dbl_ok("1.000000000000000000000001 MB/s", CFG_UNIT_BANDWIDTH) ==
                1e6);
    assert_true(dbl_ok("123456789012345678901234 B/s", CFG_UNIT_BANDWIDTH) ==
                123456789012345678901234.0);
    uint64_t v;
    const char *exp = NULL;
    assert_false(cfg_units_u64("1.000000000000000000000001 us", CFG_UNIT_TIME,
                               &v, &exp));
    assert_non_null(strstr(exp, "at most 20 significant"));
    assert_false(cfg_units_u64("-1 us", CFG_UNIT_TIME, &v, &exp));
    assert_false(cfg_units_u64("1e us", CFG_UNIT_TIME, &v, &exp));
    assert_false(cfg_units_u64("1e+ us", CFG_UNIT_TIME, &v, &exp));
}

/* Exact scaling at its edges: half a picosecond rounds up, a fraction of
 * a byte or a count is refused, 2^64 - 1 fits and 2^64 does not, and a
 * divisor of 10^19 (the largest that fits) still rounds. */
static void test_units_exact_edges(void **state)
{
    (void)state;
    assert_int_equal(u64_ok("0.5 ps", CFG_UNIT_TIME), 1);
    assert_int_equal(u64_ok("0.49 ps", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_ok("0.51 ps", CFG_UNIT_TIME), 1);
    assert_int_equal(u64_ok("2.5 ps", CFG_UNIT_TIME), 3);
    assert_int_equal(u64_ok("1.4999 ps", CFG_UNIT_TIME), 1);
    assert_int_equal(u64_ok("0.0015 us", CFG_UNIT_TIME), 1500);
    assert_int_equal(u64_ok("000123 ns", CFG_UNIT_TIME), 123000);
    assert_int_equal(u64_ok("1234567890 ps", CFG_UNIT_TIME), 1234567890);
    assert_int_equal(u64_ok("9999999999999999999e-19 ps", CFG_UNIT_TIME), 1);
    assert_int_equal(u64_ok("4999999999999999999e-19 ps", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_ok("18446744073709551615e-20 ps", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_ok("1e-40 ps", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_ok("1e-41 ps", CFG_UNIT_TIME), 0);
    assert_int_equal(u64_ok("18446744073709551615 ps", CFG_UNIT_TIME),
                     UINT64_MAX);
    assert_int_equal(u64_ok("1844674407370955161e1 ps", CFG_UNIT_TIME),
                     18446744073709551610ull);
    assert_string_equal(u64_bad("18446744073709551616 ps", CFG_UNIT_TIME),
                        "a time below 2^64 ps (about 213 days)");
    assert_string_equal(u64_bad("1844674407370955162e1 ps", CFG_UNIT_TIME),
                        "a time below 2^64 ps (about 213 days)");
    assert_int_equal(u64_ok("17179869183 GiB", CFG_UNIT_SIZE),
                     (17179869183ull << 30));
    assert_string_equal(u64_bad("17179869184 GiB", CFG_UNIT_SIZE),
                        "a size below 2^64 bytes");
    assert_int_equal(u64_ok("16777215 TiB", CFG_UNIT_SIZE), 16777215ull << 40);
    assert_string_equal(u64_bad("16777216 TiB", CFG_UNIT_SIZE),
                        "a size below 2^64 bytes");
    assert_string_equal(u64_bad("0.5 B", CFG_UNIT_SIZE),
                        "a whole number of bytes");
    assert_string_equal(u64_bad("1e-41 B", CFG_UNIT_SIZE),
                        "a whole number of bytes");
    assert_string_equal(u64_bad("1e-20 B", CFG_UNIT_SIZE),
                        "a whole number of bytes");
    assert_int_equal(u64_ok("0e-50 B", CFG_UNIT_SIZE), 0);
    assert_int_equal(u64_ok("1.5 KiB", CFG_UNIT_SIZE), 1536);
    assert_string_equal(u64_bad("1.5", CFG_UNIT_COUNT), "a whole number");
    assert_int_equal(u64_ok("2.5K", CFG_UNIT_COUNT), 2500);
    assert_int_equal(u64_ok("0", CFG_UNIT_SIZE), 0);
    assert_int_equal(u64_ok("0", CFG_UNIT_TIME), 0);
    assert_non_null(u64_bad("5", CFG_UNIT_TIME));
    assert_non_null(u64_bad(":5 us", CFG_UNIT_TIME));
    assert_non_null(u64_bad("5: us", CFG_UNIT_TIME));
    assert_non_null(u64_bad("5/ us", CFG_UNIT_TIME));
    assert_non_null(u64_bad(". us", CFG_UNIT_TIME));
    assert_true(dbl_ok("1e-401 B/s", CFG_UNIT_BANDWIDTH) == 0.0);
    assert_string_equal(dbl_bad("1e309 B/s", CFG_UNIT_BANDWIDTH),
                        "a finite bandwidth");
    assert_string_equal(dbl_bad("1e400 GHz", CFG_UNIT_FREQ),
                        "a finite frequency");
    assert_true(dbl_ok("1.5e3 kB/s", CFG_UNIT_BANDWIDTH) == 1.5e6);
}

/* A 20-digit mantissa times a binary or sexagesimal factor passes 2^64
 * before the division by a power of ten brings it back: the scaling is
 * exact in 128 bits.  5^27 x 2^40 / 10^27 = 2^13; 12345678901234567891 x
 * 3600e12 / 1e20 = 444444440444444.44 ps; N x 3.6 for N =
 * 5124095576030431004 is 2^64 - 1.6, which rounds to 2^64 - 2, and the
 * next N overflows. */
static void test_units_wide_intermediate(void **state)
{
    (void)state;
    assert_int_equal(u64_ok("7450580596923828125e-27 TiB", CFG_UNIT_SIZE),
                     8192);
    assert_int_equal(u64_ok("12345678901234567891e-20 h", CFG_UNIT_TIME),
                     444444440444444ULL);
    assert_string_equal(u64_bad("18446744073709551615e-19 TiB", CFG_UNIT_SIZE),
                        "a whole number of bytes");
    assert_true(u64_ok("5124095576030431004e-15 h", CFG_UNIT_TIME) ==
                UINT64_MAX - 1);
    assert_string_equal(u64_bad("5124095576030431005e-15 h", CFG_UNIT_TIME),
                        "a time below 2^64 ps (about 213 days)");
    assert_int_equal(u64_ok("0e99999 s", CFG_UNIT_TIME), 0);
    /* far beyond 128 bits both ways: refused, and 0 (or inexact) */
    assert_string_equal(u64_bad("1e200 ps", CFG_UNIT_TIME),
                        "a time below 2^64 ps (about 213 days)");
    assert_int_equal(u64_ok("1e-200 ps", CFG_UNIT_TIME), 0);
    assert_string_equal(u64_bad("1e-200 B", CFG_UNIT_SIZE),
                        "a whole number of bytes");
}

int main(void)
{
    support_warnings_fatal();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_times),
        cmocka_unit_test(test_sizes_counts),
        cmocka_unit_test(test_bandwidth_freq),
        cmocka_unit_test(test_bad),
        cmocka_unit_test(test_common_spellings),
        cmocka_unit_test(test_flag_parsers),
        cmocka_unit_test(test_units_edges),
        cmocka_unit_test(test_units_exact_edges),
        cmocka_unit_test(test_units_wide_intermediate),
    };
    return cmocka_run_group_tests_name("units", tests, NULL, NULL);
}
