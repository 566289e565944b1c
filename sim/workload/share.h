/* share.h — what consecutive runs may share (CfgRunOpts.share, given to
 * the workload as WlContext.share).
 *
 * A caller that runs many cases of one scene (a reproduction: 44 cases
 * of the vehicle, each rendering the same frames) hands every run one
 * WlShare; a workload keeps there what it computed from its inputs
 * alone (a frame rasterised once, a chunk database), under a key that
 * names every input it depends on, and takes it back in the next run
 * instead of computing it again.  What a run gives must not depend on
 * whether a share was given: a workload uses one only where the kept
 * object equals what it would compute.  Without a share (NULL, `pgsim
 * run`) nothing is kept.  Objects are freed with the share, or when a
 * key is put again.
 */
#ifndef PGSIM_WORKLOAD_SHARE_H
#define PGSIM_WORKLOAD_SHARE_H

#include <glib.h>

typedef struct WlShare WlShare;

WlShare *wl_share_new(void);
void wl_share_free(WlShare *s);

/* The object kept under `key` (borrowed), or NULL. */
void *wl_share_get(WlShare *s, const char *key);
/* Keeps `obj` under `key`, freeing the object kept there before with
 * its own free function; `free_fn` frees obj (may be NULL). */
void wl_share_put(WlShare *s, const char *key, void *obj,
                  GDestroyNotify free_fn);

#endif
