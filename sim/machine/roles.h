/* roles.h — a workload's node kinds as roles that a machine's kinds play
 * (issue 34, point 2; docs/models.md "Roles").
 *
 * A workload names the node kinds it runs on (pixelmerge `node`, argus
 * `cpu`, performer `cpu` + `pipe`, pphigs `host` + `gp` + `renderer` +
 * `frame_buffer`).  On a machine that lacks one, the kind that plays it
 * is `roles.KIND` of the model or the run config's machine section
 * (`roles: {cpu: {value: node, source: ...}}`, or a bare override
 * `--set machine.roles.cpu=node`), else the machine's only kind.  The
 * role becomes a kind of its own, carved from that kind: a copy of its
 * description (clock, memory, costs, processor description) with some
 * of its processors, so the machine keeps its processor count (its
 * network endpoints) and no processor plays two roles.
 *
 * Counts: a role whose count is set (the workload's own overrides, e.g.
 * pphigs `gps` is nodes.gp.count, or --set machine.nodes.ROLE.count)
 * takes that many; otherwise the only role carved from a kind takes all
 * of it, and each of several takes one.  A kind left with fewer than 0
 * processors is a located error.  When some missing kind has no kind to
 * play it, nothing is carved: the workload reports the kind it lacks in
 * its own words (performer's pn: picks Pixel-Planes 5 by its kinds).
 */
#ifndef PGSIM_MACHINE_ROLES_H
#define PGSIM_MACHINE_ROLES_H

#include "sim/core/cfg.h"

/* Carves each kind of `needed` (NULL-terminated, may repeat) that the
 * machine section `sec` (a run config's machine: section with its
 * overrides) lacks, by overrides written into sec; `model_dirs` as for
 * mach_section_tree_in().  Appends to `notes` (char *, g_free) one
 * sentence saying what played what, when anything was carved.  FALSE
 * with a located *err on a role naming no kind, or too few processors. */
gboolean mach_section_roles(CfgNode *sec, const char *const *model_dirs,
                            const char *const *needed, GPtrArray *notes,
                            GError **err);

#endif
