#include "myoshell/anim/performance_map.h"

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/close_names.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/fit/arkit_rig.h"
#include "myoshell/fit/facs_route.h"
#include "myoshell/head/jaw.h"

namespace myo {
namespace {

// One input curve's reach: model muscle index → weight per unit of the curve, the jaw per unit of
// the curve ([open degrees, forward cm, lateral cm]) and each eye's turn per unit ([pitch, yaw]
// degrees, index 0 the subject's right eye, as FacsDrive::gaze).
struct MuscleWeights {
  std::map<int, double> muscles;
  Vec3 jaw = Vec3::Zero();
  std::array<Vec2, 2> gaze{Vec2::Zero(), Vec2::Zero()};
  bool turnsEyes() const { return !gaze[0].isZero() || !gaze[1].isZero(); }
  bool empty() const { return muscles.empty() && jaw.isZero() && !turnsEyes(); }
};

class Mapper {
 public:
  Mapper(const std::vector<std::string>& muscles, const FacsMap& facs) : facs_(facs) {
    for (size_t m = 0; m < muscles.size(); ++m) {
      MYO_CHECK(index_.emplace(muscles[m], static_cast<int>(m)).second, "mapPerformance: muscle named twice: " << muscles[m]);
    }
  }

  // Adds `weight` · muscle to `out` when the model has it; remembers the missing ones.
  void add(MuscleWeights& out, const std::string& muscle, double weight) {
    if (weight == 0.0) return;
    const auto it = index_.find(muscle);
    if (it == index_.end()) {
      missing_.insert(muscle);
      return;
    }
    out.muscles[it->second] += weight;
  }

  // An AU's muscles and jaw, restricted to `side` (fit/facs_route.h: the one path from a unit to
  // muscles). Returns false when the FACS map has nothing for it.
  bool addAu(MuscleWeights& out, int au, const std::string& side) {
    const std::optional<FacsDrive> drive = facsDriveOfAu(facs_, au, side);
    if (!drive) return false;
    for (const auto& [muscle, w] : drive->muscles) add(out, muscle, w);
    out.jaw += drive->jaw;
    out.gaze[0] += drive->gaze[0];
    out.gaze[1] += drive->gaze[1];
    return true;
  }

  // Why an AU drives nothing, for the warning.
  std::string whyNot(int au) const {
    const FacsEntry* entry = facs_.find(au);
    if (!entry) return "AU" + std::to_string(au) + " is not in the FACS map";
    if (!entry->needs.empty()) return "AU" + std::to_string(au) + " needs " + (entry->needs == "jaw" ? "the jaw" : entry->needs);
    return "AU" + std::to_string(au) + " drives no muscle of this model";
  }

  const std::set<std::string>& missing() const { return missing_; }

