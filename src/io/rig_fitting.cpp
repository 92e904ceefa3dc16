#include "myoshell/io/rig_fitting.h"

#include <fmt/core.h>

#include <filesystem>
#include <string>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"

namespace myo {

SceneInputs rigFitInputs(const RigFile& rig, const FitHeadOptions& headOptions) {
  SceneInputs inputs = fitHeadInputs(headOptions, &rig, "fit-rig " + rig.path);
  const Head& head = inputs.head;
  if (rig.vertexCount() != head.mesh.vertexCount())
    throw InputError(fmt::format("the rig's base has {} vertices and the head {}: give the head the rig was made for (or "
                                 "no head option and --landmarks)",
                                 rig.vertexCount(), head.mesh.vertexCount()),
                     rig.path);
  return inputs;
}

FittedRig fitRigShapes(const RigFile& rig, const SceneInputs& inputs, const std::string& library, const FitSettings& settings,
                       BasisCache* cache) {
  const Head& head = inputs.head;
  std::vector<RigTarget> targets;
  for (const std::string& name : rig.names) targets.push_back({name, rig.delta(name)});

  FittedRig fitted;
  const Stopwatch buildClock;
  fitted.face = std::make_shared<const AnatomicalFace>(head, inputs.muscles, inputs.anatomical, std::vector<DragDef>{},
                                                       false, cache);
  fitted.buildSeconds = buildClock.seconds();
  fitted.fit = fitRig(fitted.face->skin(), targets, settings);
  RetargetMap& map = fitted.fit.map;
  map.rig = std::filesystem::path(rig.path).filename().string();
  map.head = head.name;
  map.library = muscleLibraryLabel(library);
  map.note = fmt::format("fitted by myoshell fit-rig on the shapes of {} (head {}, {} muscles, lambda {})", map.rig,
                         head.name, fitted.face->muscleCount(), settings.lambda);
  return fitted;
}

}  // namespace myo
