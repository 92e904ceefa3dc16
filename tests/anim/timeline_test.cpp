#include <gtest/gtest.h>

#include "myoshell/anim/timeline.h"
#include "myoshell/core/errors.h"

namespace myo {
namespace {

TEST(Timeline, InterpolatesStepLinearAndSmooth) {
  const ScalarTrack track({{0.0, 0.0, Interpolation::Linear},
                           {1.0, 1.0, Interpolation::Step},
                           {2.0, -1.0, Interpolation::Smooth},
                           {3.0, 1.0, Interpolation::Linear}},
                          "t");
  EXPECT_DOUBLE_EQ(track.at(-5.0), 0.0);   // before the first key: its value
  EXPECT_DOUBLE_EQ(track.at(0.25), 0.25);  // linear
  EXPECT_DOUBLE_EQ(track.at(1.5), 1.0);    // step holds
  EXPECT_DOUBLE_EQ(track.at(2.0), -1.0);
  EXPECT_DOUBLE_EQ(track.at(2.5), 0.0);    // smoothstep is symmetric about the middle
  EXPECT_NEAR(track.at(2.1), -1.0 + 2.0 * (0.03 - 0.002), 1e-12);  // 3s² − 2s³ at s = 0.1
  EXPECT_DOUBLE_EQ(track.at(10.0), 1.0);   // after the last key: its value
  EXPECT_DOUBLE_EQ(ScalarTrack().at(1.0), 0.0);
}

TEST(Timeline, VectorTracksInterpolateComponentwise) {
  const VectorTrack track({{0.0, Vec3(0, 0, 0)}, {2.0, Vec3(2, -4, 6)}}, "drag");
  EXPECT_TRUE(track.at(1.0).isApprox(Vec3(1, -2, 3)));
}

TEST(Timeline, RejectsKeysOutOfOrder) {
  try {
    ScalarTrack({{1.0, 0.0}, {1.0, 1.0}}, "timeline.activations.m");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("timeline.activations.m: key times must increase"), std::string::npos) << e.what();
  }
  EXPECT_THROW(interpolationFromString("cubic"), InputError);
}

}  // namespace
}  // namespace myo
