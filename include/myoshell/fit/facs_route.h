// The one path from an action unit or an ARKit name to muscles through the FACS map
// (docs/facs.md; docs/fitting.md, "Derived shapes"). A performance's curves take it
// (anim/performance_map.h) and so does a retargeting map's entry for an ARKit shape no artist made
// (fitRig's derived shapes), so a name drives the same muscles whichever way it arrives.
//
// An ARKit name shows FACS action units (fit/arkit_names.h, ArkitFacs); each unit drives its muscles
// at its weights (fit/facs_map.h). A sided name (mouthSmileLeft) drives its side's muscles fully,
// the other side's not at all and midline muscles at half weight (one side's shape pulls half of a
// muscle both sides share), and moves the jaw sideways towards its side.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/fit/retarget_map.h"

namespace myo {

struct FacsDrive {
  std::vector<std::pair<std::string, double>> muscles;  // muscle → weight (> 0), first-seen order, summed
  Vec3 jaw = Vec3::Zero();  // opening (degrees), protrusion and lateral shift (cm, + the subject's left)
  // Each eye's turn (index 0 the subject's right, 1 the left): pitch, yaw in degrees (+ up, + the
  // subject's left). A sided name turns its side's eye only (eyeLookUpLeft the left eye).
  std::array<Vec2, 2> gaze{Vec2::Zero(), Vec2::Zero()};
  bool turnsEyes() const { return !gaze[0].isZero() || !gaze[1].isZero(); }
  double mouthPressureKpa = 0.0;  // air held in the mouth (anatomy/mouth_pressure.h)
  bool empty() const { return muscles.empty() && jaw.isZero() && !turnsEyes() && mouthPressureKpa == 0.0; }
};

// The share of a muscle a sided shape drives: 1 on `side` ("left" | "right"), 0 on the other, ½ for
// a midline muscle (no _left/_right ending); 1 for every muscle when `side` is "".
double facsSideShare(const std::string& muscle, const std::string& side);

// What action unit `au` drives on `side`; nothing when the map does not hold it or it drives
// neither a muscle nor the jaw (an AU that `needs` what the model lacks).
std::optional<FacsDrive> facsDriveOfAu(const FacsMap& facs, int au, const std::string& side);

// What an ARKit name (any spelling) drives through its action units, summed. The units that drive
// nothing are appended to `idle` when given.
FacsDrive facsDriveOfArkitName(const FacsMap& facs, const std::string& arkitName, std::vector<int>* idle = nullptr);

// A retargeting map's entry for `arkitName` made from its FACS units (source "derived"), the
// activations of the muscles among `muscleNames` (each clamped to [0, 1]; the others left out), the
// jaw values ("open", "forward", "lateral") it moves and the eyes' turn ("left_pitch", "left_yaw",
// "right_pitch", "right_yaw", degrees) and the air in the mouth. Nothing when it drives none of them.
std::optional<RetargetShape> derivedRetargetShape(const FacsMap& facs, const std::string& arkitName,
                                                  const std::vector<std::string>& muscleNames);

}  // namespace myo
