#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/mesh/subdivision.h"

namespace myo {
namespace {

int edgeCount(const TriMesh& m) {
  return static_cast<int>(buildEdgeTable(m.F, m.vertexCount()).edges.size());
}

// Distance from p to the polyline through loop (closed) of V.
double distanceToPolyline(const Vec3& p, const MatX3& V, const std::vector<int>& loop) {
  double best = INFINITY;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec3 a = V.row(loop[i]), b = V.row(loop[(i + 1) % loop.size()]);
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (a + t * (b - a))).norm());
  }
  return best;
}

TEST(LoopSubdivision, FlatGridStaysFlatAndCountsAreVPlusE) {
  const TriMesh grid = gridMesh(3.0, 2.0, 6, 4);
  const int V = grid.vertexCount(), E = edgeCount(grid);
  const TriMesh s = loopSubdivide(grid);
  EXPECT_EQ(s.vertexCount(), V + E);
  EXPECT_EQ(s.triangleCount(), 4 * grid.triangleCount());
  EXPECT_LT(s.V.col(2).cwiseAbs().maxCoeff(), 1e-14);
  // Orientation kept: every normal still +z, and the result is manifold and consistent.
  for (int t = 0; t < s.triangleCount(); ++t) {
    const Vec3 a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    EXPECT_GT((b - a).cross(c - a).z(), 0.0) << "triangle " << t;
  }
  const EdgeTable table = buildEdgeTable(s.F, s.vertexCount());
  EXPECT_EQ(table.nonManifoldCount, 0);
  EXPECT_EQ(table.inconsistentOrientationCount, 0);
  // Area of a flat domain with straight sides and fixed corners is unchanged.
  EXPECT_NEAR(surfaceArea(s.V, s.F), 6.0, 1e-12);
}

TEST(LoopSubdivision, OriginalIdsComeFirstAndEdgePointsFollow) {
  const TriMesh sphere = icosphere(1.0, 0);
  const TriMesh s = loopSubdivide(sphere);
  EXPECT_EQ(s.vertexCount(), 12 + 30);
  // Edge (F(0,0), F(0,1)) is edge 0: its point is vertex 12 and the first child triangle uses it.
  EXPECT_EQ(s.F(0, 0), sphere.F(0, 0));
  EXPECT_EQ(s.F(0, 1), 12);
  // Closed regular valence-5 mesh: every original vertex moves radially inwards by the same amount.
  const double r0 = s.V.row(0).norm();
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(s.V.row(i).norm(), r0, 1e-12);
    EXPECT_NEAR(s.V.row(i).normalized().dot(sphere.V.row(i).normalized()), 1.0, 1e-12);
  }
  EXPECT_TRUE(boundaryLoops(s.F, s.vertexCount()).empty());
}

TEST(LoopSubdivision, BoundaryVerticesStayOnTheBoundaryPolyline) {
  const TriMesh grid = gridMesh(3.0, 2.0, 6, 4);
  const auto loops0 = boundaryLoops(grid.F, grid.vertexCount());
  ASSERT_EQ(loops0.size(), 1u);
  EXPECT_EQ(loops0[0].size(), 20u);
  const TriMesh s = loopSubdivide(grid, 2);
  const auto loops = boundaryLoops(s.F, s.vertexCount());
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 80u);
  for (int v : loops[0]) EXPECT_LT(distanceToPolyline(s.V.row(v), grid.V, loops0[0]), 1e-12) << v;
  // Original boundary vertices stay boundary vertices.
  const std::set<int> onBoundary(loops[0].begin(), loops[0].end());
  for (int v : loops0[0]) EXPECT_TRUE(onBoundary.count(v)) << v;
}

TEST(LoopSubdivision, InterpolatingBoundaryKeepsACurvedRimExactly) {
  // A disc-like cap: the boundary is curved, so only the interpolating rule keeps it on the polyline.
  TriMesh cap = icosphere(1.0, 1);
  std::vector<int> keep;
  for (int t = 0; t < cap.triangleCount(); ++t) {
    bool upper = true;
    for (int k = 0; k < 3; ++k) upper = upper && cap.V(cap.F(t, k), 2) > -0.2;
    if (upper) keep.push_back(t);
  }
  MatX3i F(static_cast<int>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) F.row(static_cast<int>(i)) = cap.F.row(keep[i]);
  cap.F = F;
  const auto loops0 = boundaryLoops(cap.F, cap.vertexCount());
  ASSERT_EQ(loops0.size(), 1u);
  LoopOptions opt;
  opt.smoothBoundary = false;
  const TriMesh s = loopSubdivide(cap, 2, opt);
  const auto loops = boundaryLoops(s.F, s.vertexCount());
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 4 * loops0[0].size());
  for (int v : loops[0]) EXPECT_LT(distanceToPolyline(s.V.row(v), cap.V, loops0[0]), 1e-12) << v;
}

TEST(LoopSubdivision, SmoothCreaseDependsOnlyOnTheBoundary) {
  TriMesh grid = gridMesh(3.0, 2.0, 6, 4);
  // Bend the boundary so the crease rule has something to smooth, then move the interior.
  for (int i = 0; i < grid.vertexCount(); ++i) grid.V(i, 2) = 0.3 * std::sin(grid.V(i, 0) * 2.0);
  TriMesh moved = grid;
  const auto loop = boundaryLoops(grid.F, grid.vertexCount())[0];
  const std::set<int> onBoundary(loop.begin(), loop.end());
  for (int i = 0; i < grid.vertexCount(); ++i)
    if (!onBoundary.count(i)) moved.V(i, 2) += 0.5;
  const TriMesh a = loopSubdivide(grid, 2), b = loopSubdivide(moved, 2);
  const auto loopsA = boundaryLoops(a.F, a.vertexCount());
  ASSERT_EQ(loopsA.size(), 1u);
  for (int v : loopsA[0])
    EXPECT_LT((a.V.row(v) - b.V.row(v)).norm(), 1e-14) << v;
}

TEST(LoopSubdivision, BoundaryLoopsAreOrderedAndOriented) {
  // A grid with one interior cell's two triangles removed has two loops: outer (20 edges) and a hole (4).
  TriMesh grid = gridMesh(3.0, 2.0, 6, 4);
  MatX3i F(grid.triangleCount() - 2, 3);
  int r = 0;
  for (int t = 0; t < grid.triangleCount(); ++t)
    if (t != 2 * (6 + 2) && t != 2 * (6 + 2) + 1) F.row(r++) = grid.F.row(t);
  const auto loops = boundaryLoops(F, grid.vertexCount());
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 20u);
  EXPECT_EQ(loops[1].size(), 4u);
  // The outer loop runs counter-clockwise (surface to its left): positive signed area in xy.
  double area = 0.0;
  for (size_t i = 0; i < loops[0].size(); ++i) {
    const Vec3 a = grid.V.row(loops[0][i]), b = grid.V.row(loops[0][(i + 1) % loops[0].size()]);
    area += 0.5 * (a.x() * b.y() - b.x() * a.y());
  }
  EXPECT_NEAR(area, 6.0, 1e-12);
}

}  // namespace
}  // namespace myo
