#include "myoshell/face/arkit_rig.h"

#include <fmt/core.h>

#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/face/arkit_names.h"

namespace myo {

ArkitRig settleArkitRig(const AnatomicalSkin& skin, const RetargetMap& map) {
  const bool warped = skin.settings().warping;
  auto settle = [&](const NamedValues& activations) -> MatX3 {
    SkinLoads loads;
    loads.gravity = skin.restGravity();  // no gravity load: the rig's shapes are the muscles' alone
    loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
    loads.activations = VecX::Zero(static_cast<Eigen::Index>(skin.muscles().size()));
    for (const auto& [name, value] : activations) loads.activations(skin.muscleIndex(name)) = value;
    const SettledSkin s = skin.settle(loads, warped);
    if (!s.converged || !s.u.allFinite())
      throw NumericalError(fmt::format("rig: the warped static solve did not converge (residual {:.3g})", s.residual));
    return s.u;
  };
  const MatX3 rest = settle({});  // zero with warping off; the warped solve's own rest otherwise

  const Eigen::Index n = skin.head().mesh.vertexCount();
  const std::vector<std::string>& names = arkitNames();
  ArkitRig rig;
  rig.shapes.resize(names.size());
  // Each shape is its own static solve on the read-only skin: side by side on parallelThreads().
  parallelFor(static_cast<std::int64_t>(names.size()), [&](std::int64_t k) {
    const RetargetShape* s = map.find(names[static_cast<size_t>(k)]);
    ArkitRigShape& shape = rig.shapes[static_cast<size_t>(k)];
    shape.name = names[static_cast<size_t>(k)];
    shape.delta = MatX3::Zero(n, 3);
    if (s && s->reachable) {
      shape.delta = settle(map.totalActivations(*s)) - rest;
      if (!s->correctiveOf.empty()) shape.delta -= settle(map.totalActivations(*map.find(s->correctiveOf))) - rest;
      shape.mapped = true;
    }
    Eigen::Index peakVertex = 0;
    shape.maxDisplacementCm = shape.delta.rowwise().norm().maxCoeff(&peakVertex);
    shape.maxDisplacementVertex = static_cast<int>(peakVertex);
  });
  for (const ArkitRigShape& shape : rig.shapes) rig.made += shape.mapped ? 1 : 0;
  return rig;
}

}  // namespace myo
