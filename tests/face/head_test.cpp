#include <gtest/gtest.h>

#include <set>

#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/head/mediapipe_mesh.h"
#include "myoshell/io/head_files.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/subdivision.h"
#include "support/test_data.h"

namespace myo {
namespace {

TEST(DefaultHead, SourceMeshIsTheCanonicalFaceMesh) {
  const TriMesh m = defaultHeadSourceMesh();
  EXPECT_EQ(m.vertexCount(), 468);
  EXPECT_EQ(m.triangleCount(), 898);
  const auto loops = boundaryLoops(m.F, m.vertexCount());
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 36u);
  // cm, +y up, +z out of the face, symmetric about x = 0: forehead (10) to chin (152) ≈ 17.7 cm.
  EXPECT_NEAR(m.V(10, 1) - m.V(152, 1), 17.67, 0.01);
  EXPECT_GT(m.V(4, 2), m.V(10, 2));        // nose tip in front of the forehead
  EXPECT_LT(m.V(61, 0), 0.0);              // 61 is the subject's right mouth corner: −x
  EXPECT_NEAR(m.V(61, 0), -m.V(291, 0), 1e-6);
}

TEST(DefaultHead, MouthOpeningRemovesTheEighteenLipTriangles) {
  TriMesh m = defaultHeadSourceMesh();
  EXPECT_EQ(openMediapipeMouth(m), 18);
  EXPECT_EQ(m.triangleCount(), 880);
  const auto loops = boundaryLoops(m.F, m.vertexCount());
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 36u);  // outer rim
  EXPECT_EQ(loops[1].size(), 20u);  // mouth: both inner lip lines
  const std::set<int> mouth(loops[1].begin(), loops[1].end());
  for (int v : kMediapipeInnerLipUpper) EXPECT_TRUE(mouth.count(v)) << v;
  for (int v : kMediapipeInnerLipLower) EXPECT_TRUE(mouth.count(v)) << v;
}

TEST(DefaultHead, BuildsFromEmbeddedDataAtThesisSize) {
  // The thesis model's built-in head (eyes closed); the anatomical model's, with open eyes:
  // eyelids_default_head_test.cpp.
  const Head head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Thesis));
  const TriMesh& m = head.mesh;
  // 468 + 1348 edges → 1816; + 5336 edges → 7152 vertices, 14080 triangles.
  EXPECT_EQ(m.vertexCount(), 7152);
  EXPECT_EQ(m.triangleCount(), 880 * 16);
  const EdgeTable table = buildEdgeTable(m.F, m.vertexCount());
  EXPECT_EQ(table.nonManifoldCount, 0);
  EXPECT_EQ(table.inconsistentOrientationCount, 0);
  // Two boundary loops: the outer rim (36·4 edges) and the open mouth (20·4).
  const auto loops = boundaryLoops(m.F, m.vertexCount());
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 144u);
  EXPECT_EQ(loops[1].size(), 80u);
  // Original ids kept: the subdivided vertex i is near MediaPipe's vertex i (Loop moves it a little).
  const TriMesh src = defaultHeadSourceMesh();
  for (int i = 0; i < 468; ++i) EXPECT_LT((m.V.row(i) - src.V.row(i)).norm(), 0.5) << i;
  // Mouth open: the inner lip landmarks lie on the mouth loop.
  const std::set<int> mouth(loops[1].begin(), loops[1].end());
  EXPECT_TRUE(mouth.count(head.landmarks.vertex("upper_lip_inner")));
  EXPECT_TRUE(mouth.count(head.landmarks.vertex("lower_lip_inner")));
  for (int k = 60; k < 68; ++k) EXPECT_TRUE(mouth.count(head.landmarks.multipie68[k])) << k;
  // Outward normals: the nose tip's triangles face +z.
  EXPECT_EQ(head.landmarks.vertex("nose_tip"), 4);
  EXPECT_EQ(head.landmarks.vertex("mouth_corner_right"), 61);
  EXPECT_EQ(head.landmarks.vertex("mouth_corner_left"), 291);
  Vec3 n = Vec3::Zero();
  for (int t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      if (m.F(t, k) == 4) {
        const Vec3 a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), c = m.V.row(m.F(t, 2));
        n += (b - a).cross(c - a);
      }
  EXPECT_GT(n.normalized().z(), 0.9);
  // Every required landmark resolves, and the frame has the documented axes.
  head.landmarks.requireAll();
  const FaceFrame f = head.frame();
  EXPECT_GT(f.axes(0, 0), 0.99);
  EXPECT_GT(f.axes(1, 1), 0.95);
  EXPECT_GT(f.axes(2, 2), 0.95);
  EXPECT_NEAR(f.scale, 8.9, 0.2);
}

TEST(DefaultHead, GravityPinsAreTheRimAndTheNoseBridge) {
  const Head head = loadDefaultHead();
  const auto loops = boundaryLoops(head.mesh.F, head.mesh.vertexCount());
  EXPECT_EQ(head.gravityPins.size(), loops[0].size() + 2);
  const std::set<int> pins(head.gravityPins.begin(), head.gravityPins.end());
  for (int v : loops[0]) EXPECT_TRUE(pins.count(v));
  EXPECT_TRUE(pins.count(head.landmarks.vertex("nasion_approx")));
  for (int v : loops[1]) EXPECT_FALSE(pins.count(v)) << "mouth vertex " << v << " pinned";
}

TEST(IctHead, LoadsWithLandmarksAndRigidPins) {
  MYO_REQUIRE_SHARED_DATA();
  const auto dir = test::sharedDataDir() / "ict";
  const Head head = loadHead((dir / "head_skin.obj").string(),
                             (dir / "landmarks_multipie68.json").string(),
                             (dir / "rigid_vertices.json").string());
  EXPECT_EQ(head.mesh.vertexCount(), 11248);
  EXPECT_EQ(head.mesh.triangleCount(), 22288);
  EXPECT_EQ(head.gravityPins.size(), 910u);
  EXPECT_EQ(head.landmarks.multipie68.size(), 68u);
  EXPECT_EQ(head.landmarks.vertex("nose_tip"), 4857);
  // Names ICT's file does not give resolve through their Multi-PIE point.
  EXPECT_EQ(head.landmarks.vertex("upper_lip_inner"), head.landmarks.multipie68[62]);
  EXPECT_EQ(boundaryLoops(head.mesh.F, head.mesh.vertexCount()).size(), 4u);
  const FaceFrame f = head.frame();
  EXPECT_GT(f.axes(0, 0), 0.99);
  EXPECT_GT(f.axes(2, 2), 0.95);
}

}  // namespace
}  // namespace myo
