/* sweep_lock.c — one sweep at a time in an output folder (sweep_lock.h).
 *
 * Each runner holds a shared flock(2) on <dir>/.sweep-<fp>.lock, <fp> the
 * first 16 hex digits of its fingerprint, for as long as it writes.  To
 * get there it first takes <dir>/.sweep.lock exclusively (a short
 * critical section, so two starts cannot pass each other), tries each
 * other .sweep-*.lock with LOCK_EX|LOCK_NB: one that is held belongs to a
 * running sweep, and the runner is refused; one that is not was left by
 * a finished or killed sweep and is removed.  Then it takes its own
 * shared lock and lets go of .sweep.lock.  O(files in dir).
 */
#include "sim/app/sweep/sweep_lock.h"
#include <errno.h>
#include <fcntl.h>
#include <glib/gstdio.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

#define FP_DIGITS 16

struct SweepLock {
    int fd;
};

static gboolean os_error(GError **err, const char *path, const char *what)
{
    int e = errno;
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s: found %s, expected %s",
                path, g_strerror(e), what);
    return FALSE;
}

/* Opens (creating) path and flocks it with op; -1 with errno. */
static int lock_file(const char *path, int op)
{
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0)
        return -1;
    int r;
    do
        r = flock(fd, op);
    while (r != 0 && errno == EINTR);
    if (r != 0) {
        int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    return fd;
}

/* FALSE with *err when a lock of another sweep is held in dir; removes
 * the stale ones.  Called under .sweep.lock. */
static gboolean no_other_sweep(const char *dir, const char *mine,
                               GError **err)
{
    GDir *d = g_dir_open(dir, 0, NULL);
    const char *name;
    gboolean ok = TRUE;
    while (ok && d && (name = g_dir_read_name(d))) {
        if (!g_str_has_prefix(name, ".sweep-") ||
            !g_str_has_suffix(name, ".lock") || strcmp(name, mine) == 0)
            continue;
        char *path = g_build_filename(dir, name, NULL);
        int fd = lock_file(path, LOCK_EX | LOCK_NB);
        if (fd >= 0) {
            g_remove(path); /* stale: its sweep has ended */
            close(fd);
        } else if (errno == EWOULDBLOCK) {
            g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                        "%s: found another sweep writing there (lock %s), "
                        "expected one sweep at a time in an output folder "
                        "(wait for it to end, or use another --out)",
                        dir, name);
            ok = FALSE;
        } else {
            ok = os_error(err, path, "a lock file that can be opened");
        }
        g_free(path);
    }
    if (d)
        g_dir_close(d);
    return ok;
}

SweepLock *sweep_lock_take(const char *dir, const char *fingerprint,
                           GError **err)
{
    if (g_mkdir_with_parents(dir, 0777) != 0) {
        os_error(err, dir, "a folder that can be created");
        return NULL;
    }
    char *gate = g_build_filename(dir, ".sweep.lock", NULL);
    char *mine = g_strdup_printf(".sweep-%.*s.lock", FP_DIGITS, fingerprint);
    char *own = g_build_filename(dir, mine, NULL);
    SweepLock *l = NULL;
    int g = lock_file(gate, LOCK_EX);
    if (g < 0)
        os_error(err, gate, "a lock file that can be opened");
    else if (no_other_sweep(dir, mine, err)) {
        int fd = lock_file(own, LOCK_SH);
        if (fd < 0)
            os_error(err, own, "a lock file that can be opened");
        else {
            l = g_new0(SweepLock, 1);
            l->fd = fd;
        }
    }
    if (g >= 0)
        close(g);
    g_free(own);
    g_free(mine);
    g_free(gate);
    return l;
}

void sweep_lock_release(SweepLock *l)
{
    if (!l)
        return;
    close(l->fd); /* the file stays; the next runner removes it */
    g_free(l);
}
