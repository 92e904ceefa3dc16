// Per-corner texture coordinates (TriMesh::cornerUV) and the UV seam split (mesh/uv_seams.h): the
// OBJ reader keeps every corner's UV through its triangulation, subdivision keeps seams, and the
// split appends exactly one duplicate per further UV of a vertex. On ICT's head (shared data) the
// split is checked against an independent count and its duplicate count is recorded.
#include "myoshell/mesh/uv_seams.h"

#include <gtest/gtest.h>

#include <iostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/mesh/subdivision.h"
#include "support/test_data.h"
#include "support/uv_seam_mesh.h"

namespace myo {
namespace {

MatX2 rows(std::initializer_list<std::pair<double, double>> values) {
  MatX2 out(static_cast<Eigen::Index>(values.size()), 2);
  Eigen::Index i = 0;
  for (const auto& [u, v] : values) out.row(i++) << u, v;
  return out;
}

// Every split corner points at a copy of the mesh corner's vertex and carries the corner's UV.
void expectSplitKeepsCorners(const TriMesh& mesh, const SeamSplit& split) {
  ASSERT_EQ(split.triangles.rows(), mesh.F.rows());
  ASSERT_EQ(split.uv.rows(), split.vertexCount());
  for (int v = 0; v < mesh.vertexCount(); ++v) ASSERT_EQ(split.sourceVertex[static_cast<size_t>(v)], v);
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int out = split.triangles(t, c);
      ASSERT_EQ(split.sourceVertex[static_cast<size_t>(out)], mesh.F(t, c)) << t << " " << c;
      ASSERT_TRUE(split.uv.row(out) == mesh.cornerUV.row(3 * t + c)) << t << " " << c;
    }
}

// Distinct corner UVs per vertex, counted with a set: the duplicates the split must make.
int expectedDuplicates(const TriMesh& mesh) {
  std::vector<std::set<std::pair<double, double>>> uvs(static_cast<size_t>(mesh.vertexCount()));
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
    for (int c = 0; c < 3; ++c)
      uvs[static_cast<size_t>(mesh.F(t, c))].insert({mesh.cornerUV(3 * t + c, 0), mesh.cornerUV(3 * t + c, 1)});
  int extra = 0;
  for (const auto& s : uvs) extra += s.empty() ? 0 : static_cast<int>(s.size()) - 1;
  return extra;
}

TEST(CornerUv, ObjReaderKeepsEachCornersTextureCoordinateThroughTheTriangulation) {
  const TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  // Quad A splits along 0–4 (a tie), quad B along 2–4 (the shorter diagonal).
  MatX3i F(5, 3);
  F << 0, 1, 4, 0, 4, 3, 1, 2, 4, 2, 5, 4, 2, 6, 5;
  ASSERT_EQ(mesh.F, F);
  ASSERT_TRUE(mesh.hasCornerUV());
  const MatX2 expected = rows({{0, 0}, {0.4, 0}, {0.4, 1},       // A: 0 1 4
                               {0, 0}, {0.4, 1}, {0, 1},         // A: 0 4 3
                               {0.6, 0}, {1, 0}, {0.6, 1},       // B: 1 2 4
                               {1, 0}, {1, 1}, {0.6, 1},         // B: 2 5 4
                               {1, 0}, {0, 0}, {1, 1}});         // no vt: vertices 2, 6, 5's UVs
  EXPECT_EQ(mesh.cornerUV, expected);
  // The per-vertex UVs are as before: the first corner's (vertex 6, named by no vt, gets 0).
  EXPECT_EQ(mesh.UV, rows({{0, 0}, {0.4, 0}, {1, 0}, {0, 1}, {0.4, 1}, {1, 1}, {0, 0}}));
}

TEST(CornerUv, AFileWithoutTextureCoordinatesHasNone) {
  const TriMesh mesh = readObjFromString("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
  EXPECT_EQ(mesh.cornerUV.rows(), 0);
  EXPECT_FALSE(mesh.hasCornerUV());
  const SeamSplit split = splitUvSeams(mesh);
  EXPECT_EQ(split.vertexCount(), 4);
  EXPECT_EQ(split.triangles, mesh.F);
  EXPECT_EQ(split.uv.rows(), 0);
}

TEST(CornerUv, AShapeReadLikeTheRestSharesItsCornerUvsUnlessItHasItsOwn) {
  const TriMesh rest = readObjFromString(test::kUvSeamObj, "seam.obj");
  const std::string positionsOnly =
      "v 0 0 1\nv 1 0 1\nv 1.8 0 1\nv 0 1 1.2\nv 1 1 1.2\nv 2 1 1.2\nv 3 0.5 1.5\n"
      "f 1 2 5 4\nf 2 3 6 5\nf 3 7 6\n";
  EXPECT_EQ(readObjLikeFromString(positionsOnly, rest).cornerUV, rest.cornerUV);
  // With texture coordinates of its own the shape's corners are unknown (its faces may be
  // triangulated differently), so its cornerUV is empty rather than wrong.
  EXPECT_EQ(readObjLikeFromString(test::kUvSeamObj, rest).cornerUV.rows(), 0);
}

TEST(UvSeams, SplitAppendsOneDuplicatePerFurtherUvInOrderOfFirstAppearance) {
  const TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  const SeamSplit split = splitUvSeams(mesh);
  // Vertex 1 meets (0.6, 0) in triangle 2 first, then vertex 4 meets (0.6, 1): duplicates 7 and 8.
  EXPECT_EQ(split.sourceVertex, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 1, 4}));
  EXPECT_EQ(split.duplicateCount(mesh.vertexCount()), 2);
  MatX3i F(5, 3);
  F << 0, 1, 4, 0, 4, 3, 7, 2, 8, 2, 5, 8, 2, 6, 5;
  EXPECT_EQ(split.triangles, F);
  EXPECT_EQ(split.uv, rows({{0, 0}, {0.4, 0}, {1, 0}, {0, 1}, {0.4, 1}, {1, 1}, {0, 0}, {0.6, 0}, {0.6, 1}}));
  expectSplitKeepsCorners(mesh, split);
  EXPECT_EQ(split.duplicateCount(mesh.vertexCount()), expectedDuplicates(mesh));

