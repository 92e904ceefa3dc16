// Accuracy of the reduced solutions against the full-space reference and beam theory on a clamped
// strip (validation.h; numbers in docs/validation.md). Asserts the bounds of the validation issue.
#include "myoshell/verify/validation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace myo {
namespace {

constexpr int kModes = 20;

StripDef strip(int nx, int ny) {
  StripDef d;
  d.nx = nx;
  d.ny = ny;
  return d;
}

void print(const AccuracyCase& c) {
  std::cout << c.name << " (d = " << c.d << "): " << c.quantity << " ref " << c.reference << ", warped "
            << c.warped << ", linear " << c.linear << "; error (" << c.metric << ") warped " << c.errorWarped
            << ", linear " << c.errorLinear << "\n";
  for (const auto& [k, v] : c.extra) std::cout << "    " << k << " = " << v << "\n";
}

TEST(BendingRigidity, AlternatingGridValues) {
  const BendingRigidity D = measureBendingRigidity(strip(40, 4));
  const double kB = StripDef::defaultMaterial().kB;
  // Bent onto a cylinder: D = 6·k_B exactly, no Poisson coupling (diagonals see only twist).
  EXPECT_NEAR(D.cylinder / kB, 6.0, 1e-5);
  EXPECT_NEAR(D.poisson, 0.0, 1e-6);
  EXPECT_NEAR(D.anticlastic, D.cylinder, 1e-6 * D.cylinder);
  // Interior relaxed: the non-affine fluctuations of the hinge energy soften it to 0.8·D_cyl.
  EXPECT_NEAR(D.relaxed / D.cylinder, 0.80, 0.005);
}

// Small end load: warped, linear and full-space agree within 2%; beam theory within 5%, at two
// mesh resolutions.
class SmallLoad : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(SmallLoad, ReducedMatchesReferenceAndBeamTheory) {
  const auto [nx, ny] = GetParam();
  const AccuracyCase c = cantileverSmallLoad(strip(nx, ny), kModes, 0.01);
  print(c);
  EXPECT_LE(c.errorWarped, 0.02);
  EXPECT_LE(c.errorLinear, 0.02);
  EXPECT_LE(c.get("field_error_warped"), 0.02);
  EXPECT_LE(c.get("field_error_linear"), 0.02);
  EXPECT_NEAR(c.reference, 0.01, 2e-4);  // δ_lin/L = 1%, L = 1 cm
  EXPECT_LE(c.get("beam_tip_error"), 0.05);
  EXPECT_LE(c.get("omega1_error"), 0.05);
  // Measured and documented: the cylinder-imposed D_eff misses the mesh's softer relaxed modes.
  EXPECT_GT(c.get("beam_tip_error_cylinder"), 0.2);
  // Tiny loads (P ≈ 1.4e-4 dyn) sit at the round-off floor of the membrane forces: measured
  // 1.3e-7 and 7.5e-7, far below what would matter against a 2% bound.
  EXPECT_LE(c.get("reference_relative_residual"), 1e-5);
  EXPECT_TRUE(c.passed);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, SmallLoad,
                         ::testing::Values(std::pair{40, 4}, std::pair{80, 8}),
                         [](const auto& info) {
                           return std::to_string(info.param.first) + "x" + std::to_string(info.param.second);
                         });

// Large end load (tip rotation ≈ 50°): modal warping beats linear modal by ≥ 3× and keeps the
// strip's length, while the linear solution stretches it.
TEST(LargeLoad, WarpedClearlyBetterThanLinear) {
  const AccuracyCase c = cantileverLargeLoad(strip(40, 4), kModes, 0.8);
  print(c);
  EXPECT_GE(c.get("tip_rotation_deg_reference"), 45.0);
  EXPECT_GE(c.errorLinear, 3.0 * c.errorWarped);
  EXPECT_LE(c.errorWarped, 0.15);  // METHOD.md §5.3: ≈ 0.11 at this load
  EXPECT_GE(c.get("tip_error_linear"), 3.0 * c.get("tip_error_warped"));
  // Length growth of the centre line: the reference is inextensible to < 0.1%, linear stretches
  // by > 20%, warped shortens by < 6%.
  EXPECT_LE(std::abs(c.get("length_growth_reference")), 1e-3);
  EXPECT_GE(c.get("length_growth_linear"), 0.2);
  EXPECT_LE(std::abs(c.get("length_growth_warped")), 0.06);  // measured −4.3%
  EXPECT_GE(c.get("area_growth_linear"), 0.1);
  EXPECT_LE(std::abs(c.get("area_growth_warped")), 0.06);  // measured −4.9%
  EXPECT_LE(c.get("reference_relative_residual"), 1e-6);
  EXPECT_TRUE(c.passed);
}

// Released tip: warped (exact stepper) vs full-space BDF2. Bound: ≤ 10% trajectory error (the
// measured 4.5% is mostly the 3% static error of the starting shape) and better than linear.
TEST(Dynamics, ReleasedTipTrajectory) {
  const AccuracyCase c = releasedTip(strip(40, 4), kModes, 0.3, 2.0, 100, 0.02);
  print(c);
  EXPECT_LE(c.errorWarped, 0.10);
  EXPECT_LE(c.errorWarped, c.errorLinear);
  EXPECT_TRUE(c.passed);
}

}  // namespace
}  // namespace myo
