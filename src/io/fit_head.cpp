#include "myoshell/io/fit_head.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "myoshell/core/errors.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/head_files.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

// The rig's base mesh as a head, with the landmark file given (checked as loadHead checks an OBJ).
Head rigBaseHead(const RigFile& rig, const std::string& landmarks) {
  Head head;
  head.name = fs::path(rig.path).stem().string();
  head.mesh = rig.base;
  head.landmarks = readLandmarks(landmarks, head.mesh.vertexCount());
  head.landmarks.requireAll();
  checkLoadedHead(head, LengthUnit::cm);
  head.gravityPins = defaultGravityPins(head.mesh, head.landmarks);
  head.pinsSource = "longest boundary loop + nasion_approx + Multi-PIE 28";
  return head;
}

}  // namespace

SceneInputs fitHeadInputs(const FitHeadOptions& o, const RigFile* rig, const std::string& what) {
  SceneDesc scene;
  scene.name = "fit";
  scene.muscleLibrary = o.library;
  if (usesRigBase(o, rig)) {
    if (o.unitsGiven)
      throw InputError("--units: a glTF rig is in metres by specification and read in cm; --units applies to an OBJ head");
    if (o.landmarks.empty())  // the commands find them first (findRigBaseLandmarkFile)
      throw InputError(what + ": the head is the rig's base mesh, which carries no landmarks: give --landmarks FILE (or "
                              "the head with --head)");
    SceneInputs inputs = readSceneInputs(scene);
    inputs.head = rigBaseHead(*rig, o.landmarks);
    return inputs;
  }
  const HeadFiles files = resolveHeadArgument(o.head, o.landmarks, "", o.units);
  scene.head.obj = files.obj;
  scene.head.landmarks = files.landmarks;
  scene.head.units = files.unit;
  return readSceneInputs(scene);
}

LengthUnit fitHeadUnit(const FitHeadOptions& o, const RigFile* rig) {
  if (usesRigBase(o, rig)) return LengthUnit::cm;
  return resolveHeadArgument(o.head, o.landmarks, "", o.units).unit;
}

std::string muscleLibraryLabel(const std::string& library) {
  if (library == "builtin" || library == "face") return library;
  return std::filesystem::path(library).filename().string();
}

double parseLambda(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v) || v < 0.0)
    throw InputError("--lambda: '" + text + "' is not a number ≥ 0");
  return v;
}

}  // namespace myo
