// The One-Euro filter against its definition: a constant passes unchanged, β = 0 is the
// first-order low-pass filter in closed form, jitter at rest is smoothed, and β cuts the lag of fast
// motion (Casiez et al. 2012).
#include "myoshell/anim/one_euro_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "myoshell/core/errors.h"

namespace myo {
namespace {

std::vector<double> uniformTimes(int n, double fps) {
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = i / fps;
  return t;
}

TEST(OneEuroFilter, ConstantPassesUnchanged) {
  const auto t = uniformTimes(50, 25.0);
  const std::vector<double> x(50, 0.37);
  const auto y = oneEuroFilter(t, x, OneEuroSettings{});
  for (double v : y) EXPECT_DOUBLE_EQ(v, 0.37);
}

TEST(OneEuroFilter, BetaZeroIsTheFirstOrderLowPassOfAStep) {
  // A unit step at i = 1 through y_i = y_{i−1} + α (1 − y_{i−1}) gives y_k = 1 − (1 − α)^k.
  const double fps = 30.0, fc = 2.0;
  const auto t = uniformTimes(40, fps);
  std::vector<double> x(40, 1.0);
  x[0] = 0.0;
  OneEuroSettings s;
  s.minCutoff = fc;
  s.beta = 0.0;
  const auto y = oneEuroFilter(t, x, s);
  const double alpha = 1.0 / (1.0 + 1.0 / (2.0 * M_PI * fc / fps));
  for (int k = 1; k < 40; ++k) EXPECT_NEAR(y[k], 1.0 - std::pow(1.0 - alpha, k), 1e-12) << k;
}

TEST(OneEuroFilter, SmoothsJitterAtRest) {
  const auto t = uniformTimes(500, 25.0);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<double> x(500);
  for (double& v : x) v = 0.3 + noise(rng);
  const auto y = oneEuroFilter(t, x, OneEuroSettings{});
  auto deviation = [](const std::vector<double>& v) {
    double s = 0.0;
    for (size_t i = 100; i < v.size(); ++i) s += (v[i] - 0.3) * (v[i] - 0.3);
    return std::sqrt(s / (v.size() - 100));
  };
  EXPECT_LT(deviation(y), 0.5 * deviation(x));
}

TEST(OneEuroFilter, BetaCutsTheLagOfFastMotion) {
  // A fast ramp (2 units/s): with β > 0 the filtered curve trails it by less than with β = 0.
  const auto t = uniformTimes(30, 25.0);
  std::vector<double> x(30);
  for (int i = 0; i < 30; ++i) x[i] = 2.0 * t[i];
  OneEuroSettings slow;
  slow.beta = 0.0;
  OneEuroSettings fast;
  fast.beta = 2.0;
  const auto ys = oneEuroFilter(t, x, slow), yf = oneEuroFilter(t, x, fast);
  EXPECT_LT(x[29] - yf[29], 0.5 * (x[29] - ys[29]));
  EXPECT_GT(x[29] - yf[29], 0.0);
}

TEST(OneEuroFilter, OffOrShortLeavesTheCurve) {
  OneEuroSettings off;
  off.enabled = false;
  const std::vector<double> t = {0.0, 0.1, 0.2}, x = {0.0, 1.0, 0.0};
  EXPECT_EQ(oneEuroFilter(t, x, off), x);
  EXPECT_EQ(oneEuroFilter({0.0}, {0.5}, OneEuroSettings{}), std::vector<double>{0.5});
}

TEST(OneEuroFilter, SettingsAreChecked) {
  OneEuroSettings s;
  s.minCutoff = 0.0;
  try {
    checkOneEuroSettings(s, "drive --filter");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "drive --filter: min_cutoff must be a positive number of Hz");
  }
  s = {};
  s.beta = -1.0;
  EXPECT_THROW(checkOneEuroSettings(s), InputError);
  s = {};
  s.derivativeCutoff = NAN;
  EXPECT_THROW(checkOneEuroSettings(s), InputError);
  EXPECT_NO_THROW(checkOneEuroSettings(OneEuroSettings{}));
}

}  // namespace
}  // namespace myo
