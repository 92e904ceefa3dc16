#include "myoshell/fit/facs_route.h"

#include <algorithm>
#include <set>

#include "myoshell/fit/arkit_names.h"

namespace myo {
namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void addWeight(FacsDrive& d, const std::string& muscle, double w) {
  auto it = std::find_if(d.muscles.begin(), d.muscles.end(), [&](const auto& p) { return p.first == muscle; });
  if (it == d.muscles.end()) d.muscles.emplace_back(muscle, w);
  else it->second += w;
}

}  // namespace

double facsSideShare(const std::string& muscle, const std::string& side) {
  if (side.empty()) return 1.0;
  const bool left = endsWith(muscle, "_left"), right = endsWith(muscle, "_right");
  if (!left && !right) return 0.5;
  return (side == "left") == left ? 1.0 : 0.0;
}

std::optional<FacsDrive> facsDriveOfAu(const FacsMap& facs, int au, const std::string& side) {
  const FacsEntry* entry = facs.find(au);
  if (!entry || (entry->muscles.empty() && !entry->movesJaw() && !entry->turnsEyes() && entry->mouthPressureKpa == 0.0))
    return std::nullopt;
  FacsDrive d;
  for (const auto& [muscle, w] : entry->muscles) {
    const double share = w * facsSideShare(muscle, side);
    if (share != 0.0) addWeight(d, muscle, share);
  }
  d.jaw = Vec3(entry->jawOpenDeg, entry->jawForwardCm, (side == "right" ? -1.0 : 1.0) * entry->jawLateralCm);
  // The AU's turn is a direction (AU61 towards the subject's left): a side chooses the eye, not it.
  const Vec2 turn(entry->gazePitchDeg, entry->gazeYawDeg);
  if (side != "left") d.gaze[0] = turn;
  if (side != "right") d.gaze[1] = turn;
  d.mouthPressureKpa = entry->mouthPressureKpa;
  return d;
}

FacsDrive facsDriveOfArkitName(const FacsMap& facs, const std::string& arkitName, std::vector<int>* idle) {
  const ArkitFacs& units = arkitFacs(arkitName);
  FacsDrive out;
  for (int au : units.aus) {
    const std::optional<FacsDrive> one = facsDriveOfAu(facs, au, units.side);
    if (!one || one->empty()) {
      if (idle) idle->push_back(au);
      continue;
    }
    for (const auto& [muscle, w] : one->muscles) addWeight(out, muscle, w);
    out.jaw += one->jaw;
    out.gaze[0] += one->gaze[0];
    out.gaze[1] += one->gaze[1];
    out.mouthPressureKpa += one->mouthPressureKpa;
  }
  return out;
}

std::optional<RetargetShape> derivedRetargetShape(const FacsMap& facs, const std::string& arkitName,
                                                  const std::vector<std::string>& muscleNames) {
  const FacsDrive drive = facsDriveOfArkitName(facs, arkitName);
  const std::set<std::string> known(muscleNames.begin(), muscleNames.end());
  RetargetShape s;
  s.name = canonicalArkitName(arkitName);
  s.source = RetargetSource::Derived;
  for (const auto& [muscle, w] : drive.muscles)
    if (known.count(muscle)) s.activations.emplace_back(muscle, std::clamp(w, 0.0, 1.0));
  const char* dofs[3] = {"open", "forward", "lateral"};
  for (int k = 0; k < 3; ++k)
    if (drive.jaw[k] != 0.0) s.jaw.emplace_back(dofs[k], drive.jaw[k]);
  const char* eyes[2] = {"right", "left"};
  for (int e = 0; e < 2; ++e) {
    if (drive.gaze[static_cast<size_t>(e)].x() != 0.0) s.gaze.emplace_back(std::string(eyes[e]) + "_pitch", drive.gaze[static_cast<size_t>(e)].x());
    if (drive.gaze[static_cast<size_t>(e)].y() != 0.0) s.gaze.emplace_back(std::string(eyes[e]) + "_yaw", drive.gaze[static_cast<size_t>(e)].y());
  }
  s.mouthPressureKpa = drive.mouthPressureKpa;
  if (s.activations.empty() && s.jaw.empty() && s.gaze.empty() && s.mouthPressureKpa == 0.0) return std::nullopt;
  return s;
}

}  // namespace myo
