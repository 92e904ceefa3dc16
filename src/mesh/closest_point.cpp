#include "myoshell/mesh/closest_point.h"

#include <limits>

namespace myo {

Vec3 closestPointBarycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the triangle's vertices, edges and face, in that order.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

SurfacePoint closestSurfacePoint(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& p) {
  SurfacePoint best;
  double bestSq = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    const Vec3 bary = closestPointBarycentric(p, a, b, c);
    const Vec3 q = bary(0) * a + bary(1) * b + bary(2) * c;
    const double sq = (q - p).squaredNorm();
    if (sq < bestSq) {
      bestSq = sq;
      best.point = q;
      best.triangle = static_cast<int>(t);
      best.barycentric = bary;
    }
  }
  if (best.triangle >= 0) {
    Vec3 n = Vec3::Zero();
    for (int k = 0; k < 3; ++k) n += best.barycentric(k) * vertexNormals.row(F(best.triangle, k)).transpose();
    if (n.norm() > 0) best.normal = n.normalized();
    best.distance = std::sqrt(bestSq);
  }
  return best;
}

int nearestVertex(const MatX3& V, const Vec3& p) {
  Eigen::Index best = 0;
  (V.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

}  // namespace myo
