// The exported frames turned with a performance's head pose (`drive --head-motion`, Python's
// myoshell.drive(head_motion=True)): the simulation's gravity follows the pose anyway; this turns the
// skin itself, rigidly, as the performer's head turned, so an exported take shows the nods.
#pragma once

#include "myoshell/anim/head_pose_track.h"
#include "myoshell/core/types.h"
#include "myoshell/head/face_frame.h"

namespace myo {

// The pivot of the turn: about where the skull sits on the spine (the atlanto-occipital joint),
// below and behind the eyes — 0.9 of the eye distance down and back in the face frame. cm.
Vec3 headMotionPivot(const FaceFrame& frame);

// `positions` (n×3, cm) turned by the pose at time t (s) about headMotionPivot, into `turned`:
// p' = c + A R Aᵀ (p − c), the head pose R being in face-frame axes A (anim/head_pose_track.h).
void turnWithHead(const MatX3& positions, const FaceFrame& frame, const HeadPoseTrack& pose, double t, MatX3& turned);

}  // namespace myo
