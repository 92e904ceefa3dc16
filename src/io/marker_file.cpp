#include "myoshell/io/marker_file.h"

#include "myoshell/core/doc_reader.h"

namespace myo {

MarkerTarget readMarkerFile(const std::string& path, int vertexCount) {
  return readMarkerTarget(loadDocumentFile(path), vertexCount, path);
}

}  // namespace myo
