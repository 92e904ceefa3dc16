#include "myoshell/io/head_files.h"

#include <filesystem>

#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/vertex_set_file.h"
#include "myoshell/mesh/obj_reader.h"

namespace myo {

Landmarks readLandmarks(const std::string& path, int vertexCount) {
  return parseLandmarks(readWholeFile(path, "cannot open landmark file"), vertexCount, path);
}

HeadFiles resolveHeadArgument(const std::string& head, const std::string& landmarks, const std::string& pins,
                              const std::string& units) {
  namespace fs = std::filesystem;
  HeadFiles f;
  try {
    f.unit = parseLengthUnit(units);
  } catch (const InputError& e) {
    throw InputError("--units: " + e.message());
  }
  if (head == "default") {
    if (!landmarks.empty() || !pins.empty() || f.unit != LengthUnit::cm)
      throw InputError("--landmarks, --pins and --units apply to an OBJ head, not the default head");
    return f;
  }
  fs::path obj = head;
  f.landmarks = landmarks;
  f.pins = pins;
  if (fs::is_directory(obj)) {  // a folder laid out like ../shared/data/ict
    const fs::path dir = obj;
    obj = dir / "head_skin.obj";
    if (f.landmarks.empty()) f.landmarks = (dir / "landmarks_multipie68.json").string();
    if (f.pins.empty() && fs::exists(dir / "rigid_vertices.json")) f.pins = (dir / "rigid_vertices.json").string();
  }
  if (!fs::exists(obj))
    throw InputError("no such head: give 'default', an OBJ file or a folder with head_skin.obj", obj.string());
  if (f.landmarks.empty())
    throw InputError("an OBJ head needs --landmarks FILE (layout of docs/heads.md); `myoshell landmarks " +
                         obj.string() + "` finds them automatically",
                     obj.string());
  f.obj = obj.string();
  return f;
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
