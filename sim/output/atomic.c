/* atomic.c — write to a temporary file, fsync, rename (atomic.h).
 *
 * POSIX rename() within one file system replaces the target atomically,
 * which is why the temporary file lives in the target's directory.
 * Cost: one extra fsync of the file and one of the directory.
 */
#include "sim/output/atomic.h"
#include "sim/core/error.h"
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

static gboolean io_error(GError **err, const char *path, int errnum)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                "%s: found %s, expected a writable file", path,
                g_strerror(errnum));
    return FALSE;
}

static gboolean write_all(int fd, const char *p, size_t len)
{
    while (len > 0) {
        ssize_t n = write(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return FALSE;
        p += n;
        len -= (size_t)n;
    }
    return TRUE;
}

/* Makes the rename durable; failures here do not undo the write. */
static void sync_dir(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
}

gboolean rpt_write_atomic(const char *path, const void *data, size_t len,
                          GError **err)
{
    char *dir = g_path_get_dirname(path);
    char *base = g_path_get_basename(path);
    char *name = g_strdup_printf(".%s.XXXXXX", base);
    char *tmp = g_build_filename(dir, name, NULL);
    int fd = g_mkstemp_full(tmp, O_WRONLY | O_CLOEXEC, 0644);
    int errnum = fd < 0 ? errno : 0;
    if (fd >= 0) {
        errno = 0;
        if (fchmod(fd, 0644) != 0 || !write_all(fd, data, len) ||
            fsync(fd) != 0)
            errnum = errno ? errno : EIO;
        if (close(fd) != 0 && !errnum)
            errnum = errno;
        if (!errnum && rename(tmp, path) != 0)
            errnum = errno;
        if (errnum)
            unlink(tmp);
        else
            sync_dir(dir);
    }
    g_free(dir);
    g_free(base);
    g_free(name);
    g_free(tmp);
    return errnum ? io_error(err, path, errnum) : TRUE;
}
