// The same scene run twice, on one thread and on two, gives byte-identical OBJ, GLB, PC2 and PNG
// outputs, and a stats.json identical but for its timings; the anatomical face's pose is the same
// bytes on one, two and three threads.
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

TEST(Determinism, TheSameSceneGivesTheSameBytesOnOneThreadAndOnTwo) {
  const fs::path dir = fs::temp_directory_path() / ("myo_determinism_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"name": "twice", "model": "thesis",
    "muscles": {"use": ["zygomaticus_major_left", "depressor_anguli_oris_right"]},
    "numerics": {"skin_modes": 8}, "duration": 0.15, "fps": 20,
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.1, "value": 1}],
                                 "depressor_anguli_oris_right": [{"t": 0, "value": 0.5}]}}})";
  for (const char* run : {"a", "b"}) {
    const std::string threads = run == std::string("a") ? "1" : "2";
    const auto r = test::runCli("run '" + (dir / "scene.json").string() + "' --out '" + (dir / run).string() +
                                "' --format glb,pc2,obj --render --size 96 --threads " + threads + " --cache '" +
                                (dir / ("cache_" + std::string(run))).string() + "'");
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

// The anatomical face's build (step 1 beside the factorisation, the static responses side by side),
// each from a cold cache: the settled shape is the same bytes for every thread count.
TEST(Determinism, TheAnatomicalPoseIsTheSameBytesOnOneTwoAndThreeThreads) {
  const fs::path dir = fs::temp_directory_path() / ("myo_determinism_pose_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string first;
  for (const char* threads : {"1", "2", "3"}) {
    const fs::path out = dir / (std::string(threads) + ".obj");
    const auto r = test::runCli("pose --set zygomaticus_major_left=0.8 --set corrugator_supercilii_right=0.5 --head-pose 30,10,0 --out '" +
                                out.string() + "' --threads " + threads + " --cache '" + (dir / ("cache_" + std::string(threads))).string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.merged;
    if (first.empty())
      first = bytes(out);
    else
      EXPECT_TRUE(bytes(out) == first) << threads << " threads";
  }
  EXPECT_GT(first.size(), 100000u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace myo
