#include "myoshell/io/head_files.h"

#include <filesystem>

#include "myoshell/core/whole_file.h"
#include "myoshell/face/head_checks.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/mesh/vertex_set.h"

namespace myo {

Landmarks readLandmarks(const std::string& path, int vertexCount) {
  return parseLandmarks(readWholeFile(path, "cannot open landmark file"), vertexCount, path);
}

Head loadHead(const std::string& objPath, const std::string& landmarkPath, const std::string& pinPath,
              LengthUnit unit) {
  Head head;
  head.name = std::filesystem::path(objPath).stem().string();
  head.mesh = readObj(objPath);
  head.landmarks = readLandmarks(landmarkPath, head.mesh.vertexCount());
  head.landmarks.requireAll();
  rescaleToCentimetres(head.mesh, unit);
  checkLoadedHead(head, unit);
  if (!pinPath.empty()) {
    head.gravityPins = readVertexSet(pinPath, head.mesh.vertexCount());
    head.pinsSource = std::filesystem::path(pinPath).filename().string();
  } else {
    head.gravityPins = defaultGravityPins(head.mesh, head.landmarks);
    head.pinsSource = "longest boundary loop + nasion_approx + Multi-PIE 28";
  }
  return head;
}

}  // namespace myo
