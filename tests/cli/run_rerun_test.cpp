// `myoshell run` into a folder a previous run wrote: the files of that run this one does not
// rewrite go (stale frames, an old GLB or PC2), and nothing else (the user's own files stay).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <fcntl.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "myoshell/render/video.h"
#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

class RunRerun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_RunRerun_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string scene(const std::string& file, const std::string& name, double duration) {
    std::ofstream(dir_ / file) << R"({"name": ")" << name << R"(", "model": "thesis", "muscles": {"use": ["zygomaticus_major_left"]},
      "gravity": {"enabled": false}, "numerics": {"skin_modes": 8}, "duration": )"
                               << duration << R"(, "fps": 20,
      "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.2, "value": 1}]}}})";
    return (dir_ / file).string();
  }
  std::string cacheArg() const { return " --cache '" + (dir_ / "cache").string() + "'"; }
  fs::path dir_;
};

TEST_F(RunRerun, AShorterRerunRemovesTheStaleFramesAndExportsButNotTheUsersFiles) {
  const fs::path out = dir_ / "out";
  auto r = test::runCli("run '" + scene("s.json", "s", 0.45) + "' --out '" + out.string() + "' --format obj,glb,pc2" + cacheArg());
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  for (int f = 0; f < 10; ++f) ASSERT_TRUE(fs::exists(out / "obj" / ("s_000" + std::to_string(f) + ".obj"))) << f;
  ASSERT_TRUE(fs::exists(out / "s.glb"));
  std::ofstream(out / "notes.txt") << "mine";
  std::ofstream(out / "obj" / "mine.obj") << "# mine";
  r = test::runCli("run '" + scene("s.json", "s", 0.2) + "' --out '" + out.string() + "' --format obj" + cacheArg());
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  for (int f = 0; f < 5; ++f) EXPECT_TRUE(fs::exists(out / "obj" / ("s_000" + std::to_string(f) + ".obj"))) << f;
  for (int f = 5; f < 10; ++f) EXPECT_FALSE(fs::exists(out / "obj" / ("s_000" + std::to_string(f) + ".obj"))) << f;
  EXPECT_FALSE(fs::exists(out / "s.glb"));
  EXPECT_FALSE(fs::exists(out / "s.pc2"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_TRUE(fs::exists(out / "obj" / "mine.obj"));
  EXPECT_TRUE(fs::exists(out / "stats.json"));
  std::ifstream in(out / ".myoshell-manifest.json");
  const nlohmann::json manifest = nlohmann::json::parse(in);
  EXPECT_EQ(manifest["files"].size(), 6u);  // five frames and stats.json
}

}  // namespace
}  // namespace myo
