// Writing Wavefront OBJ meshes (the OBJ sequence of `myoshell run`, `myoshell head --write-obj`).
// Reading is mesh/obj_reader.h's job.
#pragma once

#include <string>

#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// Writes an OBJ through core's atomic writer (a temporary file renamed into place; nothing is left
// behind on failure): a comment line, positions (shortest text that reads back to the same double),
// texture coordinates, then the mesh's polygons when present, else its triangles; 1-based indices.
// Texture coordinates: with corner UVs (TriMesh::cornerUV), the distinct ones in order of first
// appearance and each face corner its own (UV seams kept); else, with per-vertex UVs, one per vertex
// (faces then "f a/a b/b c/c"). V (n×3, cm) overrides the positions when non-null
// and must have the mesh's vertex count (CheckError otherwise).
void writeObj(const std::string& path, const TriMesh& mesh, const MatX3* V = nullptr);

// A deformed copy of a user's OBJ file: the text of `sourcePath` with the first three numbers of
// its i-th `v` line replaced by row i of V (n×3, in the file's own unit; shortest round-trip text),
// every other byte kept (texture coordinates with their seams, normals — those of the rest shape —,
// quads, groups, comments), written through core's atomic writer. Returns false, writing nothing,
// when the file's `v` lines cannot be matched to V (another count, a line with fewer than three
// numbers): the caller then writes the mesh as read (writeObj). InputError when it cannot be read.
bool writeObjLikeFile(const std::string& path, const std::string& sourcePath, const MatX3& V);

}  // namespace myo
