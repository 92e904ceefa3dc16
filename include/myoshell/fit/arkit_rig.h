// The physics of `myoshell rig` (docs/fitting.md, "Making a rig"): each shape of a retargeting map
// settled on an anatomical skin, as the 52 ARKit shapes in ARKit's order. io/rig_making.h reads the
// map and the head and writes the result as a glTF rig; Python's myoshell.rig returns it as arrays.
#pragma once

#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/core/types.h"
#include "myoshell/fit/retarget_map.h"
#include "myoshell/head/jaw.h"

namespace myo {

struct ArkitRigShape {
  std::string name;               // ARKit spelling
  bool mapped = false;            // the map has the shape and it is reachable (else delta is zero)
  MatX3 delta;                    // n×3, cm: the settled shape minus the settled rest; a corrective's
                                  // (mouthClose) is what it adds to its base's
  double maxDisplacementCm = 0;   // max over vertices of |delta|, cm
  int maxDisplacementVertex = 0;  // where it is reached
};

struct ArkitRig {
  std::vector<ArkitRigShape> shapes;  // arkitNames() order, all 52
  int made = 0;                       // how many are mapped
  std::vector<std::string> warnings;  // e.g. gaze shapes on a head without open eyes (left zero)
};

// Settles every reachable shape of `map` without gravity load (the shapes are the muscles' alone),
// warped when the skin's settings say so, and places it with `placement` (anatomy/skin_placement.h:
// built from the skin's head and muscles when null), as the playing face places it: a shape with jaw
// values (open in degrees, forward and lateral in cm: rig_fit.h) is carried by the jaw in that pose,
// its lids turned by its lid muscles, the eyeballs', teeth's and lips' contact projected; minus the
// rest; a shape with a gaze (eyeLook*) turns the lids after the eyes (eyelids.h): on a head
// without open eyes it stays zero and `warnings` says so. A corrective rides on its base's jaw. InputError for a muscle the skin does not have (read
// the map with the skin's names to name the file), for jaw values on a head without a jaw (no
// 68-point jaw line) or outside their ranges; NumericalError when a warped solve does not converge
// ("rig: the warped static solve did not converge (residual R)").
ArkitRig settleArkitRig(const AnatomicalSkin& skin, const RetargetMap& map, const SkinPlacement* placement = nullptr);

// The jaw pose a map's shape names (its "open", "forward", "lateral" values summed); InputError
// naming the shape for another name.
JawPose jawPoseOf(const RetargetShape& shape);

// The eyes' turn a map's shape names (its "left_pitch", "left_yaw", "right_pitch", "right_yaw").
EyeGaze gazeOf(const RetargetShape& shape);

}  // namespace myo
