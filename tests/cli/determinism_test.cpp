// The same scene run twice gives byte-identical OBJ, GLB, PC2 and PNG outputs, and a stats.json
// identical but for its timings.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// stats.json without the fields that measure time.
nlohmann::json withoutTimings(nlohmann::json j) {
  for (const char* key : {"precompute_seconds", "steps_per_second", "step_ms_mean", "cache_hits", "simulate_seconds", "output_seconds", "realtime_factor"}) j.erase(key);
  for (auto& frame : j["per_frame"]) frame.erase("step_ms");
  return j;
}

TEST(Determinism, TheSameSceneGivesTheSameBytes) {
  const fs::path dir = fs::temp_directory_path() / ("myo_determinism_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"name": "twice", "model": "thesis",
    "muscles": {"use": ["zygomaticus_major_left", "depressor_anguli_oris_right"]},
    "numerics": {"skin_modes": 8}, "duration": 0.15, "fps": 20,
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.1, "value": 1}],
                                 "depressor_anguli_oris_right": [{"t": 0, "value": 0.5}]}}})";
  for (const char* run : {"a", "b"}) {
    const auto r = test::runCli("run '" + (dir / "scene.json").string() + "' --out '" + (dir / run).string() +
                                "' --format glb,pc2,obj --render --size 96 --cache '" + (dir / ("cache_" + std::string(run))).string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.merged;
  }
  int compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "a")) {
    if (entry.is_directory() || entry.path().filename() == "stats.json") continue;
    const fs::path other = dir / "b" / fs::relative(entry.path(), dir / "a");
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(bytes(entry.path()) == bytes(other)) << "differs: " << entry.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 4 + 4 + 2 + 1);  // OBJ and PNG frames, GLB, PC2, contact sheet
  const auto a = nlohmann::json::parse(bytes(dir / "a" / "stats.json"));
  const auto b = nlohmann::json::parse(bytes(dir / "b" / "stats.json"));
  EXPECT_EQ(withoutTimings(a), withoutTimings(b));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace myo
