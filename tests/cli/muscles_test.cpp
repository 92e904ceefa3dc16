// `myoshell muscles`: a library listed with each muscle's side, action units and kind, and placed on
// a head when one is given; a bad library or a head without a landmark fails naming it.
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

TEST(CliMuscles, ListsTheWholeFaceByDefaultWithItsRingsAndTheBuiltInTen) {
  test::CliResult r = test::runCli("muscles --library builtin --json");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["muscles"].size(), 10u);  // the thesis's eight, then the mouth's two rings
  EXPECT_EQ(j["muscles"][8]["name"], "orbicularis_oris_upper");
  EXPECT_EQ(j["muscles"][9]["kind"], "ring");
  EXPECT_EQ(j["muscles"][0]["name"], "zygomaticus_major_right");
  EXPECT_EQ(j["muscles"][0]["side"], "right");
  EXPECT_EQ(j["muscles"][0]["aus"], nlohmann::json::array({12}));
  EXPECT_EQ(j["muscles"][0]["kind"], "linear");
  EXPECT_FALSE(j["muscles"][0].contains("length_cm"));

  r = test::runCli("muscles --head default --json");  // the default: the whole face
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["muscles"].size(), 40u);
  int rings = 0;
  for (const auto& m : j["muscles"]) {
    rings += m["kind"] == "ring";
    EXPECT_GT(m["length_cm"].get<double>(), 0.5) << m["name"];
    EXPECT_FALSE(m["aus"].empty()) << m["name"];
    if (m["name"] == "platysma_left") EXPECT_EQ(m["aus"], nlohmann::json::array({20, 21}));
    if (m["name"] == "procerus") EXPECT_EQ(m["side"], "center");
  }
  EXPECT_EQ(rings, 7);  // the oculi orbital and palpebral, the oris upper, lower and the lower marginal part
}

TEST(CliMuscles, ABadLibraryFailsNamingTheFileAndTheFault) {
  const fs::path dir = fs::path(testing::TempDir()) / ("myo_muscles_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "lib.json") << R"({"muscles": [{"name": "o", "ring": {"path": [{"landmark": "nose_tip"}]}}]})";
  const test::CliResult r = test::runCli("muscles --library '" + (dir / "lib.json").string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.err, HasSubstr("lib.json:1:45: key 'muscles[0].ring.path': must be a list of at least 3 anchors"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace myo
