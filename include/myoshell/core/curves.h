// Small scalar curves the face's weight maps are made of (jaw.h, eyelids.h).
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace myo {

// C¹ step: 0 for t ≤ 0, 1 for t ≥ 1, 3t² − 2t³ between.
inline double smoothStep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Piecewise-linear interpolation of the points (x, y), sorted by x; the end values outside.
inline double interpolateLinear(const std::vector<std::pair<double, double>>& xy, double x) {
  if (x <= xy.front().first) return xy.front().second;
  if (x >= xy.back().first) return xy.back().second;
  const auto upper = std::upper_bound(xy.begin(), xy.end(), x,
                                      [](double value, const std::pair<double, double>& p) { return value < p.first; });
  const auto& [x1, y1] = *upper;
  const auto& [x0, y0] = *(upper - 1);
  const double t = x1 > x0 ? (x - x0) / (x1 - x0) : 0.0;
  return (1.0 - t) * y0 + t * y1;
}

}  // namespace myo
