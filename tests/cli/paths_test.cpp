// Paths that work outside the repository (resources.h, docs/paths.md): shipped scenes found from
// the executable, the data folder from --data / $MYOSHELL_DATA, the basis cache from --cache /
// $MYOSHELL_CACHE / $XDG_CACHE_HOME / ~/.cache, and a cache folder that cannot be used.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// One cache for every run of this file: the small scene's bases are computed once.
fs::path sharedCache() { return fs::path(testing::TempDir()) / "myo_thesis_cache"; }

class Paths : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_paths_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }
  // `myoshell paths --json ARGS` under a controlled environment: ENV is `env` syntax
  // (-u NAME, NAME=VALUE).
  nlohmann::json paths(const std::string& env, const std::string& args = "") {
    const test::CliResult r =
        test::runCli("paths --json " + args, {}, "env -u MYOSHELL_CACHE -u XDG_CACHE_HOME -u MYOSHELL_DATA " + env);
    EXPECT_EQ(r.exitCode, 0) << r.merged;
    return nlohmann::json::parse(r.out);
  }
  fs::path dir_;
};

TEST_F(Paths, CacheOptionBeatsMyoshellCacheBeatsXdgBeatsHome) {
  const std::string home = "HOME=/h";
  auto j = paths(home);
  EXPECT_EQ(j["cache"]["path"], "/h/.cache/myoshell");
  EXPECT_EQ(j["cache"]["source"], "$HOME/.cache");
  j = paths(home + " XDG_CACHE_HOME=/x");
  EXPECT_EQ(j["cache"]["path"], "/x/myoshell");
  EXPECT_EQ(j["cache"]["source"], "$XDG_CACHE_HOME");
  j = paths(home + " XDG_CACHE_HOME=relative/x");  // the XDG spec: a relative path is ignored
  EXPECT_EQ(j["cache"]["path"], "/h/.cache/myoshell");
  j = paths(home + " XDG_CACHE_HOME=/x MYOSHELL_CACHE=/m");
  EXPECT_EQ(j["cache"]["path"], "/m");
  EXPECT_EQ(j["cache"]["source"], "$MYOSHELL_CACHE");
  j = paths(home + " XDG_CACHE_HOME=/x MYOSHELL_CACHE=/m", "--cache /c");
  EXPECT_EQ(j["cache"]["path"], "/c");
  EXPECT_EQ(j["cache"]["source"], "--cache");
}

TEST_F(Paths, ScenesComeFromTheSourceTreeAndDataFromTheOptionOrTheEnvironment) {
  auto j = paths("");
  EXPECT_EQ(fs::path(j["scenes"]["path"].get<std::string>()), test::sourceDir() / "scenes");
  EXPECT_EQ(j["scenes"]["exists"], true);
  EXPECT_EQ(j["data"]["source"], "source tree's ../shared/data");
  j = paths("MYOSHELL_DATA=/d");
  EXPECT_EQ(j["data"]["path"], "/d");
  j = paths("MYOSHELL_DATA=/d", "--data /e");
  EXPECT_EQ(j["data"]["path"], "/e");
  EXPECT_EQ(j["data"]["source"], "--data");
}

TEST_F(Paths, TheMyoshellCacheVariableIsWhereARunKeepsItsBases) {
  const test::CliResult r = test::runCli(
      "run '" + (test::sourceDir() / "tests" / "bad_inputs" / "scene_small.json").string() + "' --out '" +
          (dir_ / "out").string() + "'",
      dir_, "env -u XDG_CACHE_HOME HOME='" + (dir_ / "home").string() + "' MYOSHELL_CACHE='" + (dir_ / "c").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  bool any = false;
  for (const auto& e : fs::directory_iterator(dir_ / "c")) any |= e.path().extension() == ".myobasis";
  EXPECT_TRUE(any);
  EXPECT_FALSE(fs::exists(dir_ / "home")) << "nothing is written into HOME when MYOSHELL_CACHE is set";
  EXPECT_FALSE(fs::exists(dir_ / ".cache")) << "nothing is written into the current folder";
}

TEST_F(Paths, AnUnusableCacheFolderWarnsOnceNamingItAndTheRunCarriesOn) {
  std::ofstream(dir_ / "file") << "x";
  const fs::path bad = dir_ / "file" / "cache";
  const test::CliResult r =
      test::runCli("run '" + (test::sourceDir() / "tests" / "bad_inputs" / "scene_small.json").string() +
                   "' --out '" + (dir_ / "out").string() + "' --cache '" + bad.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  EXPECT_THAT(r.err, HasSubstr("warning: no basis cache (cannot create the basis cache directory " + bad.string() +
                               " (Not a directory)); the bases are computed and not kept"));
  EXPECT_EQ(r.err.find("warning"), r.err.rfind("warning")) << "one warning: " << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "stats.json"));
}

TEST_F(Paths, BenchRunsFromAnyFolderAndSaysWhereTheIctHeadWasLookedFor) {
  const test::CliResult r =
      test::runCli("bench --json --seconds 0.02 --runs 1 --heads default,ict --no-reference --rows t2_zygomaticus "
                   "--data '" + (dir_ / "nodata").string() + "' --cache '" + sharedCache().string() + "'",
                   "/tmp");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 1u);
  EXPECT_EQ(j["rows"][0]["head"], "default");
  ASSERT_EQ(j["notes"].size(), 1u);
  EXPECT_THAT(j["notes"][0].get<std::string>(), HasSubstr((dir_ / "nodata" / "ict" / "head_skin.obj").string()));
}

TEST_F(Paths, FiguresRunFromAnyFolder) {
  const test::CliResult r = test::runCli("figures --only fig26,fig27 --size 64 --software --out '" +
                                             (dir_ / "fig").string() + "' --data '" + (dir_ / "nodata").string() +
                                             "' --cache '" + sharedCache().string() + "'",
                                         "/tmp");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  EXPECT_TRUE(fs::exists(dir_ / "fig" / "fig26_transition.png"));
  EXPECT_THAT(r.out, HasSubstr("fig27 skipped: the ICT head (" + (dir_ / "nodata" / "ict" / "head_skin.obj").string()));
}

TEST_F(Paths, TheDemoRunsInAReadOnlyFolderWithAWritableOut) {
  // Permission bits do not stop root: then /proc, where no one can create a folder.
  fs::path ro = dir_ / "readonly";
  fs::create_directories(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  if (::geteuid() == 0) ro = "/proc";
  const test::CliResult r = test::runCli(
      "demo --json --out '" + (dir_ / "demo").string() + "'", ro,
      "env -u XDG_CACHE_HOME MYOSHELL_CACHE='" + sharedCache().string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  EXPECT_TRUE(fs::exists(dir_ / "demo" / "demo.glb"));
  EXPECT_TRUE(fs::exists(dir_ / "demo" / "demo_sheet.png"));
  EXPECT_THAT(r.err, Not(HasSubstr("warning: no basis cache")));
}

}  // namespace
}  // namespace myo
