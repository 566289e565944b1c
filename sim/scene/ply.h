/* ply.h — PLY (Stanford polygon file) reading and writing.
 *
 * Reads ASCII, binary_little_endian and binary_big_endian files, version
 * 1.0, with any elements and properties of the eight scalar types (and
 * their int8 ... float64 aliases); uses `vertex` (x, y, z required;
 * nx, ny, nz and red, green, blue optional: integer colours are / 255)
 * and `face` (a list property vertex_indices or vertex_index of >= 3
 * entries; red, green, blue optional), and skips every other element and
 * property.  The vertex element must come before the face element.
 *
 * Malformed input is a located input error, never a crash:
 * header and ASCII body "file:line:column: found <what>, expected <what>";
 * binary body "file: byte offset N: found <what>, expected <what>"
 * (truncation, an index out of range, a list count below 3 ...).
 * Counts are checked against the file size before anything is allocated.
 *
 * Writes x, y, z as double (positions round-trip exactly), normals as
 * double when present, vertex colours and face colours as uchar.
 * O(file size).  Format: G. Turk, "The PLY Polygon File Format", 1994.
 */
#ifndef PGSIM_SCENE_PLY_H
#define PGSIM_SCENE_PLY_H

#include "sim/scene/mesh.h"

typedef enum {
    SCENE_PLY_ASCII,
    SCENE_PLY_BINARY_LE,
    SCENE_PLY_BINARY_BE
} ScenePlyFormat;

/* Parses `len` bytes; `name` names the file in errors.  Returns a new
 * mesh (free with scene_mesh_free()) or NULL with *err set. */
SceneMesh *scene_ply_parse(const guchar *data, gsize len, const char *name,
                           GError **err);
SceneMesh *scene_ply_load(const char *path, GError **err);
/* Encodes a mesh; returns new bytes (free with g_free()), *len set. */
guchar *scene_ply_encode(const SceneMesh *m, ScenePlyFormat f, gsize *len);
gboolean scene_ply_save(const SceneMesh *m, const char *path, ScenePlyFormat f,
                        GError **err);

#endif
