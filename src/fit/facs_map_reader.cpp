// The FACS map's reader (fit/facs_map.h): the document parser (yaml-cpp, through core's DocReader)
// and the shipped map. Kept apart from the map's use (facs_map.cpp) so the web page's WebAssembly
// takes the map's use without a document reader (docs/web.md).
#include "myoshell/fit/facs_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "myoshell/core/check.h"
#include "myoshell/core/close_names.h"
#include "myoshell/core/doc_reader.h"
#include "myoshell/core/errors.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anatomy/mouth_pressure.h"
#include "myoshell/head/jaw.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace detail {
extern const char kFacsAuMapJson[];
}  // namespace detail

namespace {

// FACS numbers its codes with at most two digits; the bound keeps the cast to int defined.
constexpr int kLargestAu = 999;

std::string auName(int au) { return "AU" + std::to_string(au); }

std::string openFaceList() {
  std::vector<std::string> names;
  for (const int au : openFaceIntensityAus()) names.push_back(auName(au));
  return joinNames(names);
}

// "unknown muscle 'x' (did you mean a, b?)", or the whole list when nothing is close.
std::string unknownMuscle(const std::string& muscle, const std::vector<std::string>& known) {
  const std::vector<std::string> close = closeNames(muscle, known);
  if (!close.empty()) return "unknown muscle '" + muscle + "' (did you mean " + joinNames(close) + "?)";
  return "unknown muscle '" + muscle + "' (the muscles: " + joinNames(known) + ")";
}

FacsEntry readEntry(DocReader& r, const std::set<std::string>& known, const std::vector<std::string>& knownList) {
  FacsEntry e;
  const YAML::Node auNode = r.node("au");
  const double au = r.asNumber(auNode, r.keyPath("au"));
  if (au < 1 || au > kLargestAu || au != std::floor(au))
    r.failAt(auNode, r.keyPath("au"),
             "must be a positive integer up to " + std::to_string(kLargestAu) + " (got " + auNode.Scalar() + ")");
  e.au = static_cast<int>(au);
  e.name = r.requiredString("name");
  if (e.name.empty()) r.fail("name", "must name the action unit (FACS's name, e.g. \"lip corner puller\")");
  const std::vector<int>& openFace = openFaceIntensityAus();
  const bool inOpenFace = std::binary_search(openFace.begin(), openFace.end(), e.au);
  e.openface = r.boolean("openface", inOpenFace);
  if (e.openface != inOpenFace)
    r.fail("openface", inOpenFace ? auName(e.au) + " is one of OpenFace 2.0's intensity AUs: write true"
                                  : "OpenFace 2.0 estimates no intensity for " + auName(e.au) + " (its AUs: " +
                                        openFaceList() + ")");

  const YAML::Node muscles = r.node("muscles");
  const std::string mpath = r.keyPath("muscles");
  if (!muscles.IsMap()) r.failAt(muscles, mpath, "must be an object of muscle: weight ({} when the AU drives none yet)");
  std::set<std::string> seen;
  for (const auto& kv : muscles) {
    const std::string muscle = r.asString(kv.first, mpath);
    const std::string at = mpath + "." + muscle;
    if (muscle.empty()) r.failAt(kv.first, at, "a muscle name cannot be empty");
    if (!seen.insert(muscle).second) r.failAt(kv.first, at, "is given twice");
    if (!known.empty() && !known.count(muscle)) r.failAt(kv.first, at, unknownMuscle(muscle, knownList));
    const double w = r.asNumber(kv.second, at);
    if (w < 0.0 || w > 1.0) r.failAt(kv.second, at, "weight " + kv.second.Scalar() + " is outside [0, 1]");
    e.muscles.emplace_back(muscle, w);
  }
  if (r.has("jaw")) {
    // The jaw at intensity 1, within the jaw's anatomical ranges (head/jaw.h).
    DocReader j = r.child("jaw");
    e.jawOpenDeg = j.number("open", 0.0);
    j.requireWithin("open", e.jawOpenDeg, kJawOpenMinDeg, kJawOpenMaxDeg);
    e.jawForwardCm = j.number("forward", 0.0);
    j.requireWithin("forward", e.jawForwardCm, kJawForwardMinCm, kJawForwardMaxCm);
    e.jawLateralCm = j.number("lateral", 0.0);
    j.requireWithin("lateral", e.jawLateralCm, -kJawLateralMaxCm, kJawLateralMaxCm);
    j.finish();
    if (!e.movesJaw()) r.fail("jaw", "moves nothing: give open, forward or lateral, or leave the key out");
  }
  if (r.has("gaze")) {
    // The eyes' turn at intensity 1 (AU61–64), within an eye's comfortable range.
    DocReader g = r.child("gaze");
    e.gazePitchDeg = g.number("pitch", 0.0);
    g.requireWithin("pitch", e.gazePitchDeg, -kGazeMaxDeg, kGazeMaxDeg);
    e.gazeYawDeg = g.number("yaw", 0.0);
    g.requireWithin("yaw", e.gazeYawDeg, -kGazeMaxDeg, kGazeMaxDeg);
    g.finish();
    if (!e.turnsEyes()) r.fail("gaze", "turns nothing: give pitch or yaw, or leave the key out");
  }
  e.mouthPressureKpa = r.number("mouth_pressure_kpa", 0.0);
  r.requireWithin("mouth_pressure_kpa", e.mouthPressureKpa, 0.0, kMouthPressureMaxKpa);
  e.needs = r.string("needs", "");
  if (r.has("needs") && e.needs.empty()) r.fail("needs", "must say what the model lacks (e.g. \"lids\")");
  if (!e.needs.empty() && (!e.muscles.empty() || e.movesJaw() || e.turnsEyes() || e.mouthPressureKpa > 0.0))
    r.fail("needs", "an AU with muscles, a jaw or a gaze needs nothing more: give those, or needs, not both");
  if (e.needs.empty() && e.muscles.empty() && !e.movesJaw() && !e.turnsEyes() && !(e.mouthPressureKpa > 0.0))
    r.failAt(muscles, mpath, "drives no muscle: list its muscles, give its jaw or gaze, or say in 'needs' what the model lacks");
  e.note = r.string("note", "");
  r.finish();
  return e;
}

}  // namespace

