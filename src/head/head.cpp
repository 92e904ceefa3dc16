#include "myoshell/head/head.h"

#include <algorithm>

#include "default_head_data.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/mediapipe_mesh.h"
#include "myoshell/mesh/subdivision.h"

namespace myo {

TriMesh defaultHeadSourceMesh() {
  TriMesh mesh = parseGeometryPipelineMetadata(detail::kDefaultHeadBinarypb,
                                               detail::kDefaultHeadBinarypbSize,
                                               "<embedded geometry_pipeline_metadata_landmarks.binarypb>");
  mesh.sourcePath = "<default head>";
  return mesh;
}

std::string defaultHeadLandmarkJson() {
  return std::string(reinterpret_cast<const char*>(detail::kDefaultHeadLandmarks),
                     detail::kDefaultHeadLandmarksSize);
}

std::string defaultHeadSourceSha256() { return detail::kDefaultHeadSha256; }

std::vector<int> defaultGravityPins(const TriMesh& mesh, const Landmarks& landmarks) {
  std::vector<int> pins;
  const auto loops = boundaryLoops(mesh.F, mesh.vertexCount());
  const std::vector<int>* rim = nullptr;
  double best = -1.0;
  for (const auto& loop : loops) {
    double len = 0.0;
    for (size_t i = 0; i < loop.size(); ++i)
      len += (mesh.V.row(loop[i]) - mesh.V.row(loop[(i + 1) % loop.size()])).norm();
    if (len > best) {
      best = len;
      rim = &loop;
    }
  }
  if (rim) pins = *rim;
  if (landmarks.has("nasion_approx")) pins.push_back(landmarks.vertex("nasion_approx"));
  if (landmarks.multipie68.size() == 68) pins.push_back(landmarks.multipie68[28]);
  std::sort(pins.begin(), pins.end());
  pins.erase(std::unique(pins.begin(), pins.end()), pins.end());
  return pins;
}

Head loadDefaultHead(const DefaultHeadOptions& options) {
  Head head;
  head.name = "default";
  TriMesh mesh = defaultHeadSourceMesh();
  if (options.openMouth) openMediapipeMouth(mesh);
  if (options.openEyes) openMediapipeEyes(mesh);
  mesh = loopSubdivide(mesh, options.subdivisionLevels);
  mesh.sourcePath = "<default head>";
  head.landmarks = parseLandmarks(defaultHeadLandmarkJson(), mesh.vertexCount(),
                                  "<default head landmarks>");
  head.landmarks.requireAll();
  head.mesh = std::move(mesh);
  head.gravityPins = defaultGravityPins(head.mesh, head.landmarks);
  head.pinsSource = "outer rim + nasion_approx + Multi-PIE 28";
  return head;
}

}  // namespace myo
