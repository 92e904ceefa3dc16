// SurfaceLocator against the brute force it replaces: the very same closest point, bit for bit,
// including which of several equally close triangles wins (the lowest index).
#include <gtest/gtest.h>

#include <random>

#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/primitives.h"

namespace myo {
namespace {

void expectSameAsBruteForce(const TriMesh& mesh, const std::vector<Vec3>& queries) {
  const MatX3 normals = vertexNormals(mesh.V, mesh.F);
  const SurfaceLocator locator(mesh.V, mesh.F, normals);
  for (const Vec3& p : queries) {
    const SurfacePoint a = closestSurfacePoint(mesh.V, mesh.F, normals, p);
    const SurfacePoint b = locator.closest(p);
    ASSERT_EQ(a.triangle, b.triangle) << p.transpose();
    EXPECT_EQ(a.barycentric, b.barycentric) << p.transpose();
    EXPECT_EQ(a.point, b.point) << p.transpose();
    EXPECT_EQ(a.normal, b.normal) << p.transpose();
    EXPECT_EQ(a.distance, b.distance) << p.transpose();
  }
}

TEST(SurfaceLocator, MatchesBruteForceAroundASphere) {
  const TriMesh sphere = icosphere(3.0, 4);  // 5,120 triangles
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Vec3> queries;
  for (int k = 0; k < 400; ++k) queries.emplace_back(u(rng), u(rng), u(rng));
  for (int v = 0; v < sphere.vertexCount(); v += 37) queries.push_back(sphere.V.row(v).transpose());  // on it
  expectSameAsBruteForce(sphere, queries);
}

// Points straight above the grid's vertices and edges are equally close to several triangles.
TEST(SurfaceLocator, BreaksTiesByTheLowestTriangleAsTheBruteForce) {
  const TriMesh grid = gridMesh(4.0, 3.0, 16, 12);
  std::vector<Vec3> queries;
  for (int v = 0; v < grid.vertexCount(); ++v) queries.push_back(grid.V.row(v).transpose() + Vec3(0, 0, 0.5));
  for (int v = 0; v + 1 < grid.vertexCount(); v += 3)
    queries.push_back(0.5 * (grid.V.row(v) + grid.V.row(v + 1)).transpose() + Vec3(0, 0, -0.25));
  queries.emplace_back(-1.0, -1.0, 0.0);  // off a corner
  expectSameAsBruteForce(grid, queries);
}

TEST(SurfaceLocator, EmptyMeshFindsNothing) {
  const SurfaceLocator locator(MatX3::Zero(0, 3), MatX3i::Zero(0, 3), MatX3::Zero(0, 3));
  EXPECT_EQ(locator.closest(Vec3::Zero()).triangle, -1);
}

}  // namespace
}  // namespace myo
