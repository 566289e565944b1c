/* memlimit.h — the memory a run may ask for, checked before allocating.
 *
 * Sizes the user chooses (an isosurface grid, a triangle or teapot count,
 * an image, a machine's node count) are turned into an estimate of bytes
 * by the code that will allocate them, and sim_mem_check() compares the
 * estimate with the limit: by default the machine's physical memory
 * (sysconf), changed with `--mem-limit` (pgsim run / validate / render /
 * sweep) or $PGSIM_MEM_LIMIT.  An estimate over the limit is an input
 * error naming the size, never a GLib abort.  Estimates are doubles so a
 * product of user sizes cannot wrap.  Process-wide state (one limit per
 * process); O(1).
 */
#ifndef PGSIM_CORE_MEMLIMIT_H
#define PGSIM_CORE_MEMLIMIT_H

#include <glib.h>

/* The limit in bytes: sim_mem_set_limit()'s, else $PGSIM_MEM_LIMIT's
 * (bytes with an optional k/M/G/T suffix), else physical memory or the
 * process's address-space, data or cgroup limit if smaller. */
guint64 sim_mem_limit(void);
/* 0 restores the default. */
void sim_mem_set_limit(guint64 bytes);
/* Parses "512M", "8G", "1000000" (bytes; k/M/G/T are powers of 1024);
 * FALSE when malformed or zero. */
gboolean sim_mem_parse(const char *text, guint64 *out);

/* TRUE when `bytes` fit the limit; otherwise FALSE with an input error
 * "<where>: found <what> needing about N MiB, expected at most M MiB
 * (--mem-limit; docs/config.md, Limits)".  `where` is "file:line:col"
 * (or a flag name) and `what` names the size ("grid 1024"). */
gboolean sim_mem_check(double bytes, const char *where, const char *what,
                       GError **err);

#endif
