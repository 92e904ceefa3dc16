// `myoshell check`: what it prints is a scene that means what the input meant. Its output, saved
// as a file, passes `check` again and prints the same (a fixed point); it says "all" for every
// muscle, names a pin file only when there is one, and puts no `interp` on a track's last key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

class CheckCommand : public testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("myo_check_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    // Scenes name files relative to their folder; fig27 reaches ../../../shared/data. Saved three
    // folders below root_, with root_/shared/data the shared data, the same paths resolve.
    dir_ = root_ / "a" / "b" / "c";
    fs::create_directories(dir_);
    fs::create_directories(root_ / "shared");
    fs::create_directory_symlink(test::sharedDataDir(), root_ / "shared" / "data");
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }

  fs::path root_, dir_;
};

// Every track of a printed scene: its keys (a JSON list).
std::vector<nlohmann::json> tracksOf(const nlohmann::json& scene) {
  std::vector<nlohmann::json> tracks;
  const auto& timeline = scene.at("timeline");
  for (const auto& group : {"activations", "drags"})
    if (timeline.contains(group))
      for (const auto& track : timeline.at(group)) tracks.push_back(track);
  if (timeline.contains("gravity")) tracks.push_back(timeline.at("gravity"));
  return tracks;
}

TEST_F(CheckCommand, ItsOutputPassesCheckAndPrintsTheSameForEveryShippedScene) {
  std::vector<fs::path> scenes = {test::sourceDir() / "scenes" / "demo.json"};
  for (const char* folder : {"thesis", "bench"})
    for (const auto& entry : fs::directory_iterator(test::sourceDir() / "scenes" / folder))
      if (entry.path().extension() == ".json") scenes.push_back(entry.path());
  ASSERT_GE(scenes.size(), 14u);
  int checked = 0;
  for (const fs::path& scene : scenes) {
    if (scene.stem() == "fig27_ict_head" && !test::haveSharedData()) continue;
    const test::CliResult first = test::runCli("check '" + scene.string() + "'");
    ASSERT_EQ(first.exitCode, 0) << scene << ": " << first.merged;
    const std::string saved = write(scene.filename().string(), first.out);
    const test::CliResult second = test::runCli("check '" + saved + "'");
    ASSERT_EQ(second.exitCode, 0) << scene << " as printed by check: " << second.merged;
    EXPECT_EQ(second.out, first.out) << scene;

    const auto printed = nlohmann::json::parse(first.out);
    int keyed = 0;
    for (const auto& track : tracksOf(printed)) {
      ASSERT_FALSE(track.empty()) << scene;
      EXPECT_FALSE(track.back().contains("interp")) << scene << ": interp on a last key: " << track.back();
      for (size_t k = 0; k + 1 < track.size(); ++k) keyed += track[k].contains("interp");
    }
    EXPECT_GT(keyed, 0) << scene << ": every other key says how it goes on";
    ++checked;
  }
  EXPECT_GE(checked, 13);
}

TEST_F(CheckCommand, TheDemoEasesItsRisesAsItsFileSays) {
  // The demo's smooth interp sits on the key that starts each rise (0 → 1), not on its target.
  const test::CliResult r = test::runCli("check '" + (test::sourceDir() / "scenes" / "demo.json").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const auto keys = nlohmann::json::parse(r.out)["timeline"]["activations"]["zygomaticus_major_left"];
  ASSERT_EQ(keys.size(), 4u);
  EXPECT_EQ(keys[0]["value"], 0);
  EXPECT_EQ(keys[0]["interp"], "smooth");
  EXPECT_EQ(keys[1]["interp"], "linear");
}

TEST_F(CheckCommand, PrintsAllForEveryMuscleAndNoEmptyPinFile) {
  const std::string scene = write("plain.json", R"({"gravity": {"enabled": false}, "duration": 0.1})");
  const test::CliResult r = test::runCli("check '" + scene + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["muscles"]["use"], "all");
  EXPECT_EQ(j["head"], nlohmann::json({{"builtin", "default"}}));  // no "gravity_pins": ""
  // "all" reads back as every muscle, and a selection prints as itself.
  const std::string all = write("all.json", r.out);
  EXPECT_EQ(test::runCli("check '" + all + "'").out, r.out);
  const std::string some = write("some.json", R"({"muscles": {"use": ["zygomaticus_major_left"]}})");
  EXPECT_EQ(nlohmann::json::parse(test::runCli("check '" + some + "'").out)["muscles"]["use"],
            nlohmann::json::array({"zygomaticus_major_left"}));
  const test::CliResult other = test::runCli("check '" + write("bad.json", R"({"muscles": {"use": "some"}})") + "'");
  EXPECT_EQ(other.exitCode, 2);
  EXPECT_NE(other.merged.find("bad.json:1:21: key 'muscles.use': must be \"all\" or a list of muscle names (got \"some\")"),
            std::string::npos)
      << other.merged;
}

TEST_F(CheckCommand, NamesTheHeadsPinFileOnlyWhenItHasOne) {
  MYO_REQUIRE_SHARED_DATA();
  const std::string ict = (test::sharedDataDir() / "ict").string();
  const std::string withPins = write("pins.json", R"({"model": "thesis", "head": {"obj": ")" + ict + R"(/head_skin.obj", "landmarks": ")" + ict +
                                                      R"(/landmarks_multipie68.json", "gravity_pins": ")" + ict +
                                                      R"(/rigid_vertices.json"}})");
  const test::CliResult a = test::runCli("check '" + withPins + "'");
  ASSERT_EQ(a.exitCode, 0) << a.merged;
  EXPECT_EQ(nlohmann::json::parse(a.out)["head"]["gravity_pins"], ict + "/rigid_vertices.json");
  const std::string noPins = write("nopins.json", R"({"head": {"obj": ")" + ict + R"(/head_skin.obj", "landmarks": ")" +
                                                      ict + R"(/landmarks_multipie68.json"}})");
  const test::CliResult b = test::runCli("check '" + noPins + "'");
  ASSERT_EQ(b.exitCode, 0) << b.merged;
  EXPECT_FALSE(nlohmann::json::parse(b.out)["head"].contains("gravity_pins")) << b.out;
}

TEST_F(CheckCommand, InterpOnALastKeyFailsInCheckAndRun) {
  const std::string scene = write("last.json",
                                  "{\"timeline\": {\"activations\": {\"zygomaticus_major_left\": [\n"
                                  "  {\"t\": 0, \"value\": 0},\n"
                                  "  {\"t\": 0.4, \"value\": 1, \"interp\": \"smooth\"}]}}}\n");
  const std::string where = scene + ":3:36: key 'timeline.activations.zygomaticus_major_left[1].interp': a track's last key";
  const test::CliResult c = test::runCli("check '" + scene + "'");
  EXPECT_EQ(c.exitCode, 2);
  EXPECT_NE(c.merged.find(where), std::string::npos) << c.merged;
  const fs::path out = root_ / "out";
  const test::CliResult r = test::runCli("run '" + scene + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.merged.find(where), std::string::npos) << r.merged;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace myo
