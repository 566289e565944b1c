/* memlimit.c — the process's memory limit and the check against it
 * (memlimit.h).  Physical memory comes from sysconf(_SC_PHYS_PAGES) x
 * the page size (POSIX/glibc), lowered by getrlimit(RLIMIT_AS and
 * RLIMIT_DATA) and a cgroup v2 memory.max; O(1) after the first call. */
#include "sim/core/memlimit.h"
#include "sim/core/error.h"

#include <errno.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

static guint64 set_limit;

void sim_mem_set_limit(guint64 bytes)
{
    set_limit = bytes;
}

gboolean sim_mem_parse(const char *text, guint64 *out)
{
    char *end = NULL;
    if (!text || !g_ascii_isdigit(*text))
        return FALSE;
    errno = 0;
    guint64 v = g_ascii_strtoull(text, &end, 10);
    gboolean range = errno == ERANGE; /* saturated at 2^64 - 1 */
    const char *units = "kMGT";
    const char *u = *end ? strchr(units, *end) : NULL;
    int shift = u ? 10 * (int)(u - units + 1) : 0;
    if (u)
        end++;
    if (*end || v == 0 || range || v > (G_MAXUINT64 >> shift))
        return FALSE;
    *out = v << shift;
    return TRUE;
}

/* The smaller of v and a resource limit's soft value (if set). */
static guint64 below_rlimit(guint64 v, int resource)
{
    struct rlimit rl;
    if (getrlimit(resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        v = MIN(v, (guint64)rl.rlim_cur);
    return v;
}

/* The smaller of v and the cgroup (v2) memory limit, if one is set. */
static guint64 below_cgroup(guint64 v)
{
    char *text = NULL;
    guint64 max;
    if (g_file_get_contents("/sys/fs/cgroup/memory.max", &text, NULL, NULL) &&
        g_ascii_string_to_unsigned(g_strstrip(text), 10, 1, G_MAXUINT64, &max,
                                   NULL))
        v = MIN(v, max);
    g_free(text);
    return v;
}

/* Physical memory, or less when this process may not have it all: an
 * address-space or data limit (ulimit -v, -d) or a cgroup's memory.max,
 * so that an estimate under the limit can also be allocated.  Read once. */
static guint64 physical(void)
{
    static guint64 cached;
    if (cached)
        return cached;
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    guint64 v = pages <= 0 || size <= 0
                    ? (guint64)1 << 32 /* assumption: 4 GiB when unknown */
                    : (guint64)pages * (guint64)size;
    v = below_cgroup(below_rlimit(below_rlimit(v, RLIMIT_AS), RLIMIT_DATA));
    cached = v;
    return v;
}

guint64 sim_mem_limit(void)
{
    guint64 env = 0;
    if (set_limit)
        return set_limit;
    if (sim_mem_parse(g_getenv("PGSIM_MEM_LIMIT"), &env))
        return env;
    return physical();
}

/* "512.0 KiB", "38.0 GiB": one decimal in the largest binary unit that
 * keeps the number at least 1 (g_format_size() puts a no-break space
 * between number and unit, which a grep for "4.0 GiB" does not find). */
static const char *size_text(double bytes, char buf[32])
{
    static const char *const unit[] = {"B", "KiB", "MiB", "GiB", "TiB",
                                       "PiB", "EiB"};
    guint u = 0;
    while (bytes >= 1024.0 && u + 1 < G_N_ELEMENTS(unit)) {
        bytes /= 1024.0;
        u++;
    }
    g_snprintf(buf, 32, u ? "%.1f %s" : "%.0f %s", bytes, unit[u]);
    return buf;
}

gboolean sim_mem_check(double bytes, const char *where, const char *what,
                       GError **err)
{
    double limit = (double)sim_mem_limit();
    if (bytes <= limit)
        return TRUE;
    char need[32], have[32];
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s: found %s needing about %s, expected at most %s "
                "(--mem-limit; docs/config.md, Limits)",
                where, what, size_text(bytes, need), size_text(limit, have));
    return FALSE;
}
