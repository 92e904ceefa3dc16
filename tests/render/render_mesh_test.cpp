// renderMesh: coverage, lighting, depth test, per-vertex colours, on-top and translucent drawing.
#include <gtest/gtest.h>

#include "myoshell/render/markers.h"
#include "myoshell/render/render_mesh.h"

namespace myo {
namespace {

const Rgb kBlack = Rgb::Zero();

// Orthographic camera on +z looking at the origin; 100×100 pixels show [−1, 1]²: 50 px per cm.
Camera frontCamera() {
  Camera c;
  c.eye = Vec3(0, 0, 10);
  c.orthoHeight = 2.0;
  return c;
}

// A triangle in the plane z = `z`, counter-clockwise seen from +z: pixels (25,75) (75,75) (50,25).
MatX3 triangle(double z) {
  MatX3 V(3, 3);
  V << -0.5, -0.5, z, 0.5, -0.5, z, 0.0, 0.5, z;
  return V;
}
MatX3i oneFace() {
  MatX3i F(1, 3);
  F << 0, 1, 2;
  return F;
}

int coloredPixels(const Image& im) {
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += im.at(x, y) != kBlack;
  return n;
}

TEST(RenderMesh, TriangleFacingTheCameraCoversItsPixelsAndIsLit) {
  Image im(100, 100, kBlack);
  DepthBuffer depth(100, 100);
  renderMesh(im, depth, frontCamera(), triangle(0), oneFace());
  EXPECT_NEAR(coloredPixels(im), 1250, 60);  // area ½·50·50 px
  EXPECT_EQ(im.at(10, 10), kBlack);
  EXPECT_EQ(im.at(30, 30), kBlack);  // left of the edge (25,75)–(50,25)
  EXPECT_EQ(im.at(50, 80), kBlack);  // below the base
  const Rgb centre = im.at(50, 58);
  EXPECT_GT(centre.sum(), 0.5);
  EXPECT_NEAR(depth.at(50, 58), 10.0, 1e-9);  // cm in front of the eye
  EXPECT_TRUE(std::isinf(depth.at(10, 10)));
}

TEST(RenderMesh, BothSidesOfAnOpenMeshAreShadedUnlessCulled) {
  MatX3i back(1, 3);
  back << 0, 2, 1;  // the same triangle seen from its back side
  Image im(100, 100, kBlack);
  DepthBuffer depth(100, 100);
  RenderStyle s;
  s.backColor = Rgb(0.2, 0.3, 0.9);
  renderMesh(im, depth, frontCamera(), triangle(0), back, s);
  const Rgb c = im.at(50, 58);
  EXPECT_GT(c.z(), c.x());  // back colour, lit
  EXPECT_GT(c.sum(), 0.3);
  Image culled(100, 100, kBlack);
  DepthBuffer d2(100, 100);
  s.cullBackFaces = true;
  renderMesh(culled, d2, frontCamera(), triangle(0), back, s);
  EXPECT_EQ(coloredPixels(culled), 0);
}

TEST(RenderMesh, NearerTriangleHidesFartherWhateverTheDrawOrder) {
  RenderStyle red, blue;
  red.color = Rgb(1, 0, 0);
  blue.color = Rgb(0, 0, 1);
  red.specular = blue.specular = 0;  // no white highlight: any blue would come from the far one
  for (bool nearFirst : {true, false}) {
    Image im(100, 100, kBlack);
    DepthBuffer depth(100, 100);
    if (nearFirst) {
      renderMesh(im, depth, frontCamera(), triangle(1.0), oneFace(), red);
      renderMesh(im, depth, frontCamera(), triangle(-1.0), oneFace(), blue);
    } else {
      renderMesh(im, depth, frontCamera(), triangle(-1.0), oneFace(), blue);
      renderMesh(im, depth, frontCamera(), triangle(1.0), oneFace(), red);
    }
    const Rgb c = im.at(50, 58);
    EXPECT_GT(c.x(), 0.5) << "near first: " << nearFirst;
    EXPECT_EQ(c.z(), 0.0) << "near first: " << nearFirst;
    EXPECT_NEAR(depth.at(50, 58), 9.0, 1e-9);
  }
}

TEST(RenderMesh, PerVertexColoursInterpolate) {
  RenderStyle s;
  s.vertexColors.resize(3, 3);
  s.vertexColors << 1, 0, 0, 0, 1, 0, 0, 0, 1;
  s.ambient = 1, s.diffuse = 0, s.specular = 0;  // unlit: the colour itself
  for (bool perspective : {false, true}) {
    Camera cam = frontCamera();
    cam.perspective = perspective;
    cam.fovYDegrees = 2 * std::atan(0.1) * 180 / std::numbers::pi;  // 50 px per cm at z = 0 too
    Image im(100, 100, kBlack);
    DepthBuffer depth(100, 100);
    renderMesh(im, depth, cam, triangle(0), oneFace(), s);
    // Centroid (50, 58.3): pixel (50, 58) has centre (50.5, 58.5).
    const Rgb c = im.at(50, 58);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 1.0 / 3.0, 0.03) << "perspective " << perspective;
    EXPECT_GT(im.at(30, 72).x(), 0.6);  // near the red corner (25, 75)
    EXPECT_GT(im.at(70, 72).y(), 0.6);  // near the green corner (75, 75)
    EXPECT_GT(im.at(50, 30).z(), 0.6);  // near the blue corner (50, 25)
  }
}

TEST(RenderMesh, OnTopIgnoresTheSkinAndOpacityBlends) {
  RenderStyle skin, muscle;
  skin.color = Rgb(0.9, 0.9, 0.9);
  muscle.color = Rgb(1, 0, 0);
  muscle.ambient = skin.ambient = 1, muscle.diffuse = skin.diffuse = 0;
  muscle.specular = skin.specular = 0;
  {  // muscle behind the skin, drawn on top
    Image im(100, 100, kBlack);
    DepthBuffer depth(100, 100);
    renderMesh(im, depth, frontCamera(), triangle(1.0), oneFace(), skin);
    muscle.depthTest = false;
    muscle.depthWrite = false;
    renderMesh(im, depth, frontCamera(), triangle(-1.0), oneFace(), muscle);
    EXPECT_NEAR(im.at(50, 58).x(), 1.0, 1e-9);
    EXPECT_NEAR(im.at(50, 58).y(), 0.0, 1e-9);
    EXPECT_NEAR(depth.at(50, 58), 9.0, 1e-9);  // the skin's depth stays
  }
  {  // muscle first, then the skin at half opacity
    Image im(100, 100, kBlack);
    DepthBuffer depth(100, 100);
    muscle.depthTest = true;
    muscle.depthWrite = true;
    renderMesh(im, depth, frontCamera(), triangle(-1.0), oneFace(), muscle);
    skin.opacity = 0.5;
    renderMesh(im, depth, frontCamera(), triangle(1.0), oneFace(), skin);
    const Rgb c = im.at(50, 58);
    EXPECT_NEAR(c.x(), 0.95, 0.01);
    EXPECT_NEAR(c.y(), 0.45, 0.01);
  }
}

TEST(RenderMesh, WireframeDarkensTheEdges) {
  RenderStyle s;
  s.wireframe = true;
  s.wireWidth = 2;
  s.wireColor = Rgb(0, 0, 1);
  Image im(100, 100, kBlack);
  DepthBuffer depth(100, 100);
  renderMesh(im, depth, frontCamera(), triangle(0), oneFace(), s);
  EXPECT_EQ(im.at(50, 74), Rgb(0, 0, 1));  // on the base edge y = 75
  EXPECT_NE(im.at(50, 58), Rgb(0, 0, 1));
}

TEST(Markers, HiddenMarkersAreNotDrawn) {
  Image im(100, 100, kBlack);
  DepthBuffer depth(100, 100);
  RenderStyle grey;
  grey.color = Rgb(0.5, 0.5, 0.5);
  renderMesh(im, depth, frontCamera(), triangle(0), oneFace(), grey);
  const Rgb green(0, 1, 0), red(1, 0, 0);
  // (0, −0.2) is pixel (50, 60); (0.6, 0.6) is pixel (80, 20), outside the triangle.
  drawMarkers(im, &depth, frontCamera(),
              {{Vec3(0, -0.2, 0.5), green, 3}, {Vec3(0, -0.2, -2), red, 5}, {Vec3(0.6, 0.6, -2), red, 3}});
  EXPECT_EQ(im.at(50, 60), green);           // in front: drawn
  EXPECT_NE(im.at(50, 64), red);             // behind the surface: not drawn (would cover r = 5)
  EXPECT_EQ(im.at(80, 20), red);             // nothing in front of it
  drawMarkers(im, nullptr, frontCamera(), {{Vec3(0, -0.2, -2), red, 5}});
  EXPECT_EQ(im.at(50, 64), red);             // without a depth buffer every marker is drawn
}

}  // namespace
}  // namespace myo
