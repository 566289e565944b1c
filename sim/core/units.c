/* units.c — parsing numbers with units ("640 MB/s", "350us", "64KiB").
 *
 * A number is scanned into an exact decimal (mantissa, power of ten) of
 * at most 20 significant digits (what fits in 64 bits); a unit is an
 * exact, case-sensitive match in the kind's table and contributes a power of
 * ten, a power-of-two factor (KiB ...) and an optional division by 8 (bits).
 * Integer results are computed exactly in 128-bit arithmetic (mantissa x
 * factor x 10^e, divided last) and checked to fit 64 bits, so no binary
 * rounding ever enters a time, size or count;
 * doubles go through one correctly rounded g_ascii_strtod()
 * (locale-independent).
 *
 * Invariants: never accepts a negative value, a missing number, trailing
 * junk or a value that does not fit.  Complexity O(length of the text).
 */
#include "sim/core/units.h"
#include <string.h>

typedef struct {
    const char *sym;
    int pow10;    /* decimal scale */
    uint64_t bin; /* binary factor (1 unless KiB ...) */
    int div;      /* 8 for bit units, else 1 */
} Unit;

typedef struct {
    uint64_t mant;
    int exp10;
    const char *unit; /* points into the input, trimmed at the end */
    size_t unit_len;
} Num;

typedef enum { NUM_OK, NUM_NONE, NUM_NEG, NUM_DIGITS } NumStatus;

static const Unit time_units[] = {
    {"ps", 0, 1, 1},        {"ns", 3, 1, 1},        {"us", 6, 1, 1},
    {"\xc2\xb5s", 6, 1, 1}, {"\xce\xbcs", 6, 1, 1}, /* micro, mu */
    {"ms", 9, 1, 1},        {"s", 12, 1, 1},        {"sec", 12, 1, 1},
    {"min", 12, 60, 1},     {"h", 12, 3600, 1},     {NULL, 0, 0, 0},
};

/* Bytes per second, SI (k = 1e3, as written in the papers: K too) and
 * binary; bits per second (bit/s, b/s, bps); MBps spells MB/s. */
static const Unit bw_units[] = {
    {"B/s", 0, 1, 1},       {"kB/s", 3, 1, 1},      {"KB/s", 3, 1, 1},
    {"MB/s", 6, 1, 1},      {"GB/s", 9, 1, 1},      {"TB/s", 12, 1, 1},
    {"Bps", 0, 1, 1},       {"kBps", 3, 1, 1},      {"KBps", 3, 1, 1},
    {"MBps", 6, 1, 1},      {"GBps", 9, 1, 1},      {"KiB/s", 0, 1024, 1},
    {"MiB/s", 0, 1048576, 1}, {"GiB/s", 0, 1073741824, 1},
    {"bit/s", 0, 1, 8},     {"kbit/s", 3, 1, 8},    {"Kbit/s", 3, 1, 8},
    {"Mbit/s", 6, 1, 8},    {"Gbit/s", 9, 1, 8},    {"b/s", 0, 1, 8},
    {"kb/s", 3, 1, 8},      {"Kb/s", 3, 1, 8},      {"Mb/s", 6, 1, 8},
    {"Gb/s", 9, 1, 8},      {"bps", 0, 1, 8},       {"kbps", 3, 1, 8},
    {"Kbps", 3, 1, 8},      {"Mbps", 6, 1, 8},      {"Gbps", 9, 1, 8},
    {NULL, 0, 0, 0},
};

static const Unit freq_units[] = {
    {"Hz", 0, 1, 1},  {"kHz", 3, 1, 1}, {"KHz", 3, 1, 1},
    {"MHz", 6, 1, 1}, {"GHz", 9, 1, 1}, {NULL, 0, 0, 0},
};

static const Unit size_units[] = {
    {"B", 0, 1, 1},
    {"kB", 3, 1, 1},
    {"KB", 3, 1, 1},
    {"MB", 6, 1, 1},
    {"GB", 9, 1, 1},
    {"TB", 12, 1, 1},
    {"KiB", 0, 1024, 1},
    {"MiB", 0, 1048576, 1},
    {"GiB", 0, 1073741824, 1},
    {"TiB", 0, 1099511627776, 1},
    {NULL, 0, 0, 0},
};

