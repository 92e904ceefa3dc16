// `myoshell landmarks`: the landmark file it writes is usable as --landmarks; --json, --compare and
// the picture; a mesh that is not a head exits 2 (tests/bad_inputs/cases.json has more).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_runner.h"
#include "support/test_data.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path landmarksScratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_landmarks_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

TEST(LandmarksCommand, IctFileIsUsableAsLandmarksAndComparesWithTheGivenOne) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path dir = landmarksScratch("ict");
  const fs::path ict = test::sharedDataDir() / "ict";
  const std::string obj = (ict / "head_skin.obj").string();
  const test::CliResult r = test::runCli("landmarks '" + obj + "' --out lm.json --picture lm.png --json --compare '" +
                                             (ict / "landmarks_multipie68.json").string() + "'",
                                         dir);
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["units"], "cm");
  EXPECT_EQ(j["eyes"], "open");
  EXPECT_EQ(j["mouth"], "open");
  EXPECT_EQ(j["multipie68"].size(), 68u);
  EXPECT_TRUE(j["landmarks"].contains("nose_tip"));
  EXPECT_TRUE(j["frame"].contains("origin"));
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
  // The mean (≤ 3 mm) over the 68 and over the 68 with the named points, measured 2.27 and
  // 2.06 mm; off the jaw line 1.59 mm; and its maximum (≤ 8 mm), measured 6.95 mm (search version 4;
  // docs/heads.md, "Automatic landmarks").
  EXPECT_LT(j["compare"]["multipie68"]["mean_mm"].get<double>(), 3.0);
  EXPECT_LT(j["compare"]["all"]["mean_mm"].get<double>(), 3.0);
  EXPECT_LT(j["compare"]["off_jaw_17_67"]["mean_mm"].get<double>(), 2.1);
  EXPECT_LT(j["compare"]["multipie68"]["max_mm"].get<double>(), 8.0);
  EXPECT_TRUE(fs::exists(dir / "lm.png"));
  // The file carries a confidence per point and loads as --landmarks, passing the head's checks.
  const auto file = nlohmann::json::parse(std::ifstream(dir / "lm.json"));
  EXPECT_EQ(file["confidence"]["multipie68"].size(), 68u);
  const test::CliResult h = test::runCli("head '" + obj + "' --landmarks lm.json --json", dir);
  ASSERT_EQ(h.exitCode, 0) << h.merged;
  EXPECT_EQ(nlohmann::json::parse(h.out)["landmarks"]["multipie68"], 68);
}

TEST(LandmarksCommand, NotAHeadExitsTwoAndWritesNothing) {
  const fs::path dir = landmarksScratch("plane");
  const std::string obj = (test::sourceDir() / "tests" / "bad_inputs" / "not_a_head_plane.obj").string();
  const test::CliResult r = test::runCli("landmarks '" + obj + "' --out lm.json", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.merged, HasSubstr("not_a_head_plane.obj: not a head: the mesh is flat"));
  EXPECT_FALSE(fs::exists(dir / "lm.json"));
}

}  // namespace
}  // namespace myo
