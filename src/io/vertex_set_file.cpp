#include "myoshell/io/vertex_set_file.h"

#include "myoshell/core/whole_file.h"

namespace myo {

std::vector<int> readVertexSet(const std::string& path, int vertexCount) {
  return parseVertexSet(readWholeFile(path), vertexCount, path);
}

}  // namespace myo
