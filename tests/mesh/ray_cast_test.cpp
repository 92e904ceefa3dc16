// firstRayHit against analytic cases: a ray through a sphere meets it where the line's quadratic
// says, from outside the near side and from inside the far side; a ray beside it misses.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/mesh/ray_cast.h"

namespace myo {
namespace {

TEST(RayCast, MeetsASphereWhereTheLineDoes) {
  const double r = 3.0;
  const TriMesh sphere = icosphere(r, 4);
  const MatX3 normals = vertexNormals(sphere.V, sphere.F);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    const Vec3 d = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 o = -10.0 * d + 0.5 * Vec3(u(rng), u(rng), u(rng));  // outside, aimed at the sphere
    // |o + t d|² = r²: the near root. The mesh is inscribed (its faces lie within r of the centre,
    // at least r cos(the faces' half angle)), so it is met a little later than the true sphere.
    const double b = o.dot(d), c = o.squaredNorm() - r * r;
    const double tNear = -b - std::sqrt(b * b - c);
    const std::optional<SurfacePoint> hit = firstRayHit(sphere.V, sphere.F, normals, o, d);
    ASSERT_TRUE(hit.has_value()) << k;
    EXPECT_NEAR(hit->distance, tNear, 0.02 * r) << k;
    EXPECT_GE(hit->distance, tNear - 1e-12) << "inscribed: never before the sphere";
    EXPECT_NEAR((hit->point - (o + hit->distance * d)).norm(), 0.0, 1e-12);
    EXPECT_GT(hit->normal.dot(-d), 0.0) << "the near side faces the ray";
    EXPECT_NEAR(hit->barycentric.sum(), 1.0, 1e-12);
    // From the centre, the far side: at about r.
    const std::optional<SurfacePoint> out = firstRayHit(sphere.V, sphere.F, normals, Vec3::Zero(), d);
    ASSERT_TRUE(out.has_value());
    EXPECT_NEAR(out->distance, r, 0.02 * r);
  }
}

TEST(RayCast, MissesBesideTheSphereAndBehindTheOrigin) {
  const TriMesh sphere = icosphere(3.0, 3);
  const MatX3 normals = vertexNormals(sphere.V, sphere.F);
  EXPECT_FALSE(firstRayHit(sphere.V, sphere.F, normals, Vec3(3.5, 0, -10), Vec3::UnitZ()).has_value());
  // Pointing away: the sphere lies behind (t < 0).
  EXPECT_FALSE(firstRayHit(sphere.V, sphere.F, normals, Vec3(0, 0, -10), -Vec3::UnitZ()).has_value());
}

}  // namespace
}  // namespace myo