static const Unit count_units[] = {
    {"", 0, 1, 1},
    {"K", 3, 1, 1},
    {"M", 6, 1, 1},
    {NULL, 0, 0, 0},
};

static const Unit *const tables[] = {
    [CFG_UNIT_TIME] = time_units,   [CFG_UNIT_BANDWIDTH] = bw_units,
    [CFG_UNIT_FREQ] = freq_units,   [CFG_UNIT_SIZE] = size_units,
    [CFG_UNIT_COUNT] = count_units,
};

static const char *const expected_text[] = {
    [CFG_UNIT_TIME] = "a non-negative time with a unit (ps, ns, us, "
                      "\xc2\xb5s, ms, s, min, h)",
    [CFG_UNIT_BANDWIDTH] = "a non-negative bandwidth with a unit (B/s, "
                           "kB/s, MB/s, GB/s, MBps, KiB/s, MiB/s, GiB/s, "
                           "bit/s, Mbit/s, Gbit/s, Mb/s, Gbps ...)",
    [CFG_UNIT_FREQ] = "a non-negative frequency with a unit (Hz, kHz, MHz, "
                      "GHz)",
    [CFG_UNIT_SIZE] = "a non-negative size with a unit (B, kB, KB, MB, GB, "
                      "TB, KiB, MiB, GiB, TiB)",
    [CFG_UNIT_COUNT] = "a non-negative integer, optionally with K (1e3) or "
                       "M (1e6)",
};

static const char *const overflow_text[] = {
    [CFG_UNIT_TIME] = "a time below 2^64 ps (about 213 days)",
    [CFG_UNIT_BANDWIDTH] = "a finite bandwidth",
    [CFG_UNIT_FREQ] = "a finite frequency",
    [CFG_UNIT_SIZE] = "a size below 2^64 bytes",
    [CFG_UNIT_COUNT] = "a count below 2^64",
};

const char *cfg_units_expected(CfgUnitKind kind)
{
    return expected_text[kind];
}

static gboolean is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* Adds one digit; `frac` digits lower the exponent once taken. */
static void add_digit(Num *n, int d, gboolean frac, gboolean *lossy)
{
    if (n->mant == 0 && d == 0) {
        if (frac)
            n->exp10--;
        return;
    }
    if (n->mant <= (UINT64_MAX - (uint64_t)d) / 10) {
        n->mant = n->mant * 10 + (uint64_t)d;
        if (frac)
            n->exp10--;
        return;
    }
    if (!frac)
        n->exp10++;
    if (d != 0)
        *lossy = TRUE;
}

static const char *scan_exponent(const char *p, Num *n)
{
    const char *q = p + 1;
    int sign = 1;
    if (*q == '+' || *q == '-')
        sign = *q++ == '-' ? -1 : 1;
    if (!is_digit(*q))
        return p; /* not an exponent: leave it to the unit */
    int e = 0;
    while (is_digit(*q)) {
        if (e < 100000)
            e = e * 10 + (*q - '0');
        q++;
    }
    n->exp10 += sign * e;
    return q;
}

static NumStatus scan_number(const char *s, Num *n)
{
    const char *p = s;
    int digits = 0;
    gboolean lossy = FALSE;
    memset(n, 0, sizeof *n);
    while (*p == ' ')
        p++;
    if (*p == '-')
        return NUM_NEG;
    if (*p == '+')
        p++;
    for (; is_digit(*p); p++, digits++)
        add_digit(n, *p - '0', FALSE, &lossy);
    if (*p == '.')
        for (p++; is_digit(*p); p++, digits++)
            add_digit(n, *p - '0', TRUE, &lossy);
    if (digits == 0)
        return NUM_NONE;
    if (*p == 'e' || *p == 'E')
        p = scan_exponent(p, n);
    while (*p == ' ')
        p++;
    n->unit = p;
    n->unit_len = strlen(p);
    while (n->unit_len > 0 && g_ascii_isspace(p[n->unit_len - 1]))
        n->unit_len--;
    return lossy ? NUM_DIGITS : NUM_OK;
}

static const Unit *find_unit(CfgUnitKind kind, const Num *n)
{
    for (const Unit *u = tables[kind]; u->sym; u++)
        if (strlen(u->sym) == n->unit_len &&
            memcmp(u->sym, n->unit, n->unit_len) == 0)
            return u;
    return NULL;
}

