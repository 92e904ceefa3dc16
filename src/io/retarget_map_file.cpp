#include "myoshell/io/retarget_map_file.h"

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/doc_reader.h"

namespace myo {

RetargetMap readRetargetMapFile(const std::string& path, const std::vector<std::string>& knownMuscles) {
  return readRetargetMap(loadDocumentFile(path), path, knownMuscles);
}

void writeRetargetMapFile(const std::string& path, const RetargetMap& map) {
  writeFileAtomically(path, serialiseRetargetMap(map));
}

}  // namespace myo
