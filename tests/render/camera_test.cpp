// Cameras: projection conventions, view presets from a face frame, fit to bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "myoshell/render/camera.h"
#include "myoshell/render/render_mesh.h"

namespace myo {
namespace {

// A unit square centred at `centre` whose front side faces `normal` (one of ±x, ±y, ±z).
void square(const Vec3& centre, const Vec3& normal, MatX3& V, MatX3i& F) {
  const Vec3 a = std::abs(normal.y()) > 0.5 ? Vec3::UnitZ() : Vec3::UnitY();
  const Vec3 b = a.cross(normal);  // (b, a, normal) right-handed
  V.resize(4, 3);
  V.row(0) = centre - 0.5 * b - 0.5 * a;
  V.row(1) = centre + 0.5 * b - 0.5 * a;
  V.row(2) = centre + 0.5 * b + 0.5 * a;
  V.row(3) = centre - 0.5 * b + 0.5 * a;
  F.resize(2, 3);
  F << 0, 1, 2, 0, 2, 3;
}

// Number of drawn pixels of the square facing `normal` seen by `camera` with back faces culled.
int visiblePixels(const Camera& camera, const Vec3& normal) {
  MatX3 V;
  MatX3i F;
  square(Vec3::Zero(), normal, V, F);
  Image im(64, 64, Rgb::Zero());
  DepthBuffer depth(64, 64);
  RenderStyle s;
  s.cullBackFaces = true;
  renderMesh(im, depth, camera, V, F, s);
  int n = 0;
  for (double d : depth.depth) n += std::isfinite(d);
  return n;
}

TEST(Camera, ProjectionPutsUpAtTheTopAndTheTargetAtTheCentre) {
  Camera c;
  c.eye = Vec3(0, 0, 10);
  c.orthoHeight = 4;
  const ScreenPoint centre = project(c, Vec3::Zero(), 200, 100);
  EXPECT_DOUBLE_EQ(centre.x, 100);
  EXPECT_DOUBLE_EQ(centre.y, 50);
  EXPECT_DOUBLE_EQ(centre.depth, 10);
  const ScreenPoint up = project(c, Vec3(1, 1, 0), 200, 100);
  EXPECT_DOUBLE_EQ(up.x, 125);  // 25 px per cm
  EXPECT_DOUBLE_EQ(up.y, 25);
  c.perspective = true;
  EXPECT_GT(project(c, Vec3(1, 0, 5), 200, 100).x, project(c, Vec3(1, 0, 0), 200, 100).x);
}

TEST(Camera, PresetsSeeTheExpectedSide) {
  // A face frame turned 90° about world y: frame x (subject's left) = world −z, frame z = world +x.
  ViewFrame frame;
  frame.axes.col(0) = Vec3(0, 0, -1);
  frame.axes.col(1) = Vec3(0, 1, 0);
  frame.axes.col(2) = Vec3(1, 0, 0);
  frame.scale = 1;
  const Vec3 left = frame.axes.col(0), up = frame.axes.col(1), out = frame.axes.col(2);

  const Camera front = presetCamera(frame, ViewPreset::front);
  EXPECT_GT(visiblePixels(front, out), 100);
  EXPECT_EQ(visiblePixels(front, -out), 0);
  EXPECT_EQ(visiblePixels(front, left), 0);
  // The subject's left appears on the image's right; up is up.
  EXPECT_GT(project(front, left, 64, 64).x, 32);
  EXPECT_LT(project(front, up, 64, 64).y, 32);

  const Camera profile = presetCamera(frame, ViewPreset::profile);
  EXPECT_GT(visiblePixels(profile, -left), 100);  // the subject's right side
  EXPECT_EQ(visiblePixels(profile, left), 0);
  EXPECT_EQ(visiblePixels(profile, out), 0);

  const Camera tq = presetCamera(frame, ViewPreset::threeQuarter);
  const Vec3 toEye = (tq.eye - tq.target).normalized();
  const double a = 35 * std::numbers::pi / 180;
  EXPECT_NEAR(toEye.dot(out), std::cos(a), 1e-12);
  EXPECT_NEAR(toEye.dot(-left), std::sin(a), 1e-12);
  EXPECT_GT(visiblePixels(tq, out), 100);
  EXPECT_GT(visiblePixels(tq, -left), 50);

  EXPECT_GT(visiblePixels(presetCamera(frame, ViewPreset::back), -out), 100);
}

TEST(Camera, FitToBoundsFillsTheImageWithTheMargin) {
  MatX3 V(4, 3);
  V << 3, 1, 0, 7, 1, 2, 3, 3, -1, 7, 3, 0;  // 4 × 2 cm seen from +z
  for (bool perspective : {false, true}) {
    Camera c;
    c.perspective = perspective;
    fitToBounds(c, V, 200, 100, 0.1);
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (int i = 0; i < 4; ++i) {
      const ScreenPoint s = project(c, V.row(i).transpose(), 200, 100);
      EXPECT_GT(s.depth, 0);
      x0 = std::min(x0, s.x), x1 = std::max(x1, s.x), y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
    }
    EXPECT_GE(x0, 20 - 1e-9);
    EXPECT_LE(x1, 180 + 1e-9);
    EXPECT_GE(y0, 10 - 1e-9);
    EXPECT_LE(y1, 90 + 1e-9);
    if (!perspective) {
      EXPECT_NEAR(x0, 20, 1e-9);  // the width is the binding extent
      EXPECT_NEAR(x1, 180, 1e-9);
      EXPECT_NEAR(0.5 * (y0 + y1), 50, 1e-9);
    } else {
      EXPECT_GT(x1 - x0, 40);  // the bounding sphere is conservative, but the mesh fills a good part
    }
  }
}

}  // namespace
}  // namespace myo
