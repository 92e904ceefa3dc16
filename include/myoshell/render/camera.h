// Cameras of the software renderer: an orthographic or perspective look-at, view presets from a
// face-frame-like triple, and a fit-to-bounds helper. Lengths in cm (the mesh's units).
//
// Screen convention: pixel (0, 0) is the top-left corner of the image, x to the right, y down;
// pixel (i, j) covers [i, i+1) × [j, j+1). Depth is the distance in front of the eye along the
// viewing direction, cm (larger is farther).
#pragma once

#include "myoshell/core/types.h"

namespace myo {

struct Camera {
  Vec3 eye = Vec3(0, 0, 10);     // position of the eye, cm
  Vec3 target = Vec3::Zero();    // point looked at (drawn at the image centre), cm
  Vec3 up = Vec3::UnitY();       // world direction drawn upwards (need not be ⟂ to the view)
  bool perspective = false;      // false: orthographic
  double orthoHeight = 10.0;     // orthographic: world height shown by the image height, cm
  double fovYDegrees = 30.0;     // perspective: vertical field of view, degrees

  // Unit viewing direction (eye → target), image right and image up, world coordinates.
  Vec3 forward() const;
  Vec3 right() const;
  Vec3 trueUp() const;
};

// A point on the screen of a width × height image: pixel coordinates and depth (cm).
struct ScreenPoint {
  double x = 0, y = 0;  // pixels, see the screen convention above
  double depth = 0;     // cm in front of the eye (≤ 0: behind the eye of a perspective camera)
};
ScreenPoint project(const Camera& camera, const Vec3& p, int width, int height);

// Where a camera looks at a face from: a frame like the face layer's FaceFrame — `origin` (cm),
// `axes` (columns x = subject's left, y = up, z = out of the face towards a viewer in front) and
// `scale` (a size of the face, cm).
struct ViewFrame {
  Vec3 origin = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  double scale = 1.0;
};

// Presets: look at frame.origin from distance 10·scale, frame up drawn up, orthographic with
// orthoHeight = 3·scale (call fitToBounds to frame a mesh).
//   front:        from +z (the subject's left appears on the image's right)
//   threeQuarter: from +z turned 35° about y toward the subject's right (−x)
//   profile:      from the subject's right (−x), 90°
//   back:         from −z
enum class ViewPreset { front, threeQuarter, profile, back };
Camera presetCamera(const ViewFrame& frame, ViewPreset preset);
// The same, turned by `yawDegrees` about frame y (positive: toward the subject's right) and
// `pitchDegrees` about the turned x (positive: from above).
Camera orbitCamera(const ViewFrame& frame, double yawDegrees, double pitchDegrees = 0.0);

// Moves `camera` so that points V (n×3, cm; n ≥ 1) fill a width × height image leaving a
// `margin` (fraction of the image size on every side, in [0, 0.45]). Orthographic: recentres the
// target on V's screen bounds and sets orthoHeight. Perspective: recentres the target on V's
// bounding-box centre and sets the eye distance so V's bounding sphere fits. The viewing direction
// and up do not change; the eye ends in front of all points.
void fitToBounds(Camera& camera, const MatX3& V, int width, int height, double margin = 0.05);

}  // namespace myo
