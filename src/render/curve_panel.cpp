#include "myoshell/render/curve_panel.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "myoshell/core/check.h"
#include "myoshell/render/text.h"

namespace myo {
namespace {

// A line of one-pixel width from (x0, y0) to (x1, y1) (Bresenham), clipped by Image::set.
void drawLine(Image& image, int x0, int y0, int x1, int y1, const Rgb& c) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  while (true) {
    image.set(x0, y0, c);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) { err += dy; x0 += sx; }
    if (e2 <= dx) { err += dx; y0 += sy; }
  }
}

}  // namespace

CurvePanel activeCurves(const CurvePanel& all, int maxCurves, double minPeak) {
  std::vector<double> peak(all.curves.size(), 0.0);
  for (size_t c = 0; c < all.curves.size(); ++c)
    for (double v : all.curves[c].values) peak[c] = std::max(peak[c], v);
  std::vector<size_t> order(all.curves.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return peak[a] > peak[b]; });
  std::vector<bool> keep(all.curves.size(), false);
  for (size_t i = 0; i < order.size() && static_cast<int>(i) < maxCurves; ++i) keep[order[i]] = peak[order[i]] >= minPeak;
  CurvePanel out;
  out.times = all.times;
  for (size_t c = 0; c < all.curves.size(); ++c)
    if (keep[c]) out.curves.push_back(all.curves[c]);
  return out;
}

Image drawCurvePanel(const CurvePanel& panel, double time, int width, int height) {
  Image image(width, height, Rgb(1, 1, 1));
  const int n = static_cast<int>(panel.curves.size());
  if (n == 0 || panel.times.size() < 2) {
    drawText(image, 8, 8, "no active input curves", Rgb(0.4, 0.4, 0.4));
    return image;
  }
  const int labelWidth = 8 + textWidth("mouthSmileRight", 1);  // the longest ARKit names fit
  const int plotX = labelWidth, plotW = std::max(1, width - labelWidth - 8);
  const double t0 = panel.times.front(), t1 = panel.times.back();
  auto xOf = [&](double t) { return plotX + static_cast<int>(std::lround((t - t0) / (t1 - t0) * (plotW - 1))); };
  const int lane = height / n;
  for (int c = 0; c < n; ++c) {
    const PanelCurve& curve = panel.curves[c];
    MYO_CHECK(curve.values.size() == panel.times.size(), "drawCurvePanel: curve " << curve.name << " has the wrong length");
    const int top = c * lane + 3, bottom = (c + 1) * lane - 3;
    auto yOf = [&](double v) { return bottom - static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * (bottom - top))); };
    image.fillRect(plotX, top, plotW, bottom - top + 1, Rgb(0.95, 0.95, 0.95));
    drawText(image, 4, (top + bottom) / 2 - textHeight(1) / 2, curve.name, Rgb(0.1, 0.1, 0.1));
    for (size_t i = 1; i < panel.times.size(); ++i)
      drawLine(image, xOf(panel.times[i - 1]), yOf(curve.values[i - 1]), xOf(panel.times[i]), yOf(curve.values[i]),
               Rgb(0.1, 0.3, 0.8));
  }
  const int x = xOf(std::clamp(time, t0, t1));
  drawLine(image, x, 0, x, height - 1, Rgb(0.85, 0.1, 0.1));
  return image;
}

Image besideEachOther(const Image& left, const Image& right) {
  Image out(left.width + right.width, std::max(left.height, right.height), Rgb(1, 1, 1));
  blit(out, left, 0, 0);
  blit(out, right, left.width, 0);
  return out;
}

}  // namespace myo
