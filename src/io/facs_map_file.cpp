#include "myoshell/io/facs_map_file.h"

#include "myoshell/core/doc_reader.h"

namespace myo {

FacsMap readFacsMapFile(const std::string& path, const std::vector<std::string>& knownMuscles) {
  return readFacsMap(loadDocumentFile(path), path, knownMuscles);
}

}  // namespace myo
