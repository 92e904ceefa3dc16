// The FACS map (docs/facs.md): which muscles each FACS action unit (AU) drives, and how hard, so
// that AU intensities — e.g. OpenFace 2.0's, 0–5 divided by 5 — become muscle activations. Data, not
// code: assets/facs/au_map.json ships the map for the whole face's muscles.
//
//   {"note": "…",
//    "aus": [{"au": 12, "name": "lip corner puller", "openface": true,
//             "muscles": {"zygomaticus_major_left": 1.0, "zygomaticus_major_right": 1.0}, "note": "…"},
//            {"au": 26, "name": "jaw drop", "openface": true, "muscles": {}, "jaw": {"open": 20}},
//            {"au": 45, "name": "blink", "openface": true, "muscles": {}, "needs": "lids"}, …]}
//
// An AU at intensity x drives each of its muscles at x · weight (weights in [0, 1]); where several
// AUs drive one muscle their contributions add and the sum is clamped to 1. An AU the model cannot
// make yet has no muscles and says in `needs` what is missing ("lids"). An AU may move the jaw
// (`jaw`: {"open": degrees, "forward": cm, "lateral": cm} at intensity 1), with or without muscles,
// turn the eyes (`gaze`: {"pitch": degrees, "yaw": degrees} at intensity 1; AU61–64) and hold air
// in the mouth (`mouth_pressure_kpa` at intensity 1; AU34).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "myoshell/core/types.h"

namespace YAML {
class Node;
}

namespace myo {

struct FacsEntry {
  int au = 0;                 // the FACS number (12 for AU12), > 0
  std::string name;           // FACS's name, e.g. "lip corner puller"
  bool openface = false;      // one of OpenFace 2.0's intensity AUs (openFaceIntensityAus())
  std::vector<std::pair<std::string, double>> muscles;  // muscle → weight in [0, 1], file order
  std::string needs;          // what the model lacks to make it (only when it drives nothing)
  std::string note;
  // The jaw at intensity 1 (head/jaw.h, JawPose; docs/facs.md): opening in degrees, protrusion
  // and lateral shift in cm (+ towards the subject's left). Scaled by the intensity like the weights.
  double jawOpenDeg = 0.0, jawForwardCm = 0.0, jawLateralCm = 0.0;
  bool movesJaw() const { return jawOpenDeg != 0.0 || jawForwardCm != 0.0 || jawLateralCm != 0.0; }
  // The eyes' turn at intensity 1 (anatomy/eyelids.h, EyeGaze; AU61–64), degrees in [−45, 45]: pitch
  // + up, yaw + towards the subject's left. The lids follow it; the eyeball is not part of the skin.
  double gazePitchDeg = 0.0, gazeYawDeg = 0.0;
  bool turnsEyes() const { return gazePitchDeg != 0.0 || gazeYawDeg != 0.0; }
  // Air held in the mouth at intensity 1, kPa in [0, 10] (anatomy/mouth_pressure.h; AU34, puff).
  double mouthPressureKpa = 0.0;
};

struct FacsMap {
  std::string note;
  std::vector<FacsEntry> entries;  // file order, each AU once

  // The entry of an AU, or nullptr.
  const FacsEntry* find(int au) const;
};

// The AUs whose intensity OpenFace 2.0 estimates (Baltrušaitis et al. 2018), ascending:
// 1, 2, 4, 5, 6, 7, 9, 10, 12, 14, 15, 17, 20, 23, 25, 26, 45.
const std::vector<int>& openFaceIntensityAus();

// Parses a map. When `knownMuscles` is not empty, every muscle must be one of them. Errors
// (InputError) name `name:line:col`, the key path and the fault: top-level keys other than `note`
// and `aus`, an empty list, an AU number that is not a positive integer (≤ 999) or is given twice,
// a missing name, an `openface` flag that disagrees with OpenFace 2.0's list, a weight outside
// [0, 1], a muscle name that is empty, given twice or unknown (the close names are suggested),
// `needs` beside muscles, an entry with neither, an unknown key.
FacsMap parseFacsMap(const std::string& text, const std::string& name = "<string>",
                     const std::vector<std::string>& knownMuscles = {});
FacsMap readFacsMap(const YAML::Node& root, const std::string& name, const std::vector<std::string>& knownMuscles = {});

// The map as JSON text (parseFacsMap reads it back to the same map; numbers keep 17 digits).
std::string serialiseFacsMap(const FacsMap& map);

// The shipped map (assets/facs/au_map.json, embedded), checked against faceMuscleDefs()'s names.
const FacsMap& builtinFacsMap();

// AU number → intensity in [0, 1].
using AuIntensities = std::vector<std::pair<int, double>>;

// One activation per muscle of `muscleNames` (same order): Σ over the given AUs of intensity ·
// weight, clamped to [0, 1]; muscles no given AU drives stay 0, and so do AUs without muscles (they
// have nothing to drive yet). Only the AUs given are played, so a caller with fewer muscles than the
// map names leaves out the AUs it cannot play. InputError for an AU the map does not hold, an AU
// given twice, an intensity outside [0, 1] (or not finite), and a given AU that drives a muscle not
// in `muscleNames` (it would be dropped silently). `muscleNames` must not repeat a name (CheckError).
VecX activationsForAus(const FacsMap& map, const AuIntensities& intensities, const std::vector<std::string>& muscleNames);

}  // namespace myo