 private:
  const FacsMap& facs_;
  std::map<std::string, int> index_;
  std::set<std::string> missing_;
};

std::string numberText(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// The jaw within its anatomical ranges (head/jaw.h): where inputs add past them, the jaw stops.
Vec3 clampJaw(const Vec3& j) {
  return Vec3(std::clamp(j.x(), kJawOpenMinDeg, kJawOpenMaxDeg), std::clamp(j.y(), kJawForwardMinCm, kJawForwardMaxCm),
              std::clamp(j.z(), -kJawLateralMaxCm, kJawLateralMaxCm));
}

// Each eye's angles within the eye's range (head/eye_gaze.h): where inputs add past it, the eye stops.
EyeGaze clampGaze(EyeGaze g) {
  for (size_t e = 0; e < 2; ++e) {
    g.pitchDeg[e] = std::clamp(g.pitchDeg[e], -kGazeMaxDeg, kGazeMaxDeg);
    g.yawDeg[e] = std::clamp(g.yawDeg[e], -kGazeMaxDeg, kGazeMaxDeg);
  }
  return g;
}

// One of EyeGaze's four angles: k = 2·eye + (0 pitch, 1 yaw).
double& gazeAngle(EyeGaze& g, int k) { return (k % 2 == 0 ? g.pitchDeg : g.yawDeg)[static_cast<size_t>(k / 2)]; }
double gazeAngle(const EyeGaze& g, int k) { return (k % 2 == 0 ? g.pitchDeg : g.yawDeg)[static_cast<size_t>(k / 2)]; }

// "AU12" → 12, or 0 for any other name.
int auNumber(const std::string& name) {
  if (name.size() < 3 || name.compare(0, 2, "AU") != 0) return 0;
  int n = 0;
  for (size_t i = 2; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9' || n > 999) return 0;
    n = 10 * n + (name[i] - '0');
  }
  return n;
}

}  // namespace

Performance cropPerformance(const Performance& p, double start, double end, const std::string& what) {
  if (start == 0.0 && end < 0.0) return p;
  Performance out = p;
  out.times.clear();
  out.headPose.clear();
  out.gaze.clear();
  for (auto& c : out.channels) c.values.clear();
  const double eps = 1e-9;
  for (size_t f = 0; f < p.times.size(); ++f) {
    if (p.times[f] < start - eps || (end >= 0.0 && p.times[f] > end + eps)) continue;
    out.times.push_back(p.times[f]);
    if (!p.headPose.empty()) out.headPose.push_back(p.headPose[f]);
    if (!p.gaze.empty()) out.gaze.push_back(p.gaze[f]);
    for (size_t c = 0; c < p.channels.size(); ++c) out.channels[c].values.push_back(p.channels[c].values[f]);
  }
  if (out.times.size() < 2)
    throw InputError(what + ": the window " + numberText(start) + "–" + (end < 0.0 ? std::string("end") : numberText(end)) +
                     " s holds " + std::to_string(out.times.size()) + " frame(s) of the performance (" +
                     numberText(p.duration()) + " s long); it needs two");
  const double t0 = out.times.front();
  for (double& t : out.times) t -= t0;
  return out;
}

MappedPerformance mapPerformance(const Performance& p, const std::vector<std::string>& muscleNames, const FacsMap& facs,
                                 const RetargetMap& arkitMap, const OneEuroSettings& filter) {
  checkOneEuroSettings(filter);
  MappedPerformance out;
  out.times = p.times;
  out.fps = p.fps;
  out.muscles = muscleNames;
  const size_t frames = p.times.size();
  out.activations.assign(muscleNames.size(), std::vector<double>(frames, 0.0));
  Mapper mapper(muscleNames, facs);
  // The file's eye angles, when it has them, are the eyes' turn; the curves that also turn the eyes
  // (eyeLook*, AU61–64) then turn nothing, so that one gaze is not added twice (docs/performance_input.md).
  const bool anglesTurnEyes = !p.gaze.empty();

  for (const PerformanceChannel& channel : p.channels) {
    MYO_CHECK(channel.values.size() == frames, "mapPerformance: curve " << channel.name << " has the wrong length");
    MuscleWeights weights;
    std::string why;
    if (p.input == PerformanceInput::OpenFace) {
      const int au = auNumber(channel.name);
      if (au == 0) why = "not an action unit";
      else if (!mapper.addAu(weights, au, "") || weights.empty()) why = mapper.whyNot(au);
    } else {
      const auto name = findArkitName(channel.name);
      const RetargetShape* shape = name ? arkitMap.find(*name) : nullptr;
      if (!name) {
        why = "not an ARKit name";
      }
      if (name && shape && shape->reachable) {
        for (const auto& [muscle, a] : shape->activations) mapper.add(weights, muscle, a);
        for (const auto& [dof, value] : shape->jaw) {
          if (dof == "open") weights.jaw.x() += value;
          else if (dof == "forward") weights.jaw.y() += value;
          else if (dof == "lateral") weights.jaw.z() += value;
        }
        const EyeGaze turn = gazeOf(*shape);
        for (size_t e = 0; e < 2; ++e) weights.gaze[e] += Vec2(turn.pitchDeg[e], turn.yawDeg[e]);
      }
      // What the map does not make (no entry, unreachable, or nothing this model has): its FACS units.
      if (name && weights.empty()) {
        const ArkitFacs& facs = arkitFacs(*name);
        std::string reasons;
        for (int au : facs.aus) {
          MuscleWeights one;
          if (mapper.addAu(one, au, facs.side) && !one.empty()) {
            for (const auto& [muscle, w] : one.muscles) weights.muscles[muscle] += w;
            weights.jaw += one.jaw;
            weights.gaze[0] += one.gaze[0];
            weights.gaze[1] += one.gaze[1];
          } else {
            reasons += (reasons.empty() ? "" : "; ") + mapper.whyNot(au);
          }
        }
        if (!weights.empty()) why.clear();
        else if (shape && !shape->reachable) why = shape->reason;
        else if (facs.aus.empty())
          why = (shape ? "the retargeting map's " + *name + " drives nothing this model has"
                       : "the retargeting map has no " + *name) + ", and it has no FACS unit";
        else why = reasons;
      }
    }
    if (anglesTurnEyes && weights.turnsEyes()) {
      weights.gaze = {Vec2::Zero(), Vec2::Zero()};
      if (weights.empty()) continue;  // the eyes turn, by the angles
    }
    if (weights.empty()) {
      out.unmapped.push_back(channel.name);
      out.warnings.push_back(channel.name + " drives nothing: " + (why.empty() ? "no muscle" : why));
      continue;
    }
    const std::vector<double> x = oneEuroFilter(p.times, channel.values, filter);
    for (const auto& [muscle, w] : weights.muscles)
      for (size_t f = 0; f < frames; ++f) out.activations[muscle][f] += w * x[f];
    if (!weights.jaw.isZero()) {
      if (out.jaw.empty()) out.jaw.assign(frames, Vec3::Zero());
      for (size_t f = 0; f < frames; ++f) out.jaw[f] += weights.jaw * x[f];
    }
    if (weights.turnsEyes()) {
      if (out.gaze.empty()) out.gaze.assign(frames, EyeGaze{});
      for (size_t f = 0; f < frames; ++f)
        for (size_t e = 0; e < 2; ++e) {
          out.gaze[f].pitchDeg[e] += weights.gaze[e].x() * x[f];
          out.gaze[f].yawDeg[e] += weights.gaze[e].y() * x[f];
        }
    }
  }
  // The file's eye angles, each filtered as the curves are.
  if (anglesTurnEyes) {
    MYO_CHECK(p.gaze.size() == frames, "mapPerformance: the gaze has the wrong length");
    out.gaze.assign(frames, EyeGaze{});
    for (int k = 0; k < 4; ++k) {
      std::vector<double> angle(frames);
      for (size_t f = 0; f < frames; ++f) angle[f] = gazeAngle(p.gaze[f], k);
      angle = oneEuroFilter(p.times, angle, filter);
      for (size_t f = 0; f < frames; ++f) gazeAngle(out.gaze[f], k) = angle[f];
    }
  }
  for (EyeGaze& g : out.gaze) g = clampGaze(g);
  for (auto& curve : out.activations)
    for (double& a : curve) a = std::clamp(a, 0.0, 1.0);
  for (Vec3& j : out.jaw) j = clampJaw(j);
  if (!mapper.missing().empty())
    out.warnings.push_back("the maps name muscles this model does not have, left out: " +
                           joinNames(std::vector<std::string>(mapper.missing().begin(), mapper.missing().end())));

  if (!p.headPose.empty()) {
    MYO_CHECK(p.headPose.size() == frames, "mapPerformance: head pose has the wrong length");
    out.headPose.resize(frames);
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<double> angle(frames);
      for (size_t f = 0; f < frames; ++f) angle[f] = p.headPose[f][axis];
      angle = oneEuroFilter(p.times, angle, filter);
      for (size_t f = 0; f < frames; ++f) out.headPose[f][axis] = angle[f];
    }
  }
  return out;
}

namespace {

// A performance curve (a value per frame) plus a scene's own track, as one track clamped to
// [lo, hi]: a key at every frame and at every key of the own track (so a step or a peak of it
// survives); between frames the curve is linear, or held (`Step`: each frame's value until the
// next frame's, as a live take played it); after the last frame held.
ScalarTrack playedTrack(const std::vector<double>& times, const std::vector<double>& curve, const ScalarTrack& own,
                        double lo, double hi, Interpolation between, const std::string& what) {
  std::vector<double> keyTimes = times;
  for (const auto& key : own.keys()) keyTimes.push_back(key.time);
  std::sort(keyTimes.begin(), keyTimes.end());
  keyTimes.erase(std::unique(keyTimes.begin(), keyTimes.end()), keyTimes.end());
  std::vector<Keyframe<double>> keys;
  keys.reserve(keyTimes.size());
  const size_t frames = times.size();
  size_t f = 0;
  for (double t : keyTimes) {
    while (f + 1 < frames && times[f + 1] <= t) ++f;
    double value = curve[f];
    if (between == Interpolation::Linear && f + 1 < frames && t > times[f]) {
      const double s = (t - times[f]) / (times[f + 1] - times[f]);
      value = (1.0 - s) * curve[f] + s * curve[f + 1];
    }
    // With the scene's own keys between frames the track stays linear, as those keys are.
    const Interpolation to = between == Interpolation::Step && own.empty() ? Interpolation::Step : Interpolation::Linear;
    keys.push_back({t, std::clamp(value + own.at(t), lo, hi), to});  // an empty track is 0
  }
  return ScalarTrack(std::move(keys), what);
}

}  // namespace

void addPerformanceToScene(SceneDesc& scene, const MappedPerformance& mapped, Interpolation between) {
  MYO_CHECK(between == Interpolation::Linear || between == Interpolation::Step,
            "addPerformanceToScene: a performance plays linear or step");
  MYO_CHECK(mapped.times.size() >= 2, "addPerformanceToScene: a performance has at least two frames");
  scene.duration = mapped.times.back();
  scene.fps = mapped.fps;
  const size_t frames = mapped.times.size();
  for (size_t m = 0; m < mapped.muscles.size(); ++m) {
    const std::vector<double>& curve = mapped.activations[m];
    if (std::all_of(curve.begin(), curve.end(), [](double a) { return a == 0.0; })) continue;
    ScalarTrack& track = scene.activations[mapped.muscles[m]];  // the scene's own, or a new empty one
    track = playedTrack(mapped.times, curve, track, 0.0, 1.0, between, "performance of " + mapped.muscles[m]);
  }
  // The jaw: the performance's plus the scene's own jaw keys, within the jaw's ranges.
  if (!mapped.jaw.empty()) {
    ScalarTrack* tracks[3] = {&scene.jawOpen, &scene.jawForward, &scene.jawLateral};
    const char* names[3] = {"performance jaw open", "performance jaw forward", "performance jaw lateral"};
    const Vec3 lo(kJawOpenMinDeg, kJawForwardMinCm, -kJawLateralMaxCm), hi(kJawOpenMaxDeg, kJawForwardMaxCm, kJawLateralMaxCm);
    for (int dof = 0; dof < 3; ++dof) {
      std::vector<double> curve(frames);
      for (size_t f = 0; f < frames; ++f) curve[f] = mapped.jaw[f][dof];
      *tracks[dof] = playedTrack(mapped.times, curve, *tracks[dof], lo[dof], hi[dof], between, names[dof]);
    }
  }
  // The eyes: the performance's turn plus the scene's own keys, within the eye's range; an angle the
  // performance leaves at 0 throughout keeps the scene's own track (or none).
  if (!mapped.gaze.empty()) {
    const char* names[4] = {"performance right eye pitch", "performance right eye yaw", "performance left eye pitch",
                            "performance left eye yaw"};
    for (int k = 0; k < 4; ++k) {
      std::vector<double> curve(frames);
      for (size_t f = 0; f < frames; ++f) curve[f] = gazeAngle(mapped.gaze[f], k);
      if (std::all_of(curve.begin(), curve.end(), [](double a) { return a == 0.0; })) continue;
      ScalarTrack& track = (k % 2 == 0 ? scene.gazePitch : scene.gazeYaw)[static_cast<size_t>(k / 2)];
      track = playedTrack(mapped.times, curve, track, -kGazeMaxDeg, kGazeMaxDeg, between, names[k]);
    }
  }
  if (!mapped.headPose.empty() && scene.headPose.empty()) {
    std::vector<Keyframe<Vec3>> keys(frames);
    for (size_t f = 0; f < frames; ++f) keys[f] = {mapped.times[f], mapped.headPose[f], between};
    scene.headPose = HeadPoseTrack(std::move(keys), "performance head pose");
  }
}

}  // namespace myo
