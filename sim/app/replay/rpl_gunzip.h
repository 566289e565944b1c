/* rpl_gunzip.h — a gzip decompressor (GConverter) that reads every member
 * of a file.
 *
 * RFC 1952 section 2.2: a gzip file is a series of members; `cat a.gz
 * b.gz > c.gz` is a valid gzip file whose content is a then b.  GLib's
 * GZlibDecompressor stops at the end of the first member (zlib's inflate
 * returns Z_STREAM_END there) and the rest of the file is silently lost.
 * RplGunzip wraps one and starts it again on the bytes that follow a
 * member; bytes that are not a gzip member are an error (zlib's "incorrect
 * header check"), as is a member cut short.  O(bytes).
 */
#ifndef PGSIM_APP_REPLAY_RPL_GUNZIP_H
#define PGSIM_APP_REPLAY_RPL_GUNZIP_H

#include <gio/gio.h>

/* Returns a new decompressor; free with g_object_unref(). */
GConverter *rpl_gunzip_new(void);

#endif
