#include "myoshell/anatomy/skin_placement.h"

#include "myoshell/core/check.h"

namespace myo {

SkinPlacement::SkinPlacement(const Head& head, const std::vector<std::string>& muscleNames, bool contact)
    : rest_(head.mesh.V), contact_(contact) {
  if (head.landmarks.multipie68.size() == 68) {
    jaw_ = jawRig(head.mesh, head.landmarks);
    mouth_ = mouthContact(head.mesh, head.landmarks, *jaw_);
  }
  if (hasOpenEyes(head.mesh, head.landmarks)) {
    lids_ = lidRig(head.mesh, head.landmarks);
    drivers_ = lidDrivers(muscleNames);
  }
}

ContactReport SkinPlacement::place(const MatX3& u, const JawPose& jaw, const VecX& activations, MatX3& out,
                                   bool project, const EyeGaze& gaze) const {
  MYO_CHECK(jaw.isZero() || jaw_, "SkinPlacement::place: a jaw pose on a head without a jaw");
  if (jaw.isZero()) out = rest_ + u;
  else jawedPositions(*jaw_, jaw, rest_, u, out);
  ContactReport report;
  if (lids_) {
    LidPose lids = lidPose(activations);
    lids.gaze = gaze;
    report.add(applyLids(*lids_, lids, out, project));
  }
  if (mouth_) report.add(applyMouthContact(*mouth_, *jaw_, jaw, out, project));
  return report;
}

}  // namespace myo
