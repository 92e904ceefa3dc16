#include "myoshell/fit/facs_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

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

std::string shortNumber(double v) {
  std::ostringstream out;
  out << v;  // 6 significant digits: enough to recognise the value in a message
  return out.str();
}

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

const FacsEntry* FacsMap::find(int au) const {
  for (const FacsEntry& e : entries)
    if (e.au == au) return &e;
  return nullptr;
}

const std::vector<int>& openFaceIntensityAus() {
  static const std::vector<int> aus = {1, 2, 4, 5, 6, 7, 9, 10, 12, 14, 15, 17, 20, 23, 25, 26, 45};
  return aus;
}

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

std::string serialiseFacsMap(const FacsMap& map) {
  nlohmann::ordered_json j;
  if (!map.note.empty()) j["note"] = map.note;
  nlohmann::ordered_json aus = nlohmann::ordered_json::array();
  for (const FacsEntry& e : map.entries) {
    nlohmann::ordered_json a;
    a["au"] = e.au;
    a["name"] = e.name;
    a["openface"] = e.openface;
    a["muscles"] = nlohmann::ordered_json::object();
    for (const auto& [muscle, w] : e.muscles) a["muscles"][muscle] = w;
    if (e.movesJaw()) {
      a["jaw"] = nlohmann::ordered_json::object();
      if (e.jawOpenDeg != 0.0) a["jaw"]["open"] = e.jawOpenDeg;
      if (e.jawForwardCm != 0.0) a["jaw"]["forward"] = e.jawForwardCm;
      if (e.jawLateralCm != 0.0) a["jaw"]["lateral"] = e.jawLateralCm;
    }
    if (e.mouthPressureKpa > 0.0) a["mouth_pressure_kpa"] = e.mouthPressureKpa;
    if (e.turnsEyes()) {
      a["gaze"] = nlohmann::ordered_json::object();
      if (e.gazePitchDeg != 0.0) a["gaze"]["pitch"] = e.gazePitchDeg;
      if (e.gazeYawDeg != 0.0) a["gaze"]["yaw"] = e.gazeYawDeg;
    }
    if (!e.needs.empty()) a["needs"] = e.needs;
    if (!e.note.empty()) a["note"] = e.note;
    aus.push_back(a);
  }
  j["aus"] = aus;
  return j.dump(2) + "\n";
}

const FacsMap& builtinFacsMap() {
  static const FacsMap map = [] {
    std::vector<std::string> names;
    for (const MuscleDef& def : faceMuscleDefs()) names.push_back(def.name);
    return parseFacsMap(detail::kFacsAuMapJson, "<embedded assets/facs/au_map.json>", names);
  }();
  return map;
}

VecX activationsForAus(const FacsMap& map, const AuIntensities& intensities, const std::vector<std::string>& muscleNames) {
  std::map<std::string, Eigen::Index> index;
  for (size_t m = 0; m < muscleNames.size(); ++m)
    MYO_CHECK(index.emplace(muscleNames[m], static_cast<Eigen::Index>(m)).second,
              "activationsForAus: muscle named twice: " << muscleNames[m]);
  VecX a = VecX::Zero(static_cast<Eigen::Index>(muscleNames.size()));
  std::set<int> given;
  for (const auto& [au, x] : intensities) {
    const FacsEntry* entry = map.find(au);
    if (!entry) throw InputError(auName(au) + " is not in the FACS map");
    if (!given.insert(au).second) throw InputError(auName(au) + " is given twice");
    if (!(x >= 0.0 && x <= 1.0))  // NaN fails too
      throw InputError(auName(au) + ": intensity " + shortNumber(x) + " is outside [0, 1]");
    for (const auto& [muscle, w] : entry->muscles) {
      const auto it = index.find(muscle);
      if (it == index.end())
        throw InputError(auName(au) + " (" + entry->name + ") drives " + muscle +
                         ", which is not among the muscles played; leave " + auName(au) + " out to play without it");
      a(it->second) += x * w;
    }
  }
  return a.cwiseMin(1.0);  // each term is ≥ 0, so only the top needs clamping
}

}  // namespace myo
