/* structdb_file.h — the structure database file format (YAML): a user's
 * hierarchical database for the sort-first (and any SceneDb) workload,
 * and what the generators' databases are written as.
 *
 *   structure_database: 1
 *   structures:
 *     - name: wheel               # unique; executes refer to names
 *       primitive: false          # optional (seed 001 §2.3.3)
 *       elements:                 # in order; each one kind key
 *         - color: [0.8, 0.1, 0.1]
 *         - matrix: [16 numbers, row-major]
 *           mode: concat          # optional: replace (default) | concat
 *         - triangle: [[x, y, z], [x, y, z], [x, y, z]]
 *         - polygon: [[x, y, z], ...]     # >= 3 vertices
 *         - tristrip: [[x, y, z], ...]    # >= 3 vertices
 *         - polygon2d: [[x, y, z], ...]   # order-dependent (ODP)
 *         - line: [[x, y, z], [x, y, z]]  # a segment
 *         - sphere: [[x, y, z], [x, y, z]] # centre, a surface point
 *         - line_color: [r, g, b]         # colour of lines (color:
 *         - sphere_color: [r, g, b]       #  of polygons, strips, ODPs)
 *         - execute: hub                  # a structure of this file
 *         - {triangle: [...], tag: 7}     # optional caller tag
 *   posted: [world]               # traversal roots, in order
 *
 * Executes may name structures defined later; one closing a cycle is
 * refused, and so are chains over SCENE_DB_DEPTH_MAX levels, networks
 * whose shared executes expand past the memory limit (512 B an element,
 * counted without expanding: scene_db_shape), matrix entries and
 * vertices beyond +-1e15 and posted structures whose matrices carry
 * their boxes beyond it (docs/config.md, Limits).  Priorities' deltas (distributed ODP portions) are not part
 * of the format: elements get the constructors' deltas.  Errors are
 * located (file:line:column: found ..., expected ...) through the cfg
 * reader (libyaml); nothing is returned on error.  Numbers are written
 * with 17 significant digits, so a database written and read back is
 * the same (structdb_file.c).  Cost O(file size).
 */
#ifndef PGSIM_SCENE_STRUCTDB_FILE_H
#define PGSIM_SCENE_STRUCTDB_FILE_H

#include "sim/core/cfg.h"
#include "sim/scene/structdb.h"

/* The database of a parsed file (its root map); NULL with *err. */
SceneDb *scene_db_from_cfg(const CfgNode *root, GError **err);
/* Reads a file; NULL with *err (unreadable, YAML, or format error). */
SceneDb *scene_db_load(const char *path, GError **err);
/* The file text of db (a new GString). */
GString *scene_db_to_yaml(const SceneDb *db);
/* Writes db atomically (a temporary file renamed over path). */
gboolean scene_db_save(const SceneDb *db, const char *path, GError **err);

#endif
