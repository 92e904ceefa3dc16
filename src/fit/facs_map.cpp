#include "myoshell/fit/facs_map.h"

// The FACS map's use: lookups and activations (the reader and the shipped map: facs_map_reader.cpp).
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo {
namespace {

std::string auName(int au) { return "AU" + std::to_string(au); }

std::string shortNumber(double v) {
  std::ostringstream out;
  out << v;  // 6 significant digits: enough to recognise the value in a message
  return out.str();
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
