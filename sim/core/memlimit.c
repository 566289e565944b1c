/* memlimit.c — the process's memory limit and the check against it
 * (memlimit.h).  Physical memory comes from sysconf(_SC_PHYS_PAGES) x
 * the page size (POSIX/glibc); O(1). */
#include "sim/core/memlimit.h"
#include "sim/core/error.h"

#include <errno.h>
#include <string.h>
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

static guint64 physical(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || size <= 0)
        return (guint64)1 << 32; /* assumption: 4 GiB when unknown */
    return (guint64)pages * (guint64)size;
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

gboolean sim_mem_check(double bytes, const char *where, const char *what,
                       GError **err)
{
    double limit = (double)sim_mem_limit();
    if (bytes <= limit)
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_INPUT,
                "%s: found %s needing about %.0f MiB, expected at most %.0f "
                "MiB (--mem-limit; docs/config.md, Limits)",
                where, what, bytes / 1048576.0, limit / 1048576.0);
    return FALSE;
}
