#include "myoshell/mesh/ray_cast.h"

#include <cmath>
#include <limits>

namespace myo {

std::optional<SurfacePoint> firstRayHit(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& origin,
                                        const Vec3& direction) {
  double bestT = std::numeric_limits<double>::infinity();
  std::optional<SurfacePoint> best;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Vec3 e1 = b - a, e2 = c - a;
    const Vec3 p = direction.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) <= 1e-14 * e1.norm() * e2.norm() * direction.norm()) continue;  // parallel to the plane
    const double inv = 1.0 / det;
    const Vec3 s = origin - a;
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) continue;
    const Vec3 q = s.cross(e1);
    const double v = direction.dot(q) * inv;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = e2.dot(q) * inv;
    if (!(t > 0.0) || !(t < bestT)) continue;
    bestT = t;
    SurfacePoint hit;
    hit.triangle = static_cast<int>(f);
    hit.barycentric = Vec3(1.0 - u - v, u, v);
    hit.point = origin + t * direction;
    hit.normal = (hit.barycentric(0) * Vec3(vertexNormals.row(F(f, 0))) + hit.barycentric(1) * Vec3(vertexNormals.row(F(f, 1))) +
                  hit.barycentric(2) * Vec3(vertexNormals.row(F(f, 2))))
                     .normalized();
    hit.distance = t * direction.norm();
    best = hit;
  }
  return best;
}

}  // namespace myo
