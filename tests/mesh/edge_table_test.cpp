#include <gtest/gtest.h>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/primitives.h"

namespace myo {
namespace {

TEST(EdgeTable, GridCountsMatchEuler) {
  const TriMesh grid = gridMesh(2.0, 1.0, 4, 3);
  const EdgeTable table = buildEdgeTable(grid.F, grid.vertexCount());
  // Edges of an nx×ny grid with diagonals: horizontal + vertical + one diagonal per cell.
  EXPECT_EQ(static_cast<int>(table.edges.size()), 4 * 4 + 5 * 3 + 12);
  EXPECT_EQ(table.boundaryCount, 2 * (4 + 3));
  EXPECT_EQ(table.interiorCount, static_cast<int>(table.edges.size()) - 14);
  EXPECT_EQ(table.nonManifoldCount, 0);
  EXPECT_EQ(table.inconsistentOrientationCount, 0);
}

TEST(EdgeTable, HingeIndicesFollowAppendixI) {
  const TriMesh sphere = icosphere(1.0, 1);
  const EdgeTable table = buildEdgeTable(sphere.F, sphere.vertexCount());
  EXPECT_EQ(table.boundaryCount, 0);
  EXPECT_EQ(static_cast<int>(table.edges.size()), 3 * sphere.triangleCount() / 2);
  for (const Edge& e : table.edges) {
    ASSERT_GE(e.v[3], 0);
    // face[0] contains v0→v1 with v2 opposite; face[1] contains v1→v0 with v3 opposite.
    auto hasDirected = [&](int face, int a, int b, int c) {
      for (int k = 0; k < 3; ++k)
        if (sphere.F(face, k) == a && sphere.F(face, (k + 1) % 3) == b && sphere.F(face, (k + 2) % 3) == c)
          return true;
      return false;
    };
    EXPECT_TRUE(hasDirected(e.face[0], e.v[0], e.v[1], e.v[2]));
    EXPECT_TRUE(hasDirected(e.face[1], e.v[1], e.v[0], e.v[3]));
    // Convex surface with outward normals: every dihedral angle is positive (METHOD.md §1.1).
    EXPECT_GT(dihedralAngle(sphere.V.row(e.v[0]), sphere.V.row(e.v[1]), sphere.V.row(e.v[2]),
                            sphere.V.row(e.v[3])), 0.0);
  }
}

TEST(EdgeTable, CountsNonManifoldAndFlippedFaces) {
  MatX3i F(3, 3);
  F << 0, 1, 2,  //
      1, 0, 3,   // consistent neighbour
      0, 1, 4;   // third face on edge 0-1, and same direction as the first
  const EdgeTable table = buildEdgeTable(F, 5);
  EXPECT_EQ(table.nonManifoldCount, 1);
  EXPECT_EQ(table.inconsistentOrientationCount, 0);
  MatX3i G(2, 3);
  G << 0, 1, 2, 0, 1, 3;  // flipped neighbour
  const EdgeTable flipped = buildEdgeTable(G, 4);
  EXPECT_EQ(flipped.inconsistentOrientationCount, 1);
  EXPECT_EQ(flipped.firstInconsistent[0], 0);
  EXPECT_EQ(flipped.firstInconsistent[1], 1);
}

}  // namespace
}  // namespace myo
