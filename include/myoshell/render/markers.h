// Markers: filled discs with a thin outline at 3-D points (landmarks, pinned vertices, …).
#pragma once

#include <vector>

#include "myoshell/render/camera.h"
#include "myoshell/render/image.h"
#include "myoshell/render/render_mesh.h"

namespace myo {

struct Marker {
  Vec3 position = Vec3::Zero();  // cm
  Rgb color = Rgb(0.9, 0.1, 0.1);
  double radius = 3.0;           // pixels
};

struct MarkerStyle {
  // With a depth buffer, a marker is drawn only where its point is not hidden: its depth is at
  // most `depthTolerance` (cm) behind the nearest surface within one pixel of its centre.
  double depthTolerance = 0.1;
  double outlineWidth = 1.0;                // pixels; 0 for none
  Rgb outlineColor = Rgb(0.05, 0.05, 0.05);
};

// Draws `markers` in order (later ones on top). `depth` may be null: then every marker in the
// image is drawn. Markers do not write depth.
void drawMarkers(Image& image, const DepthBuffer* depth, const Camera& camera,
                 const std::vector<Marker>& markers, const MarkerStyle& style = {});

// A filled disc of radius `radius` (pixels) centred at (cx, cy) (pixel coordinates, camera.h),
// with an outline ring of `outlineWidth` pixels (0 for none).
void drawDisc(Image& image, double cx, double cy, double radius, const Rgb& color,
              double outlineWidth = 0.0, const Rgb& outlineColor = Rgb::Zero());

}  // namespace myo