FacsMap readFacsMap(const YAML::Node& root, const std::string& name, const std::vector<std::string>& knownMuscles) {
  DocReader top(root, name);
  FacsMap map;
  map.note = top.string("note", "");
  const YAML::Node list = top.node("aus");
  if (!list.IsSequence()) top.failAt(list, "aus", "must be a list of {au, name, muscles, …}");
  if (list.size() == 0) top.failAt(list, "aus", "must hold at least one action unit");
  top.finish();

  const std::set<std::string> known(knownMuscles.begin(), knownMuscles.end());
  std::map<int, size_t> first;  // AU → the entry that gave it
  for (size_t i = 0; i < list.size(); ++i) {
    DocReader r(list[i], name, "aus[" + std::to_string(i) + "]");
    FacsEntry e = readEntry(r, known, knownMuscles);
    if (const auto [it, fresh] = first.emplace(e.au, i); !fresh)
      r.failAt(list[i]["au"], r.keyPath("au"), auName(e.au) + " is already given by aus[" + std::to_string(it->second) + "]");
    map.entries.push_back(std::move(e));
  }
  return map;
}

FacsMap parseFacsMap(const std::string& text, const std::string& name, const std::vector<std::string>& knownMuscles) {
  return readFacsMap(loadDocument(text, name), name, knownMuscles);
}

const FacsMap& builtinFacsMap() {
  static const FacsMap map = [] {
    std::vector<std::string> names;
    for (const MuscleDef& def : faceMuscleDefs()) names.push_back(def.name);
    return parseFacsMap(detail::kFacsAuMapJson, "<embedded assets/facs/au_map.json>", names);
  }();
  return map;
}

}  // namespace myo
