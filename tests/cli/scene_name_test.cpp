// A scene name names the output files: one that would lead out of --out is refused.
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

class SceneName : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_SceneName_" + std::to_string(::getpid()) + "_" +
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

TEST_F(SceneName, ASceneNameThatLeavesTheOutputFolderIsRejected) {
  for (const char* name : {"../escape", "a/b", "a\\\\b", ".."}) {
    const std::string path = scene("bad.json", name, 0.1);
    const auto r = test::runCli("run '" + path + "' --out '" + (dir_ / "out").string() + "'" + cacheArg());
    EXPECT_EQ(r.exitCode, 2) << name << ": " << r.merged;
    EXPECT_NE(r.merged.find(path + ":1:10: key 'name': "), std::string::npos) << r.merged;
    EXPECT_NE(r.merged.find("must not contain '/', '\\', or '..'"), std::string::npos) << r.merged;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
    EXPECT_FALSE(fs::exists(dir_ / "escape_0000.obj"));
  }
}

}  // namespace
}  // namespace myo
