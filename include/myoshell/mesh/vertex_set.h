// Named vertex sets (pins, ROIs, landmarks' neighbourhoods) parsed from JSON text; io/vertex_set_file.h
// reads them from files.
#pragma once

#include <string>
#include <vector>

namespace myo {

// Reads a vertex set: either a JSON list of indices `[3, 8, 12]` or an object with a "vertices"
// list `{"vertices": [3, 8, 12]}`. Every index must lie in [0, vertexCount). Returns sorted unique
// indices. Errors (InputError) name the file (`name`), the line and the fault.
std::vector<int> parseVertexSet(const std::string& jsonText, int vertexCount,
                                const std::string& name = "<string>");

}  // namespace myo