/* Scans and looks the unit up; a bare 0 gets the first (base) unit. */
static const Unit *parse(const char *s, CfgUnitKind kind, Num *n,
                         const char **expected)
{
    NumStatus st = scan_number(s, n);
    gboolean integral = kind == CFG_UNIT_TIME || kind == CFG_UNIT_SIZE ||
                        kind == CFG_UNIT_COUNT;
    if (st == NUM_DIGITS && !integral)
        st = NUM_OK; /* doubles round anyway */
    if (st == NUM_DIGITS) {
        *expected = n->exp10 > 0 ? overflow_text[kind]
                                 : "a number with at most 20 significant "
                                   "digits";
        return NULL;
    }
    if (st != NUM_OK) {
        *expected = expected_text[kind];
        return NULL;
    }
    const Unit *u = find_unit(kind, n);
    if (!u && n->unit_len == 0 && n->mant == 0)
        u = tables[kind]; /* 0 of the base unit: 0 whatever its factors */
    if (!u)
        *expected = expected_text[kind];
    return u;
}

/* mant * 10^e * bin exactly, in 128 bits (mant * bin < 2^104: bin is at
 * most 2^40), so a large mantissa with a negative exponent is divided
 * before any overflow is judged; non-integral results round half up
 * (times) or are inexact.  FALSE when the result is 2^64 or more. */
static gboolean scale_exact(uint64_t mant, int e, uint64_t bin, gboolean round,
                            uint64_t *out, gboolean *inexact)
{
    unsigned __int128 v = (unsigned __int128)mant * bin, d = 1;
    for (; e > 0; e--) {
        if (v > UINT64_MAX / 10)
            return FALSE;
        v *= 10;
    }
    if (e < -32) { /* d >= 10^33 > 2 v: the quotient rounds to 0 */
        *out = 0;
        *inexact = v != 0 && !round;
        return TRUE;
    }
    for (; e < 0; e++)
        d *= 10;
    unsigned __int128 q = v / d, r = v % d;
    *inexact = r != 0 && !round;
    if (round && r >= d - r)
        q++;
    *out = (uint64_t)q;
    return q <= UINT64_MAX;
}

gboolean cfg_units_u64(const char *s, CfgUnitKind kind, uint64_t *out,
                       const char **expected)
{
    g_assert(kind == CFG_UNIT_TIME || kind == CFG_UNIT_SIZE ||
             kind == CFG_UNIT_COUNT);
    Num n;
    const Unit *u = parse(s, kind, &n, expected);
    if (!u)
        return FALSE;
    gboolean inexact;
    if (!scale_exact(n.mant, n.exp10 + u->pow10, u->bin, kind == CFG_UNIT_TIME,
                     out, &inexact)) {
        *expected = overflow_text[kind];
        return FALSE;
    }
    if (inexact) {
        *expected = kind == CFG_UNIT_SIZE ? "a whole number of bytes"
                                          : "a whole number";
        return FALSE;
    }
    return TRUE;
}

gboolean cfg_units_double(const char *s, CfgUnitKind kind, double *out,
                          const char **expected)
{
    Num n;
    const Unit *u = parse(s, kind, &n, expected);
    if (!u)
        return FALSE;
    int e = n.exp10 + u->pow10;
    if (e > 400 || e < -400) {
        e = e > 0 ? 400 : -400; /* keeps the text short; same result */
    }
    char buf[48];
    g_snprintf(buf, sizeof buf, "%" G_GUINT64_FORMAT "e%d", n.mant, e);
    double v = g_ascii_strtod(buf, NULL) * (double)u->bin / u->div;
    if (!isfinite(v)) {
        *expected = overflow_text[kind];
        return FALSE;
    }
    /* A rate is 0 (none) or at least 1 per second: below that one byte or
     * one cycle already takes longer than a run can simulate sensibly,
     * and 1e-300 B/s overflowed simulated time at run time, unlocated. */
    if (v != 0 && v < 1.0 &&
        (kind == CFG_UNIT_BANDWIDTH || kind == CFG_UNIT_FREQ)) {
        *expected = kind == CFG_UNIT_BANDWIDTH ? "0 or at least 1 B/s"
                                               : "0 or at least 1 Hz";
        return FALSE;
    }
    *out = v;
    return TRUE;
}
