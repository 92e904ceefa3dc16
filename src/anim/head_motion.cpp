#include "myoshell/anim/head_motion.h"

namespace myo {

Vec3 headMotionPivot(const FaceFrame& frame) { return frame.fromFrame(Vec3(0.0, -0.9, -0.9)); }

void turnWithHead(const MatX3& positions, const FaceFrame& frame, const HeadPoseTrack& pose, double t, MatX3& turned) {
  const Vec3 pivot = headMotionPivot(frame);
  const Mat3 r = frame.axes * pose.at(t).toRotationMatrix() * frame.axes.transpose();
  turned = ((positions.rowwise() - pivot.transpose()) * r.transpose()).rowwise() + pivot.transpose();
}

}  // namespace myo
