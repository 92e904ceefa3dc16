// Fuzzes the performance readers (anim/performance.h): detected, and forced to each of the three
// layouts, with the options a user can give. A performance that reads has at least two frames at
// strictly increasing times from 0, one value per frame in every channel, each in [0, 1], a finite
// head pose and gaze per frame or none, a finite positive frame rate, and a dropped-frame count
// ≥ 0 with a warning when it is not 0; channel names are unique.
#include <cmath>
#include <optional>
#include <set>

#include "fuzz_common.h"
#include "myoshell/anim/performance.h"
#include "myoshell/core/errors.h"

namespace {

void check(const myo::Performance& p) {
  FUZZ_EXPECT(p.times.size() >= 2, "two frames at least");
  FUZZ_EXPECT(p.times.front() == 0.0, "times start at 0");
  for (size_t i = 1; i < p.times.size(); ++i) FUZZ_EXPECT(p.times[i] > p.times[i - 1], "times increase");
  FUZZ_EXPECT(std::isfinite(p.duration()) && p.duration() > 0, "finite positive duration");
  FUZZ_EXPECT(std::isfinite(p.fps) && p.fps > 0, "finite positive frame rate");
  FUZZ_EXPECT(std::isfinite(p.auScale) && p.auScale > 0, "positive AU scale");
  std::set<std::string> names;
  for (const myo::PerformanceChannel& c : p.channels) {
    FUZZ_EXPECT(names.insert(c.name).second, "channel names unique");
    FUZZ_EXPECT(p.find(c.name) == &c, "find gives the channel");
    FUZZ_EXPECT(c.values.size() == p.times.size(), "a value per frame");
    for (const double v : c.values) FUZZ_EXPECT(v >= 0 && v <= 1, "values in [0, 1]");
  }
  FUZZ_EXPECT(p.headPose.empty() || p.headPose.size() == p.times.size(), "a head pose per frame or none");
  for (const myo::Vec3& r : p.headPose) FUZZ_EXPECT(r.allFinite(), "finite head pose");
  FUZZ_EXPECT(p.gaze.empty() || p.gaze.size() == p.times.size(), "a gaze per frame or none");
  for (const myo::EyeGaze& g : p.gaze)
    for (size_t e = 0; e < 2; ++e)
      FUZZ_EXPECT(std::isfinite(g.pitchDeg[e]) && std::isfinite(g.yawDeg[e]), "finite gaze");
  FUZZ_EXPECT(p.droppedFrames >= 0, "dropped frames counted");
  FUZZ_EXPECT(p.droppedFrames == 0 || !p.warnings.empty(), "dropped frames are warned about");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  const std::optional<myo::PerformanceInput> inputs[] = {std::nullopt, myo::PerformanceInput::OpenFace,
                                                         myo::PerformanceInput::LiveLink,
                                                         myo::PerformanceInput::MediaPipe};
  for (const auto& input : inputs) {
    myo::PerformanceOptions options;
    options.input = input;
    for (const int variant : {0, 1}) {
      if (variant == 1) {  // what a user may add: a face, a scale, a rate, a threshold
        options.face = 1;
        options.auScale = 5.0;
        options.inputFps = 30.0;
        options.minConfidence = 0.0;
      }
      try {
        check(myo::parsePerformance(text, "fuzz_performance", options));
      } catch (const myo::InputError&) {
      }
    }
  }
  return 0;
}
