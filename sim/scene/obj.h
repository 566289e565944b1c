/* obj.h — Wavefront OBJ reading and writing.
 *
 * Reads the polygonal subset: `v x y z [w]` (w divides; six numbers are
 * read as x y z r g b, a common vertex-colour extension), `vt`, `vn`, and
 * `f` with the index forms v, v/vt, v//vn, v/vt/vn, negative (relative)
 * indices and any number >= 3 of corners.  `o` and `g` start a new tag
 * (polygon tags count groups from 0).  Lines `l`, `p`, `s`, `usemtl`,
 * `mtllib` and unknown keywords are skipped; materials are not read, so
 * polygons are white.  If every face corner names a normal, the mesh
 * gets per-vertex normals (a vertex's last-named normal).
 *
 * Every malformed line is a located input error:
 * "file:line:column: found <token>, expected <what>" (a bad number, an
 * index of 0 or out of range, a face of fewer than 3 corners, an
 * inconsistent corner form ...).  O(file size).
 */
#ifndef PGSIM_SCENE_OBJ_H
#define PGSIM_SCENE_OBJ_H

#include "sim/scene/mesh.h"

/* Parses OBJ text of `len` bytes; `name` is the file name used in
 * errors.  Returns a new mesh (free with scene_mesh_free()) or NULL. */
SceneMesh *scene_obj_parse(const char *text, gsize len, const char *name,
                           GError **err);
SceneMesh *scene_obj_load(const char *path, GError **err);
/* Writes v (with colours if the mesh has them), vn (if normals) and f
 * lines with %.17g numbers, so positions round-trip exactly. */
gboolean scene_obj_save(const SceneMesh *m, const char *path, GError **err);
/* The same text as a new string (free with g_free()). */
char *scene_obj_to_string(const SceneMesh *m);

#endif
