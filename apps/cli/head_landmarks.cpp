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
  // A folder laid out like ../shared/data/ict: its head_skin.obj, with the folder's landmark file
  // unless --landmarks gives one; without either, found as for an OBJ.
  std::string obj = head.head, landmarks = head.landmarks;
  if (fs::is_directory(head.head)) {
    obj = (fs::path(head.head) / "head_skin.obj").string();
    const fs::path folderFile = fs::path(head.head) / "landmarks_multipie68.json";
    if (landmarks.empty() && fs::exists(folderFile)) landmarks = folderFile.string();
  }
  if (!fs::is_regular_file(obj)) return;  // the head's reader names the fault
  const fs::path cache = cacheDir(cacheOption).dir;
  if (!landmarks.empty()) {
    warn(checkLandmarkFile(obj, landmarks, cache), program);
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
  const FoundLandmarkFile f = findLandmarkFile(obj, cache, unit);
  head.landmarks = f.path;
  head.units = lengthUnitName(f.unit);
  say(f, program);
}

void resolveRigBaseLandmarks(HeadOptions& head, const RigFile& rig, const std::string& cacheOption,
                             const std::string& program) {
  if (head.headGiven() || !head.landmarks.empty() || head.unitsGiven()) return;  // --units: fitHeadInputs refuses it
  const FoundLandmarkFile f = findRigBaseLandmarkFile(rig, cacheDir(cacheOption).dir);
  head.landmarks = f.path;
  say(f, program);
}

void resolveSceneLandmarks(SceneDesc& scene, const std::string& cacheOption, const std::string& program) {
  std::vector<std::string> warnings;
  if (const std::optional<FoundLandmarkFile> f = completeSceneHead(scene, cacheDir(cacheOption).dir, &warnings))
    say(*f, program);
  warn(warnings, program);
}

const std::string& autoLandmarkFileUsed() { return usedFile(); }

}  // namespace myo::cli
