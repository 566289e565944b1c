/* mesh_check.h — test helpers: topology and volume checks on meshes,
 * element counts of structure databases. */
#ifndef PGSIM_TESTS_SCENE_MESH_CHECK_H
#define PGSIM_TESTS_SCENE_MESH_CHECK_H

#include "sim/scene/mesh.h"
#include "sim/scene/structdb.h"

/* Directed edges with no reverse twin (boundary edges); fails the test
 * if any directed edge occurs twice (inconsistent winding). */
guint mesh_check_open_edges(const SceneMesh *m);
/* Signed volume by the divergence theorem (fan triangulation). */
double mesh_check_volume(const SceneMesh *m);
/* Number of distinct undirected edges. */
guint mesh_check_edges(const SceneMesh *m);
/* Elements of kind k in structure sid. */
guint mesh_check_count_kind(const SceneDb *db, guint sid, SceneElemKind k);

#endif
