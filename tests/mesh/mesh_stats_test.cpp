// meshStats: counts and topology on primitives (Euler characteristic), faulty meshes, the ICT head.
#include "myoshell/mesh/mesh_stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "myoshell/mesh/obj_reader.h"
#include "myoshell/mesh/primitives.h"
#include "support/test_data.h"

namespace myo {
namespace {

int euler(const MeshStats& s) { return s.vertices - s.edges + s.triangles; }

TEST(MeshStats, GridIsADiscWithOneBoundaryLoop) {
  const MeshStats s = meshStats(gridMesh(2.0, 1.0, 4, 3));
  EXPECT_EQ(s.vertices, 20);
  EXPECT_EQ(s.triangles, 24);
  EXPECT_EQ(euler(s), 1);  // a disc
  EXPECT_EQ(s.boundaryEdges, 2 * (4 + 3));
  EXPECT_EQ(s.interiorEdges + s.boundaryEdges, s.edges);
  EXPECT_EQ(2 * s.interiorEdges + s.boundaryEdges, 3 * s.triangles);  // each triangle has 3 edge uses
  EXPECT_EQ(s.boundaryLoops, 1);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.degenerateTriangles, 0);
  EXPECT_EQ(s.inconsistentEdges, 0);
  EXPECT_NEAR(s.area, 2.0, 1e-12);
  EXPECT_TRUE(s.bboxMin.isApprox(Vec3(0, 0, 0)));
  EXPECT_TRUE(s.bboxMax.isApprox(Vec3(2, 1, 0)));
}

TEST(MeshStats, IcosphereIsClosedWithEulerTwo) {
  for (int level = 0; level <= 3; ++level) {
    const MeshStats s = meshStats(icosphere(1.5, level));
    EXPECT_EQ(s.triangles, 20 << (2 * level));
    EXPECT_EQ(euler(s), 2) << "level " << level;
    EXPECT_EQ(s.boundaryEdges, 0);
    EXPECT_EQ(s.boundaryLoops, 0);
    EXPECT_EQ(s.components, 1);
    EXPECT_EQ(s.edges, 3 * s.triangles / 2);
    EXPECT_LT(s.area, 4 * std::numbers::pi * 1.5 * 1.5);  // inscribed polyhedron
    EXPECT_LE(s.bboxMax.maxCoeff(), 1.5 + 1e-12);  // vertices lie on the sphere
    EXPECT_GT(s.bboxMax.maxCoeff(), 1.2);
  }
}

// Two copies of a mesh side by side, as one mesh.
TriMesh twice(const TriMesh& m, const Vec3& offset) {
  TriMesh out;
  const int n = m.vertexCount();
  out.V.resize(2 * n, 3);
  out.V << m.V, m.V.rowwise() + offset.transpose();
  out.F.resize(2 * m.triangleCount(), 3);
  out.F << m.F, m.F.array() + n;
  return out;
}

TEST(MeshStats, CountsComponentsAndLoopsOfDisjointPieces) {
  const MeshStats s = meshStats(twice(gridMesh(1, 1, 3, 3), Vec3(5, 0, 0)));
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(s.boundaryLoops, 2);
  EXPECT_EQ(euler(s), 2);
  const MeshStats t = meshStats(twice(icosphere(1, 1), Vec3(0, 0, 3)));
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.boundaryLoops, 0);
  EXPECT_EQ(euler(t), 4);
}

TEST(MeshStats, AnnulusHasTwoBoundaryLoops) {
  // A grid with its central cell's two triangles removed: a disc with a hole.
  const TriMesh grid = gridMesh(3, 3, 3, 3);
  TriMesh ring = grid;
  ring.F.resize(grid.triangleCount() - 2, 3);
  int r = 0;
  for (int t = 0; t < grid.triangleCount(); ++t) {
    const Vec3 c = (grid.V.row(grid.F(t, 0)) + grid.V.row(grid.F(t, 1)) + grid.V.row(grid.F(t, 2))) / 3.0;
    if (c.x() > 1 && c.x() < 2 && c.y() > 1 && c.y() < 2) continue;
    ring.F.row(r++) = grid.F.row(t);
  }
  ASSERT_EQ(r, ring.triangleCount());
  const MeshStats s = meshStats(ring);
  EXPECT_EQ(s.boundaryLoops, 2);
  EXPECT_EQ(euler(s), 0);  // an annulus
  EXPECT_EQ(s.boundaryEdges, 12 + 4);
}

TEST(MeshStats, CountsFaults) {
  MeshReport report;
  const TriMesh m = readObjFromStringLenient(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 2 0 0\n"
      "f 1 2 3\nf 2 1 4\n"
      "f 1 2 5\n"   // a third face on edge (0, 1): non-manifold
      "f 2 6 1\n"   // corners on the x axis: degenerate
      "f 3 5 1\n",  // runs 4→0 as face 3 does: inconsistent
      report);
  const MeshStats s = meshStats(m);
  EXPECT_EQ(s.nonManifoldEdges, report.count("non_manifold_edge"));
  EXPECT_EQ(s.degenerateTriangles, report.count("degenerate_triangle"));
  EXPECT_EQ(s.inconsistentEdges, report.count("inconsistent_orientation"));
  EXPECT_EQ(s.nonManifoldEdges, 1);
  EXPECT_EQ(s.degenerateTriangles, 1);
  EXPECT_EQ(s.inconsistentEdges, 1);
}

TEST(MeshStats, IctHeadMatchesTable) {
  MYO_REQUIRE_SHARED_DATA();
  const TriMesh head = readObj((test::sharedDataDir() / "ict" / "head_skin.obj").string());
  const MeshStats s = meshStats(head);
  EXPECT_EQ(s.vertices, 11248);
  EXPECT_EQ(s.triangles, 22288);
  EXPECT_EQ(head.polygons.size(), 11144u);  // all quads
  EXPECT_EQ(s.boundaryEdges, 212);
  EXPECT_EQ(s.boundaryLoops, 4);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.degenerateTriangles, 0);
  EXPECT_EQ(s.inconsistentEdges, 0);
  EXPECT_EQ(2 * s.interiorEdges + s.boundaryEdges, 3 * s.triangles);
  // V − E + F = 2 − 2g − b for one component: a genus-0 surface with 4 holes gives −2.
  EXPECT_EQ(euler(s), 2 - s.boundaryLoops);
  EXPECT_GT(s.area, 100.0);  // a human head and neck, cm²
}

}  // namespace
}  // namespace myo
