/* progress.h — a one-line progress display on stderr.
 *
 * Shown only when stderr is a terminal (isatty) and the caller is not
 * quiet; otherwise every call is a cheap no-op, so piped output never
 * gets progress noise.  Redraws at most 10 times per second of wall
 * clock.  Used by run, sweep and reproduce.  All functions accept NULL.
 */
#ifndef PGSIM_OUTPUT_PROGRESS_H
#define PGSIM_OUTPUT_PROGRESS_H

#include "sim/core/engine.h"
#include <stdio.h>

typedef struct RptProgress RptProgress;

/* Returns a new display for `total` steps (0: unknown, shows a count)
 * labelled `label`, or NULL when stderr is not a terminal.  Free with
 * rpt_progress_finish(). */
RptProgress *rpt_progress_new(uint64_t total, const char *label);
/* The same on any stream (NULL: disabled) and wall clock in microseconds
 * (NULL: g_get_monotonic_time); for tests. */
RptProgress *rpt_progress_new_full(uint64_t total, const char *label, FILE *out,
                                   gint64 (*clock_us)(void));
/* Records `done` steps; redraws if 100 ms have passed since the last. */
void rpt_progress_update(RptProgress *p, uint64_t done);
/* Steps recorded so far (0 for NULL). */
uint64_t rpt_progress_done(const RptProgress *p);
/* Sets a short text shown after the count ("2 failed"); NULL clears it.
 * With a known total, an ETA (elapsed / done * remaining) follows. */
void rpt_progress_note(RptProgress *p, const char *note);
/* Draws the final state, ends the line and frees p. */
void rpt_progress_finish(RptProgress *p);
/* Drives p from an engine: done = events run, with the simulated time
 * shown; the engine calls back every 16K events. */
void rpt_progress_attach(RptProgress *p, SimEngine *eng);

#endif
