// `myoshell head`: counts, landmarks, frame and pins as JSON, from any folder; pictures; errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_runner.h"

namespace myo {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// The CLI run in `dir`: stdout, and stderr too when mergeStderr.
test::CliResult runIn(const fs::path& dir, const std::string& args, bool mergeStderr = true) {
  test::CliResult r = test::runCli(args, dir);
  if (mergeStderr) r.out = r.merged;
  return r;
}

fs::path headScratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_head_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

TEST(HeadCommand, DefaultHeadFromAnyFolder) {
  const fs::path dir = headScratch("default");
  const test::CliResult r = runIn(dir, "head --json --render face.png --size 128", false);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["name"], "default");
  // The anatomical model's built-in head: mouth and eyes open.
  EXPECT_EQ(j["model"], "anatomical");
  EXPECT_EQ(j["eyes"], "open");
  EXPECT_EQ(j["vertices"], 6990);
  EXPECT_EQ(j["triangles"], 13632);
  EXPECT_EQ(j["boundary_loops"], nlohmann::json::array({144, 80, 64, 64}));
  EXPECT_EQ(j["landmarks"]["multipie68"], 68);
  EXPECT_EQ(j["landmarks"]["required"]["nose_tip"], 4);
  EXPECT_EQ(j["landmarks"]["required"]["mouth_corner_right"], 61);
  EXPECT_EQ(j["gravity_pins"]["count"], 146);
  EXPECT_NEAR(j["frame"]["scale"].get<double>(), 8.89, 0.01);
  // A PNG was written in the working folder.
  std::ifstream png(dir / "face.png", std::ios::binary);
  std::string sig(8, '\0');
  png.read(sig.data(), 8);
  EXPECT_EQ(sig, std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(HeadCommand, ClosedEyesGiveTheThesisModelsHead) {
  const fs::path dir = headScratch("closed_eyes");
  const test::CliResult r = runIn(dir, "head --closed-eyes --json", false);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "thesis");
  EXPECT_EQ(j["eyes"], "closed");
  EXPECT_EQ(j["vertices"], 7152);
  EXPECT_EQ(j["triangles"], 14080);
  EXPECT_EQ(j["boundary_loops"], nlohmann::json::array({144, 80}));
  EXPECT_NEAR(j["frame"]["scale"].get<double>(), 8.88, 0.01);
  const test::CliResult text = runIn(dir, "head --closed-eyes", false);
  EXPECT_NE(text.out.find("eyes: closed (no lids); the thesis model's built-in head"), std::string::npos) << text.out;
}

TEST(HeadCommand, PicturesHaveTheAskedSizeAndBadPathsAreBadInput) {
  const fs::path dir = headScratch("pictures");
  for (const char* view : {"front", "three-quarter", "profile", "back"}) {
    const test::CliResult r =
        runIn(dir, std::string("head --levels 0 --wire --pins-marked --size 96 --view ") + view +
                       " --render " + view + ".png");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    std::ifstream png(dir / (std::string(view) + ".png"), std::ios::binary);
    std::string head(24, '\0');
    png.read(head.data(), 24);
    EXPECT_EQ(head.substr(12, 4), "IHDR") << view;
    EXPECT_EQ(static_cast<unsigned char>(head[19]), 96) << view;  // width, big-endian
    EXPECT_EQ(static_cast<unsigned char>(head[23]), 96) << view;  // height
  }
  fs::create_directories(dir / "folder.png");
  test::CliResult r = runIn(dir, "head --levels 0 --render folder.png");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("folder.png: --render: is a folder; give the PNG file to write"));  // before the head is drawn
  r = runIn(dir, "head --levels 0 --view top --render x.png");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("unknown view 'top' (use front, three-quarter, profile or back)"));
}

TEST(HeadCommand, WritesTheDefaultLandmarkFileAndReadsItBack) {
  const fs::path dir = headScratch("roundtrip");
  ASSERT_EQ(runIn(dir, "head --levels 0 --write-obj h.obj --write-landmarks lm.json").exitCode, 0);
  const test::CliResult r = runIn(dir, "head h.obj --landmarks lm.json --json", false);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 468);
  EXPECT_EQ(j["triangles"], 852);  // 898 less the 18 between the lips and the 28 over the eyes
  EXPECT_EQ(j["boundary_loops"], nlohmann::json::array({36, 20, 16, 16}));
  EXPECT_EQ(j["eyes"], "open");  // the written head has the lids' openings too
  EXPECT_EQ(j["landmarks"]["required"]["chin_menton"], 152);
}

TEST(HeadCommand, IctFolder) {
  MYO_REQUIRE_SHARED_DATA();
  const test::CliResult r =
      runIn(headScratch("ict"), "head '" + (test::sharedDataDir() / "ict").string() + "' --json", false);
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 11248);
  EXPECT_EQ(j["gravity_pins"]["count"], 910);
  EXPECT_EQ(j["gravity_pins"]["source"], "rigid_vertices.json");
  EXPECT_EQ(j["landmarks"]["required"]["nose_tip"], 4857);
}

TEST(HeadCommand, LandmarkErrorsAreBadInput) {
  const fs::path dir = headScratch("errors");
  ASSERT_EQ(runIn(dir, "head --levels 0 --write-obj h.obj").exitCode, 0);
  std::ofstream(dir / "lm.json") << "{\"nose_tip\": 4}";
  test::CliResult r = runIn(dir, "head h.obj --landmarks lm.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("lm.json: missing landmark 'right_eye_outer'"));
  r = runIn(dir, "head h.obj --landmarks nope.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_THAT(r.out, HasSubstr("nope.json: cannot open landmark file"));
}

}  // namespace
}  // namespace myo
