// One set of --view names (front, three-quarter, profile, back) for `run`, `render` and `head`,
// checked before any work.
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

class ViewNames : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_ViewNames_" + std::to_string(::getpid()) + "_" +
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

TEST_F(ViewNames, ViewNamesAreOneSetAndABadOneFailsBeforeAnyFolder) {
  const auto r = test::runCli("run '" + scene("v.json", "v", 0.1) + "' --out '" + (dir_ / "out").string() +
                              "' --render --view side" + cacheArg());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.merged.find("unknown view 'side' (use front, three-quarter, profile or back)"), std::string::npos) << r.merged;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_FALSE(fs::exists(dir_ / "cache"));  // nothing built either
  const auto h = test::runCli("head --levels 0 --view threequarter --render '" + (dir_ / "h.png").string() + "'");
  EXPECT_EQ(h.exitCode, 2);
  EXPECT_NE(h.merged.find("unknown view 'threequarter' (use front, three-quarter, profile or back)"), std::string::npos)
      << h.merged;
  for (const char* view : {"front", "three-quarter", "profile", "back"}) {
    const fs::path png = dir_ / (std::string(view) + ".png");
    const auto ok = test::runCli(std::string("head --levels 0 --size 64 --view ") + view + " --render '" + png.string() + "'");
    EXPECT_EQ(ok.exitCode, 0) << view << ": " << ok.merged;
    EXPECT_TRUE(fs::exists(png)) << view;
  }
}

}  // namespace
}  // namespace myo