  // Rows per vertex follow their copies.
  MatX3 perVertex(7, 3);
  for (int v = 0; v < 7; ++v) perVertex.row(v) << v, 10 * v, -v;
  const MatX3 expanded = expandToSplit(split, perVertex);
  ASSERT_EQ(expanded.rows(), 9);
  EXPECT_EQ(expanded.topRows(7), perVertex);
  EXPECT_EQ(expanded.row(7), perVertex.row(1));
  EXPECT_EQ(expanded.row(8), perVertex.row(4));
}

TEST(UvSeams, AVertexNoTriangleNamesKeepsItsOwnUv) {
  TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  // Drop the last triangle: vertex 6 is then named by no triangle.
  mesh.F.conservativeResize(4, 3);
  mesh.cornerUV.conservativeResize(12, 2);
  mesh.UV.row(6) << 0.25, 0.75;
  const SeamSplit split = splitUvSeams(mesh);
  EXPECT_EQ(split.vertexCount(), 9);
  EXPECT_EQ(split.uv(6, 0), 0.25);
  EXPECT_EQ(split.uv(6, 1), 0.75);
}

TEST(UvSeams, CornerUvsOfTheWrongSizeAreACheckError) {
  TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  mesh.cornerUV.conservativeResize(14, 2);
  EXPECT_THROW(splitUvSeams(mesh), CheckError);
}

TEST(UvSeams, SubdivisionKeepsTheSeams) {
  const TriMesh mesh = readObjFromString(test::kUvSeamObj, "seam.obj");
  const TriMesh fine = loopSubdivide(mesh);
  ASSERT_TRUE(fine.hasCornerUV());
  // Triangle t's first child starts at its first corner, with the midpoints of its edges.
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Vec2 u0 = mesh.cornerUV.row(3 * t), u1 = mesh.cornerUV.row(3 * t + 1), u2 = mesh.cornerUV.row(3 * t + 2);
    EXPECT_TRUE(fine.cornerUV.row(12 * t) == u0.transpose()) << t;
    EXPECT_TRUE(fine.cornerUV.row(12 * t + 1) == (0.5 * (u0 + u1)).transpose()) << t;
    EXPECT_TRUE(fine.cornerUV.row(12 * t + 2) == (0.5 * (u2 + u0)).transpose()) << t;
  }
  const SeamSplit split = splitUvSeams(fine);
  expectSplitKeepsCorners(fine, split);
  // The seam 1–4 gains its edge point: vertices 1, 4 and the midpoint of 1–4 are duplicated.
  EXPECT_EQ(split.duplicateCount(fine.vertexCount()), 3);
  EXPECT_EQ(split.duplicateCount(fine.vertexCount()), expectedDuplicates(fine));
}

TEST(UvSeamsIct, HeadSkinKeepsItsCornerUvsAndSplitsAlongItsSeams) {
  MYO_REQUIRE_SHARED_DATA();
  const TriMesh mesh = readObj((test::sharedDataDir() / "ict" / "head_skin.obj").string());
  ASSERT_TRUE(mesh.hasCornerUV());
  EXPECT_EQ(mesh.cornerUV.rows(), 3 * mesh.F.rows());
  const SeamSplit split = splitUvSeams(mesh);
  expectSplitKeepsCorners(mesh, split);
  const int duplicates = split.duplicateCount(mesh.vertexCount());
  EXPECT_EQ(duplicates, expectedDuplicates(mesh));
  // The figure docs/rigs.md and docs/fitting.md quote for ICT-FaceKit's head_skin.obj.
  EXPECT_EQ(mesh.vertexCount(), 11248);
  EXPECT_EQ(duplicates, 214);
  RecordProperty("ict_vertices", std::to_string(mesh.vertexCount()));
  RecordProperty("ict_seam_duplicates", std::to_string(duplicates));
  std::cout << "[ ICT seams ] " << mesh.vertexCount() << " vertices, " << duplicates << " seam duplicates\n";
}

}  // namespace
}  // namespace myo
