#include "myoshell/render/markers.h"

#include <algorithm>
#include <cmath>

namespace myo {

void drawDisc(Image& image, double cx, double cy, double radius, const Rgb& color,
              double outlineWidth, const Rgb& outlineColor) {
  const double outer = radius + std::max(0.0, outlineWidth);
  const int x0 = static_cast<int>(std::floor(cx - outer)), x1 = static_cast<int>(std::ceil(cx + outer));
  const int y0 = static_cast<int>(std::floor(cy - outer)), y1 = static_cast<int>(std::ceil(cy + outer));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      if (d <= radius) image.set(x, y, color);
      else if (d <= outer) image.set(x, y, outlineColor);
    }
}

void drawMarkers(Image& image, const DepthBuffer* depth, const Camera& camera,
                 const std::vector<Marker>& markers, const MarkerStyle& style) {
  for (const Marker& m : markers) {
    const ScreenPoint s = project(camera, m.position, image.width, image.height);
    if (camera.perspective && s.depth <= 0) continue;
    const int cx = static_cast<int>(std::floor(s.x)), cy = static_cast<int>(std::floor(s.y));
    if (depth) {
      if (!image.contains(cx, cy)) continue;
      double front = std::numeric_limits<double>::infinity();
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = std::clamp(cx + dx, 0, depth->width - 1), y = std::clamp(cy + dy, 0, depth->height - 1);
          front = std::min(front, depth->at(x, y));
        }
      if (s.depth > front + style.depthTolerance) continue;
    }
    drawDisc(image, s.x, s.y, m.radius, m.color, style.outlineWidth, style.outlineColor);
  }
}

}  // namespace myo
