// --data, --scenes and --cache are relative to the current directory, like every path on a
// command line. bench and figures re-root the thesis scenes' head paths at the data folder and
// then at the scenes' folder: a relative --data used to be captured by the second and looked for
// under scenes/thesis/ (`bench --data ../shared/data`: "scenes/thesis/../shared/data/ict/... not found").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class RelativePaths : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_relative_paths_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "work");
    fs::create_directory_symlink(test::sourceDir() / "scenes", dir_ / "work" / "scenes");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(RelativePaths, BenchLooksForTheIctHeadUnderTheDataFolderFromHere) {
  // The ICT head is absent under nodata/: the note names where it was looked for, and no face is built.
  const test::CliResult r = test::runCli(
      "bench --json --heads ict --rows t2_zygomaticus --no-reference --scenes scenes/thesis --data nodata --cache cache",
      dir_ / "work");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["rows"].empty());
  ASSERT_EQ(j["notes"].size(), 1u);
  EXPECT_THAT(j["notes"][0].get<std::string>(),
              HasSubstr("ICT head skipped: " + (dir_ / "work" / "nodata" / "ict" / "head_skin.obj").string() + " not found"));
}

TEST_F(RelativePaths, FiguresLookForTheIctHeadUnderTheDataFolderFromHere) {
  const test::CliResult r = test::runCli(
      "figures --json --only fig27 --scenes scenes/thesis --data nodata --cache cache --out fig", dir_ / "work");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["skipped"].size(), 1u);
  EXPECT_THAT(j["skipped"][0]["reason"].get<std::string>(),
              HasSubstr((dir_ / "work" / "nodata" / "ict" / "head_skin.obj").string()));
}

TEST_F(RelativePaths, PathsPrintsTheFoldersResolvedFromHere) {
  const test::CliResult r = test::runCli("paths --json --cache c --data d", dir_ / "work");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["cache"]["path"], (dir_ / "work" / "c").string());
  EXPECT_EQ(j["data"]["path"], (dir_ / "work" / "d").string());
}

}  // namespace
}  // namespace myo
