#include "head_landmarks.h"

#include <fmt/core.h>

#include <filesystem>

#include "myoshell/core/errors.h"
#include "myoshell/io/auto_landmark_file.h"
#include "resources.h"

namespace myo::cli {

namespace {

std::string& usedFile() {
  static std::string path;
  return path;
}

// The line that says the landmarks were found automatically, and the search's warnings (eyes or
// mouth without an opening: what the model cannot animate on this head).
void say(const FoundLandmarkFile& f, const std::string& program) {
  usedFile() = f.path;
  const std::string units = fmt::format("units {}{}", lengthUnitName(f.unit), f.unitInferred ? ", inferred from its size" : "");
  if (f.reused)
    fmt::print(stderr, "{}: using the landmarks of {} found automatically before ({}; {}; pass it as --landmarks to edit)\n",
               program, f.obj, f.path, units);
  else
    fmt::print(stderr, "{}: found the landmarks of {} automatically in {:.1f} s ({}; written to {}; pass it as --landmarks to edit)\n",
               program, f.obj, f.seconds, units, f.path);
  for (const std::string& w : f.warnings) fmt::print(stderr, "{}: warning: {}\n", program, w);
}

void warn(const std::vector<std::string>& warnings, const std::string& program) {
  for (const std::string& w : warnings) fmt::print(stderr, "{}: warning: {}\n", program, w);
}

}  // namespace

void resolveHeadLandmarks(HeadOptions& head, const std::string& cacheOption, const std::string& program) {
  namespace fs = std::filesystem;
  if (head.head == "default") return;
  const fs::path cache = cacheDir(cacheOption).dir;
  if (fs::is_directory(head.head)) {  // a head folder: its file (or --landmarks) checked as an OBJ's
    const fs::path obj = fs::path(head.head) / "head_skin.obj";
    const std::string landmarks =
        head.landmarks.empty() ? (fs::path(head.head) / "landmarks_multipie68.json").string() : head.landmarks;
    if (fs::is_regular_file(obj) && fs::is_regular_file(landmarks)) warn(checkLandmarkFile(obj.string(), landmarks, cache), program);
    return;
  }
  if (!fs::is_regular_file(head.head)) return;  // the head's reader names the fault
  if (!head.landmarks.empty()) {
    warn(checkLandmarkFile(head.head, head.landmarks, cache), program);
    return;
  }
  std::optional<LengthUnit> unit;
  if (head.unitsGiven()) {
    try {
      unit = parseLengthUnit(head.units);
    } catch (const InputError& e) {
      throw InputError("--units: " + e.message());
    }
  }
  const FoundLandmarkFile f = findLandmarkFile(head.head, cache, unit);
  head.landmarks = f.path;
  head.units = lengthUnitName(f.unit);
  say(f, program);
}

void resolveSceneLandmarks(SceneDesc& scene, const std::string& cacheOption, const std::string& program) {
  std::vector<std::string> warnings;
  if (const std::optional<FoundLandmarkFile> f = completeSceneHead(scene, cacheDir(cacheOption).dir, &warnings))
    say(*f, program);
  warn(warnings, program);
}

void resolveRigBaseLandmarks(FitHeadOptions& options, const RigFile& rig, const std::string& cacheOption,
                             const std::string& program) {
  if (!usesRigBase(options, &rig) || !options.landmarks.empty()) return;
  const FoundLandmarkFile f = findRigBaseLandmarkFile(rig.path, rig.base, cacheDir(cacheOption).dir);
  options.landmarks = f.path;
  say(f, program);
}

const std::string& autoLandmarkFileUsed() { return usedFile(); }

}  // namespace myo::cli
