// Fitting a whole blendshape rig (`myoshell fit-rig`, docs/fitting.md "Fitting a rig"): every named
// target shape of a rig fitted by fitActivations (activation_fit.h), the results gathered into a
// retargeting map (retarget_map.h) that `myoshell rig` plays on any head.
//
// Names are read in ARKit's or ICT's spelling. ICT's halves of one ARKit shape (browInnerUp_L and
// browInnerUp_R make ARKit's browInnerUp) are summed into one target, so the fitted activations are
// those of both halves together. The shapes muscles cannot make (unreachableArkitShapes(): eye
// rotation, air, tongue) are listed with their reason and not fitted; nothing else is excluded.
// ARKit's mouthClose is a corrective on jawOpen (it only makes sense added to it): jawOpen +
// mouthClose is fitted as one shape and the map stores its activations minus jawOpen's. Every ARKit
// name the rig lacks is in the map too: unreachable with its reason, or derived from its FACS action
// units through the FACS map (source "derived"; fit/facs_route.h) — the same muscles a performance
// drives for that name — for the skin's muscles among them.
//
// A left/right pair of ARKit names (mirroredArkitName: eyeBlinkLeft/Right, …, mouthLeft/mouthRight,
// jawLeft/jawRight) that the rig has both of is fitted as one problem (fitMirroredActivations): one
// activation vector for the left shape, the right shape's equations using each muscle's mirror twin,
// a jaw shape's right pose the left's mirror image. The map's right entry is then exactly the
// mirror of the left's (its activations by the twins' names, the lateral jaw shift negated), while
// each side's figures are its own against its own target. Pairs are fitted so only when every
// fitted muscle's twin is fitted too (the shipped libraries') and both targets move (a zero target
// is a name the rig does not make); otherwise each shape alone.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/types.h"
#include "myoshell/fit/activation_fit.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/fit/retarget_map.h"

namespace myo {

// One target of a rig: its name (any spelling) and its displacement from the rig's base (n×3, cm).
struct RigTarget {
  std::string name;
  MatX3 displacement;
};

struct RigShapeFit {
  std::string name;                    // ARKit spelling
  std::vector<std::string> sources;    // the rig's names it was made of (one, or the two ICT halves)
  bool reachable = true;
  std::string reason;                  // when unreachable
  std::string correctiveOf;            // "jawOpen" for mouthClose
  std::string pairedWith;              // the mirror twin it was fitted together with, if any
  MatX3 target;                        // n×3, cm: what was fitted (a corrective's: with its base)
  std::optional<ActivationFit> fit;    // reachable shapes
};

struct RigFit {
  std::vector<RigShapeFit> shapes;     // ARKit order; only names the rig has
  std::vector<std::string> skipped;    // the rig's names that are no ARKit name (not fitted)
  RetargetMap map;                     // every ARKit name the rig has or can derive, ARKit order
  std::vector<std::string> derived;    // the names derived from the FACS map (not in the rig)
  double medianCosine = 0.0;           // over the reachable shapes that move (a compared vertex)
  double medianRmsMm = 0.0;
  double seconds = 0.0;                // every fit, wall time
};

// Fits every target. Throws InputError for a target of the wrong size or with a non-finite
// coordinate, a name given twice (in either spelling), a mouthClose without jawOpen, no ARKit name
// at all; NumericalError as fitActivations.
// `facs` is the map the rig's missing names are derived through.
RigFit fitRig(const AnatomicalSkin& skin, const std::vector<RigTarget>& targets, const FitSettings& settings,
              const FacsMap& facs = builtinFacsMap());

// The median of a list (the mean of the middle two for an even count; 0 for none).
double median(std::vector<double> values);

}  // namespace myo
