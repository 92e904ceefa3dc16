// The landmark reader accepts the `confidence` that `myoshell landmarks` writes, in both layouts.
#include <gtest/gtest.h>

#include "myoshell/head/landmarks.h"

namespace myo {
namespace {

TEST(LandmarkConfidence, IgnoredInTheLayoutAndThePlainMap) {
  const Landmarks a = parseLandmarks(
      R"({"named": {"nose_tip": {"vertex": 4, "confidence": 0.93}}, "confidence": {"multipie68": []}})", 10, "a.json");
  EXPECT_EQ(a.vertex("nose_tip"), 4);
  const Landmarks b = parseLandmarks(R"({"nose_tip": 3, "confidence": {"nose_tip": 0.9}})", 10, "b.json");
  EXPECT_EQ(b.vertex("nose_tip"), 3);
  EXPECT_EQ(b.named.size(), 1u);
}

}  // namespace
}  // namespace myo
