// glCameraMatrices against camera.h's project(): the same pixel and depth for any camera.
#include <gtest/gtest.h>

#include <random>

#include "myoshell/gl/gl_renderer.h"

namespace myo {
namespace {

// Pixel coordinates (camera.h convention) and view depth of p through the GL matrices, in double.
ScreenPoint throughGl(const GlCameraMatrices& m, const Vec3& p, int width, int height) {
  const Eigen::Vector4d eye = m.view.cast<double>() * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
  const Eigen::Vector4d clip = m.projection.cast<double>() * eye;
  ScreenPoint s;
  s.x = 0.5 * (clip.x() / clip.w() + 1.0) * width;
  s.y = 0.5 * (1.0 - clip.y() / clip.w()) * height;  // NDC y = +1 is the top row
  s.depth = -eye.z();
  return s;
}

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

void expectAgreement(bool perspective) {
  std::mt19937 rng(perspective ? 7 : 3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int inside = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Camera c;
    c.perspective = perspective;
    c.target = Vec3(uni(rng), uni(rng), uni(rng));
    c.eye = c.target + (6.0 + 2.0 * uni(rng)) * randomUnit(rng);  // points stay ≥ 1.4 cm in front
    c.up = randomUnit(rng);
    c.orthoHeight = 3.0 + uni(rng);
    c.fovYDegrees = 40.0 + 15.0 * uni(rng);
    const int width = 160 + 40 * trial, height = 120 + 25 * (trial % 7);
    const GlCameraMatrices m = glCameraMatrices(c, width, height);
    for (int k = 0; k < 50; ++k) {
      const Vec3 p = c.target + 1.5 * Vec3(uni(rng), uni(rng), uni(rng));
      const ScreenPoint want = project(c, p, width, height);
      const ScreenPoint got = throughGl(m, p, width, height);
      if (std::abs(want.x - 0.5 * width) > width || std::abs(want.y - 0.5 * height) > height) continue;
      ASSERT_NEAR(got.x, want.x, 1e-4) << "trial " << trial << " point " << k;
      ASSERT_NEAR(got.y, want.y, 1e-4) << "trial " << trial << " point " << k;
      ASSERT_NEAR(got.depth, want.depth, 1e-5) << "trial " << trial << " point " << k;
      // The point lies inside the depth range, so GL keeps it.
      EXPECT_GT(want.depth, m.depthNear);
      EXPECT_LT(want.depth, m.depthFar);
      inside += want.x > 0 && want.x < width && want.y > 0 && want.y < height;
    }
  }
  EXPECT_GT(inside, 300);  // most points land in the picture: the test is not vacuous
}

TEST(GlCamera, OrthographicMatricesAgreeWithProject) { expectAgreement(false); }
TEST(GlCamera, PerspectiveMatricesAgreeWithProject) { expectAgreement(true); }

TEST(GlCamera, OrthographicDepthRangeReachesBehindTheEye) {
  Camera c;  // eye at z = 10 looking at the origin
  const GlCameraMatrices m = glCameraMatrices(c, 100, 100);
  EXPECT_LT(m.depthNear, -10.0);  // the software renderer draws such points too
  EXPECT_GT(m.depthFar, 10.0);
}

}  // namespace
}  // namespace myo
