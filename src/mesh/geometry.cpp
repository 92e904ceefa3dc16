#include "myoshell/mesh/geometry.h"

#include <cmath>

namespace myo {

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

double dihedralAngle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 e = x1 - x0;
  const Vec3 n0 = e.cross(x2 - x0);
  const Vec3 n1 = (x0 - x1).cross(x3 - x1);
  const double len = e.norm();
  if (len == 0.0) return 0.0;
  // atan2 of sine and cosine terms: robust near 0 and π, no normalization needed (METHOD.md §1.1).
  return std::atan2(n0.cross(n1).dot(e) / len, n0.dot(n1));
}

MatX3 vertexNormals(const MatX3& V, const MatX3i& F) {
  MatX3 N = MatX3::Zero(V.rows(), 3);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    const Vec3 n = (b - a).cross(c - a);  // |n| = 2·area: area weighting for free
    for (int k = 0; k < 3; ++k) N.row(F(t, k)) += n.transpose();
  }
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0) N.row(i) /= len;
  }
  return N;
}

double surfaceArea(const MatX3& V, const MatX3i& F) {
  double area = 0.0;
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    area += triangleArea(V.row(F(t, 0)), V.row(F(t, 1)), V.row(F(t, 2)));
  return area;
}

}  // namespace myo
