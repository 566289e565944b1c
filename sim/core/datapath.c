/* datapath.c — data-file search (see datapath.h for the order). */
#include "sim/core/datapath.h"
#include "sim/core/error.h"

#include <errno.h>
#include <glib/gstdio.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

char **sim_env_dirs(const char *var)
{
    const char *env = g_getenv(var);
    char **list = g_strsplit(env ? env : "", ":", -1);
    guint n = 0;
    for (char **d = list; *d; d++)
        if (**d)
            list[n++] = *d;
        else
            g_free(*d);
    list[n] = NULL;
    return list;
}

GPtrArray *sim_data_roots(void)
{
    GPtrArray *roots = g_ptr_array_new_with_free_func(g_free);
    char **dirs = sim_env_dirs("PGSIM_DATA");
    for (char **r = dirs; *r; r++)
        g_ptr_array_add(roots, g_strdup(*r));
    g_strfreev(dirs);
    char *exe = g_file_read_link("/proc/self/exe", NULL);
    if (exe) {
        char *bindir = g_path_get_dirname(exe);
        g_ptr_array_add(roots, g_build_filename(bindir, "..", NULL));
        g_ptr_array_add(roots,
                        g_build_filename(bindir, "..", "share", "pgsim", NULL));
        g_free(bindir);
        g_free(exe);
    }
    return roots;
}

char *sim_data_path(const char *name)
{
    if (g_path_is_absolute(name) || g_file_test(name, G_FILE_TEST_EXISTS))
        return g_strdup(name);
    GPtrArray *roots = sim_data_roots();
    char *hit = NULL;
    for (guint i = 0; !hit && i < roots->len; i++) {
        char *p = g_build_filename(roots->pdata[i], name, NULL);
        if (g_file_test(p, G_FILE_TEST_EXISTS))
            hit = p;
        else
            g_free(p);
    }
    g_ptr_array_free(roots, TRUE);
    return hit ? hit : g_strdup(name);
}

static guint64 file_limit;

void sim_file_set_limit(guint64 bytes)
{
    file_limit = bytes;
}

/* $PGSIM_MAX_INPUT as bytes (k, M, G multiply by 2^10, 2^20, 2^30); 0 if
 * unset or malformed (then the default applies). */
static guint64 env_limit(void)
{
    const char *s = g_getenv("PGSIM_MAX_INPUT");
    char *end = NULL;
    if (!s || !*s)
        return 0;
    errno = 0;
    guint64 v = g_ascii_strtoull(s, &end, 10);
    gboolean range = errno == ERANGE; /* saturated at 2^64 - 1 */
    int shift = *end == 'k' ? 10 : *end == 'M' ? 20 : *end == 'G' ? 30 : 0;
    if (shift)
        end++;
    if (*end || range || v > (G_MAXUINT64 >> shift))
        return 0;
    return v << shift;
}

guint64 sim_file_limit(void)
{
    if (file_limit)
        return file_limit;
    guint64 env = env_limit();
    return env ? env : SIM_FILE_LIMIT_DEFAULT;
}

static gboolean io_fail(GError **err, const char *path, const char *found,
                        const char *expected)
{
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO, "%s:0:0: found %s, expected %s",
                path, found, expected);
    return FALSE;
}

static const char *kind_of(mode_t m)
{
    return S_ISDIR(m)    ? "a directory"
           : S_ISCHR(m)  ? "a character device"
           : S_ISBLK(m)  ? "a block device"
           : S_ISFIFO(m) ? "a pipe"
           : S_ISSOCK(m) ? "a socket"
                         : "a special file";
}

/* Checks the open file's type and size; *size receives its size. */
static gboolean check_stat(int fd, const char *path, gsize *size,
                           GError **err)
{
    struct stat st;
    if (fstat(fd, &st) != 0)
        return io_fail(err, path, g_strerror(errno), "a readable file");
    if (!S_ISREG(st.st_mode))
        return io_fail(err, path, kind_of(st.st_mode), "a regular file");
    guint64 limit = sim_file_limit();
    if ((guint64)st.st_size > limit) {
        char *f = g_strdup_printf("%" G_GUINT64_FORMAT " bytes",
                                  (guint64)st.st_size);
        char *e = g_strdup_printf("at most %" G_GUINT64_FORMAT
                                  " bytes (raise with PGSIM_MAX_INPUT)",
                                  limit);
        io_fail(err, path, f, e);
        g_free(f);
        g_free(e);
        return FALSE;
    }
    *size = (gsize)st.st_size;
    return TRUE;
}

/* Reads exactly `size` bytes (the file may not grow or shrink meanwhile). */
static gboolean read_all(int fd, const char *path, char *buf, gsize size,
                         GError **err)
{
    gsize got = 0;
    while (got < size) {
        ssize_t n = read(fd, buf + got, size - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return io_fail(err, path,
                           n < 0 ? g_strerror(errno) : "a file that shrank",
                           "a readable file");
        got += (gsize)n;
    }
    char extra;
    if (read(fd, &extra, 1) > 0)
        return io_fail(err, path, "a file that grew while read",
                       "a file not being written");
    return TRUE;
}

gboolean sim_file_read(const char *path, char **text, gsize *len,
                       GError **err)
{
    int fd = open(path, O_RDONLY | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        char *found = g_strdup_printf("an unreadable file (%s)",
                                      g_strerror(errno));
        io_fail(err, path, found, "a readable file");
        g_free(found);
        return FALSE;
    }
    gsize size = 0;
    char *buf = NULL;
    gboolean ok = check_stat(fd, path, &size, err);
    if (ok) {
        buf = g_try_malloc(size + 1);
        ok = buf ? read_all(fd, path, buf, size, err)
                 : io_fail(err, path, "too little memory for the file",
                           "a smaller file");
    }
    close(fd);
    if (!ok) {
        g_free(buf);
        return FALSE;
    }
    buf[size] = 0;
    *text = buf;
    if (len)
        *len = size;
    return TRUE;
}

gboolean sim_file_write(const char *path, const void *data, gsize len,
                        GError **err)
{
    GError *e = NULL;
    if (g_file_set_contents_full(path, data, (gssize)len,
                                 G_FILE_SET_CONTENTS_CONSISTENT |
                                     G_FILE_SET_CONTENTS_DURABLE,
                                 0666, &e))
        return TRUE;
    g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                "%s: found %s, expected a writable file", path, e->message);
    g_error_free(e);
    return FALSE;
}

gboolean sim_move_into(const char *stage, const char *dir, const char *name,
                       GError **err)
{
    char *from = g_build_filename(stage, name, NULL);
    char *to = g_build_filename(dir, name, NULL);
    gboolean ok = g_rename(from, to) == 0;
    if (!ok) {
        int e = errno;
        g_set_error(err, SIM_ERROR, SIM_ERROR_IO,
                    "%s: found %s, expected a writable file", to,
                    g_strerror(e));
    }
    g_free(to);
    g_free(from);
    return ok;
}
