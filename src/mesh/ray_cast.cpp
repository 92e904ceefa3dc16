#include "myoshell/mesh/ray_cast.h"

#include <cmath>
#include <limits>

namespace myo {

std::optional<LineTriangleHit> lineMeetsTriangle(const Vec3& origin, const Vec3& direction, const Vec3& a, const Vec3& b,
                                                 const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) <= 1e-14 * e1.norm() * e2.norm() * direction.norm()) return std::nullopt;  // parallel to the plane
  const double inv = 1.0 / det;
  const Vec3 s = origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vec3 q = s.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  return LineTriangleHit{e2.dot(q) * inv, u, v};
}

std::optional<SurfacePoint> firstRayHit(const MatX3& V, const MatX3i& F, const MatX3& vertexNormals, const Vec3& origin,
                                        const Vec3& direction) {
  double bestT = std::numeric_limits<double>::infinity();
  std::optional<SurfacePoint> best;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const std::optional<LineTriangleHit> h =
        lineMeetsTriangle(origin, direction, V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)));
    if (!h || !(h->t > 0.0) || !(h->t < bestT)) continue;
    bestT = h->t;
    SurfacePoint hit;
    hit.triangle = static_cast<int>(f);
    hit.barycentric = Vec3(1.0 - h->u - h->v, h->u, h->v);
    hit.point = origin + h->t * direction;
    hit.normal = (hit.barycentric(0) * Vec3(vertexNormals.row(F(f, 0))) + hit.barycentric(1) * Vec3(vertexNormals.row(F(f, 1))) +
                  hit.barycentric(2) * Vec3(vertexNormals.row(F(f, 2))))
                     .normalized();
    hit.distance = h->t * direction.norm();
    best = hit;
  }
  return best;
}

}  // namespace myo
