// Fuzzes the scene parser (YAML or JSON through yaml-cpp and nlohmann-json). A scene that parses
// prints as JSON (sceneToJson), and that JSON parses back to a scene that prints the same
// (docs/scene_format.md: "parseScene(sceneToJson(d)) gives d back"); its tracks evaluate to
// finite values, activations within [−1, 1], the gaze within ±45°.
#include <cmath>

#include "fuzz_common.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/core/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = myo::fuzz::text(data, size);
  myo::SceneDesc scene;
  try {
    scene = myo::parseScene(text, "<fuzz>");
  } catch (const myo::InputError&) {
    return 0;
  }
  const std::string json = myo::sceneToJson(scene);
  myo::SceneDesc again;
  try {
    again = myo::parseScene(json, "<fuzz>");
  } catch (const myo::InputError& e) {
    std::fprintf(stderr, "the printed scene does not parse: %s\n%s\n", e.what(), json.c_str());
    FUZZ_EXPECT(false, "sceneToJson output parses");
  }
  FUZZ_EXPECT(myo::sceneToJson(again) == json, "scene JSON round trip");
  const double times[] = {-1.0, 0.0, 0.5 * scene.duration, scene.duration, 2.0 * scene.duration};
  for (const auto& [name, track] : scene.activations)
    for (double t : times) {
      const double a = track.at(t);
      FUZZ_EXPECT(std::isfinite(a) && std::abs(a) <= 1.0 + 1e-12, "activation in [-1, 1]");
    }
  for (double t : times) FUZZ_EXPECT(std::isfinite(scene.gravity.at(t)), "finite gravity scale");
  for (const auto& [name, track] : scene.dragForces)
    for (double t : times) FUZZ_EXPECT(track.at(t).allFinite(), "finite drag force");
  for (double t : times) {
    const myo::EyeGaze g = scene.gazeAt(t);
    for (size_t e = 0; e < 2; ++e)
      FUZZ_EXPECT(std::abs(g.pitchDeg[e]) <= myo::kGazeMaxDeg && std::abs(g.yawDeg[e]) <= myo::kGazeMaxDeg,
                  "gaze within the eye's range");
  }
  return 0;
}
