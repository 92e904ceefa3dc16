#include "myoshell/fit/arkit_rig.h"

#include <fmt/core.h>

#include <map>
#include <optional>
#include <vector>

#include "myoshell/anatomy/mouth_pressure.h"
#include "myoshell/anatomy/nonlinear_settle.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/fit/arkit_names.h"

namespace myo {

JawPose jawPoseOf(const RetargetShape& shape) {
  JawPose pose;
  for (const auto& [dof, value] : shape.jaw) {
    if (dof == "open") pose.openDeg += value;
    else if (dof == "forward") pose.forwardCm += value;
    else if (dof == "lateral") pose.lateralCm += value;
    else throw InputError("shape " + shape.name + ": jaw value '" + dof + "' is not open, forward or lateral");
  }
  return pose;
}

EyeGaze gazeOf(const RetargetShape& shape) {
  EyeGaze gaze;
  for (const auto& [dof, value] : shape.gaze) {
    const size_t eye = dof.rfind("left", 0) == 0 ? 1 : 0;
    (dof.size() > 4 && dof.substr(dof.size() - 5) == "pitch" ? gaze.pitchDeg : gaze.yawDeg)[eye] += value;
  }
  return gaze;
}

ArkitRig settleArkitRig(const AnatomicalSkin& skin, const RetargetMap& map, const SkinPlacement* placement) {
  if (!placement) placement = &skin.placement();
  const bool warped = skin.settings().warping;
  const MatX3& restPositions = skin.head().mesh.V;
  // The muscles' settled displacement, placed (the jaw in `pose`, the lids, the contact).
  // Air in the mouth (cheekPuff): the skin's full-space response to the pressure's load with the
  // shell's large deflection, once per pressure (the reduced basis holds no pattern for it); added
  // to the muscles' residual.
  std::map<double, MatX3> airResponse;
  for (const RetargetShape& s : map.shapes)
    if (s.reachable && s.mouthPressureKpa > 0.0 && !airResponse.count(s.mouthPressureKpa)) {
      NonlinearResponse air = nonlinearFullResponse(skin, mouthPressureLoad(skin.head(), s.mouthPressureKpa));
      if (!air.converged || !air.u.allFinite())
        throw NumericalError(fmt::format("rig: the skin's response to {:.3g} kPa of air in the mouth did not converge (last step {:.3g})",
                                         s.mouthPressureKpa, air.lastStep));
      airResponse[s.mouthPressureKpa] = std::move(air.u);
    }
  auto settle = [&](const NamedValues& activations, const JawPose& pose, const EyeGaze& gaze = {},
                    double airKpa = 0.0) -> MatX3 {
    SkinLoads loads;
    loads.gravity = skin.restGravity();  // no gravity load: the rig's shapes are the muscles' alone
    loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
    loads.activations = VecX::Zero(static_cast<Eigen::Index>(skin.muscles().size()));
    for (const auto& [name, value] : activations) loads.activations(skin.muscleIndex(name)) = value;
    // No contact penalty: a blendshape rig is linear, and fit-rig reads it back with the fit's linear
    // columns; the shapes are placed with the projection (docs/mouth_contact.md, "Penalty forces").
    loads.jaw = pose;
    SettledSkin s = skin.settle(loads, warped);
    if (!s.converged || !s.u.allFinite())
      throw NumericalError(fmt::format("rig: the warped static solve did not converge (residual {:.3g})", s.residual));
    if (airKpa > 0.0) s.u += airResponse.at(airKpa);
    if (placement->isPlain()) return s.u;
    MatX3 moved;
    placement->place(s.u, pose, loads.activations, moved, placement->contact(), gaze);
    return moved - restPositions;
  };
  const MatX3 rest = settle({}, JawPose{});  // zero with warping off; the warped solve's own rest otherwise

  // Every shape's jaw first (serially: the errors in ARKit order).
  const std::vector<std::string>& names = arkitNames();
  std::vector<JawPose> poses(names.size());
  for (size_t k = 0; k < names.size(); ++k) {
    const RetargetShape* s = map.find(names[k]);
    if (!s || !s->reachable) continue;
    const RetargetShape* base = s->correctiveOf.empty() ? s : map.find(s->correctiveOf);
    poses[k] = jawPoseOf(*base);  // a corrective rides on its base's jaw
    if (poses[k].isZero()) continue;
    if (!placement->jaw())
      throw InputError("shape " + s->name + " sets jaw values, and the head has no jaw (its landmarks have no 68-point jaw line)");
    validateJawPose(poses[k], "shape " + s->name + ": jaw");
  }

  const Eigen::Index n = skin.head().mesh.vertexCount();
  ArkitRig rig;
  rig.shapes.resize(names.size());
  // Each shape is its own static solve on the read-only skin: side by side on parallelThreads().
  parallelFor(static_cast<std::int64_t>(names.size()), [&](std::int64_t k) {
    const RetargetShape* s = map.find(names[static_cast<size_t>(k)]);
    ArkitRigShape& shape = rig.shapes[static_cast<size_t>(k)];
    shape.name = names[static_cast<size_t>(k)];
    shape.delta = MatX3::Zero(n, 3);
    if (s && s->reachable) {
      const JawPose& pose = poses[static_cast<size_t>(k)];
      shape.delta = settle(map.totalActivations(*s), pose, gazeOf(*s), s->mouthPressureKpa) - rest;
      if (!s->correctiveOf.empty())
        shape.delta -= settle(map.totalActivations(*map.find(s->correctiveOf)), pose) - rest;
      shape.mapped = true;
    }
    Eigen::Index peakVertex = 0;
    shape.maxDisplacementCm = shape.delta.rowwise().norm().maxCoeff(&peakVertex);
    shape.maxDisplacementVertex = static_cast<int>(peakVertex);
  });
  for (const ArkitRigShape& shape : rig.shapes) rig.made += shape.mapped ? 1 : 0;
  std::vector<std::string> gazing;
  for (const RetargetShape& s : map.shapes)
    if (s.reachable && !s.gaze.empty()) gazing.push_back(s.name);
  if (!placement->lids() && !gazing.empty())
    rig.warnings.push_back("the head has no open eyes, so the " + std::to_string(gazing.size()) +
                           " shapes that turn the eyes (" + gazing.front() + ", …) only move what their muscles move");
  return rig;
}

}  // namespace myo
