/* rp_speed.h — speed against error: one reproduction at every network
 * fidelity (`pgsim reproduce NAME --fidelity all`).
 *
 * Input: the joined tables of the passes, coarse to fine (rp_fidelities:
 * analytic, flow, packet); the finest pass is the reference.  For each
 * pass: wall time, mean |rel_error| against the paper, and mean |relative
 * difference| against the packet-level simulation over the cells both
 * produced.  Writers: text, CSV (the reproduction CSV columns plus
 * fidelity, wall_s, rel_error_vs_packet) and JSON; rp_speed_chart() draws
 * error against wall time.
 */
#ifndef PGSIM_REPRODUCE_RP_SPEED_H
#define PGSIM_REPRODUCE_RP_SPEED_H

#include "sim/reproduce/rp_table.h"

/* (sim - ref) / ref for the same cell in the reference pass; NAN when
 * either is missing or ref == 0. */
double rp_speed_vs_ref(const RpJoined *j, const RpTable *ref);
/* Mean |rp_speed_vs_ref| over the pass's cells; NAN when none. */
double rp_speed_mean_vs_ref(const RpTable *t, const RpTable *ref);

/* The per-fidelity summary table only. */
void rp_speed_summary(const GPtrArray *passes, GString *out);
/* Every pass's table, then the summary. */
void rp_speed_text(const GPtrArray *passes, GString *out);
void rp_speed_csv(const GPtrArray *passes, gboolean header, GString *out);
void rp_speed_json(const GPtrArray *passes, GString *out);
/* Writes <dir>/<paper>-speed.{dat,gp,png,svg}. */
gboolean rp_speed_chart(const GPtrArray *passes, const char *dir, GError **err);

#endif
