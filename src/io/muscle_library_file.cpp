#include "myoshell/io/muscle_library_file.h"

#include <memory>

#include "myoshell/core/doc_reader.h"
#include "myoshell/mesh/obj_reader.h"

namespace myo {

std::vector<MuscleDef> readMuscleDefs(const std::string& path) {
  std::vector<MuscleDef> defs = readMuscleLibrary(loadDocumentFile(path), path);
  readMuscleShells(defs);
  return defs;
}

void readMuscleShells(std::vector<MuscleDef>& defs) {
  for (MuscleDef& d : defs)
    if (d.imported() && !d.shell) d.shell = std::make_shared<const TriMesh>(readObj(d.obj));
}

}  // namespace myo
