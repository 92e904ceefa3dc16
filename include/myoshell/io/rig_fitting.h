// Fitting a glTF rig's shapes on a head (`myoshell fit-rig`, Python's myoshell.fit_rig;
// docs/fitting.md, "Fitting a rig"): the head chosen as io/fit_head.h says (the rig's base by
// default), the anatomical face built on it, every ARKit-named shape fitted (fit/rig_fit.h) and
// gathered into a retargeting map with its provenance filled in.
#pragma once

#include <memory>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/fit/rig_fit.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/rig_file.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo {

struct FittedRig {
  std::shared_ptr<const AnatomicalFace> face;  // the face the shapes were fitted on (report pictures)
  RigFit fit;                                  // fit.map: rig (file name), head, library, note filled in
  double buildSeconds = 0;                     // the face's build, s
};

// The head and muscles `head` names for fitting `rig` (fitHeadInputs, the error prefix being
// "fit-rig RIG"): InputError as fitHeadInputs, and when the head's vertex count is not the rig's.
SceneInputs rigFitInputs(const RigFile& rig, const FitHeadOptions& head);

// Fits every shape of `rig` on the face built from `inputs` (rigFitInputs), with bases from `cache`
// when not null; the map records `library` (--library's value, muscleLibraryLabel). InputError and
// NumericalError as fitRig.
FittedRig fitRigShapes(const RigFile& rig, const SceneInputs& inputs, const std::string& library, const FitSettings& settings,
                       BasisCache* cache);

}  // namespace myo
