/* sweep_lock.h — one sweep at a time in an output folder.
 *
 * Two different sweeps writing to one --out at once would mix their rows
 * under one provenance.  A runner takes the folder's lock for the whole
 * run, finishing included; a second runner of a different sweep (another
 * fingerprint, sweep_spec_fingerprint()) is refused with an I/O error
 * naming the folder, while the same sweep run twice at once shares the
 * lock as before (its rows are the same, and finishing keeps one line per
 * point).  The lock is flock(2)-based, so it ends with the process: a
 * killed sweep never blocks the next.
 */
#ifndef PGSIM_APP_SWEEP_SWEEP_LOCK_H
#define PGSIM_APP_SWEEP_SWEEP_LOCK_H

#include "sim/core/error.h"

typedef struct SweepLock SweepLock;

/* Creates dir if needed and locks it for the sweep `fingerprint`; returns
 * a new lock (sweep_lock_release()) or NULL with *err. */
SweepLock *sweep_lock_take(const char *dir, const char *fingerprint,
                           GError **err);
/* Releases and frees; NULL is a no-op. */
void sweep_lock_release(SweepLock *l);

#endif
