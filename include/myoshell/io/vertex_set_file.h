// Vertex sets (pins, ROIs) from a file (the mesh layer parses the text: mesh/vertex_set.h).
#pragma once

#include <string>
#include <vector>

#include "myoshell/mesh/vertex_set.h"

namespace myo {

// Reads a vertex set file for a mesh of `vertexCount` vertices (parseVertexSet's formats and errors,
// naming `path`; InputError when the file cannot be read).
std::vector<int> readVertexSet(const std::string& path, int vertexCount);

}  // namespace myo
