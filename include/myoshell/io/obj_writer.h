// Writing Wavefront OBJ meshes (the OBJ sequence of `myoshell run`, `myoshell head --write-obj`).
// Reading is mesh/obj_reader.h's job.
#pragma once

#include <string>

#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// Writes an OBJ through core's atomic writer (a temporary file renamed into place; nothing is left
// behind on failure): a comment line, positions (shortest text that reads back to the same double),
// UVs when the mesh has one per vertex (faces then "f a/a b/b c/c"), then the mesh's polygons when
// present, else its triangles; 1-based indices. V (n×3, cm) overrides the positions when non-null
// and must have the mesh's vertex count (CheckError otherwise).
void writeObj(const std::string& path, const TriMesh& mesh, const MatX3* V = nullptr);

}  // namespace myo
