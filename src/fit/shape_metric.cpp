#include "myoshell/fit/shape_metric.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "myoshell/core/errors.h"

namespace myo {

Vec3 largestMotionCentroid(const MatX3& u, const MatX3& rest, int count) {
  const int n = static_cast<int>(u.rows());
  if (n == 0) return Vec3::Zero();
  count = std::clamp(count, 1, n);
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  const VecX len = u.rowwise().norm();
  std::partial_sort(order.begin(), order.begin() + count, order.end(),
                    [&](int a, int b) { return len(a) > len(b) || (len(a) == len(b) && a < b); });
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < count; ++k) c += rest.row(order[static_cast<size_t>(k)]).transpose();
  return c / count;
}

ShapeComparison compareShapes(const MatX3& result, const MatX3& target, const MatX3& rest,
                              const ShapeMetricSettings& settings) {
  if (result.rows() != target.rows() || result.rows() != rest.rows() || result.rows() == 0)
    throw InputError("shape metric: the fields have " + std::to_string(result.rows()) + " and " +
                     std::to_string(target.rows()) + " rows and the rest mesh " +
                     std::to_string(rest.rows()) + " (they must be equal and > 0)");
  ShapeComparison c;
  double dot = 0.0, uu = 0.0, ee = 0.0;
  const VecX lu = result.rowwise().norm(), le = target.rowwise().norm();
  for (Eigen::Index v = 0; v < result.rows(); ++v) {
    if (!(lu(v) > settings.threshold || le(v) > settings.threshold)) continue;
    ++c.comparedVertices;
    dot += result.row(v).dot(target.row(v));
    uu += lu(v) * lu(v);
    ee += le(v) * le(v);
  }
  c.resultNorm = std::sqrt(uu);
  c.targetNorm = std::sqrt(ee);
  c.cosine = (uu > 0.0 && ee > 0.0) ? dot / (c.resultNorm * c.targetNorm) : 0.0;
  if (c.comparedVertices > 0)
    c.magnitudeRatio = ee > 0.0 ? c.resultNorm / c.targetNorm : std::numeric_limits<double>::infinity();
  c.resultCentroid = largestMotionCentroid(result, rest, settings.topCount);
  c.targetCentroid = largestMotionCentroid(target, rest, settings.topCount);
  c.centroidDistance = (c.resultCentroid - c.targetCentroid).norm();
  Eigen::Index pu = 0, pe = 0;
  c.resultPeak = lu.maxCoeff(&pu);
  c.targetPeak = le.maxCoeff(&pe);
  c.resultPeakVertex = static_cast<int>(pu);
  c.targetPeakVertex = static_cast<int>(pe);
  c.peakDistance = (rest.row(pu) - rest.row(pe)).norm();
  return c;
}

}  // namespace myo
