// The options every command shares (apps/cli/common_options.h): the same help line wherever they
// appear, --json on every command, and command-line faults on one `myoshell: error:` line with exit 2.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

const std::vector<std::string> kCommands = {"bench", "check", "demo",    "drive", "energy", "figures",
                                            "fit",   "fit-rig", "head", "info",  "modes",  "muscles",
                                            "landmarks", "paths", "pose",  "render",  "rig",   "run",    "validate"};

// The help line of `option` in `help` (from the option to the end of its description), "" when absent.
std::string helpLine(const std::string& help, const std::string& option) {
  std::istringstream in(help);
  std::string line, previous;
  while (std::getline(in, line)) {
    const size_t at = line.find_first_not_of(' ');
    if (at != std::string::npos && line.compare(at, option.size() + 1, option + " ") == 0) {
      std::string next;
      // A long option name pushes its description onto the next line.
      if (line.find("  ", at + option.size() + 1) == std::string::npos && std::getline(in, next)) line += next;
      return line;
    }
  }
  return {};
}

std::string help(const std::string& command) {
  const test::CliResult r = test::runCli(command + " --help");
  EXPECT_EQ(r.exitCode, 0) << command << ": " << r.merged;
  return r.out;
}

TEST(CliOptions, EveryCommandTakesJson) {
  for (const std::string& c : kCommands)
    EXPECT_THAT(helpLine(help(c), "--json"), HasSubstr("Print the result as JSON")) << c;
}

TEST(CliOptions, SharedOptionsReadTheSameInEveryCommand) {
  std::map<std::string, std::string> first;  // option → its help line where first met
  int withCache = 0, withThreads = 0, withHead = 0;
  for (const std::string& c : kCommands) {
    const std::string h = help(c);
    for (const std::string option : {"--cache", "--json", "--data", "--scenes", "--threads"}) {
      const std::string line = helpLine(h, option);
      if (line.empty() || (option == "--threads" && c == "bench")) continue;  // bench notes the value only
      withCache += option == "--cache";
      withThreads += option == "--threads";
      if (!first.count(option)) first[option] = line;
      EXPECT_EQ(line, first[option]) << c << " " << option;
    }
    // --library: the same words and one default, the whole face, in every command.
    if (const std::string line = helpLine(h, "--library"); !line.empty())
      EXPECT_THAT(line, HasSubstr("Muscles: face (the whole face's 40, docs/muscles.md), builtin (the built-in ten: the "
                                  "thesis's eight, placed anatomically, and the lips' two rings) or a library file; "
                                  "default: face"))
          << c;
    if (const std::string line = helpLine(h, "--head"); !line.empty()) {
      ++withHead;
      EXPECT_THAT(line, HasSubstr("The head: 'default' (the built-in head), an OBJ file or a folder "
                                  "like ../shared/data/ict"))
          << c;
      EXPECT_THAT(helpLine(h, "--units"), HasSubstr("Length unit of an OBJ head, m, mm or cm")) << c;
      EXPECT_THAT(helpLine(h, "--landmarks"), HasSubstr("Landmark file of an OBJ head")) << c;
    }
  }
  EXPECT_EQ(withCache, 13);   // bench demo drive figures fit fit-rig head landmarks paths pose render rig run
  EXPECT_EQ(withThreads, 7);  // drive fit fit-rig pose render rig run
  EXPECT_EQ(withHead, 6);     // drive fit fit-rig muscles pose rig
}

TEST(CliOptions, ANegativeThreadCountIsOneClearLine) {
  for (const std::string c : {"run scene.json --out o", "bench", "pose"}) {
    const test::CliResult r = test::runCli(c + " --threads -1");
    EXPECT_EQ(r.exitCode, 2) << c;
    const std::string command = c.substr(0, c.find(' '));
    EXPECT_EQ(r.err, "myoshell: error: --threads: must be ≥ 0 (0 = every core), got -1 (see myoshell " + command +
                         " --help)\n")
        << c;
    EXPECT_EQ(r.out, "");
  }
  // The viewer checks its --threads the same way, on its own error line.
  const test::CliResult viewer = test::runProgram(MYO_VIEWER_PATH, "--threads -1");
  EXPECT_EQ(viewer.exitCode, 2);
  EXPECT_EQ(viewer.err, "myoshell-view: error: --threads: must be ≥ 0 (0 = every core), got -1 (see myoshell-view --help)\n");
  const test::CliResult word = test::runCli("rig --map m.json --out r.glb --threads many");
  EXPECT_EQ(word.exitCode, 2);
  EXPECT_THAT(word.err, HasSubstr("--threads: must be a whole number ≥ 0 (0 = every core), got 'many'"));
}

TEST(CliOptions, ArgumentFaultsAreOneErrorLineWithExitTwo) {
  for (const std::string args : {"run", "info a.obj --bogus", "render s.json --out o --size-x 3",
                                 "drive take.csv --out o --face -2", "head --size 10", "figures --size 5000"}) {
    const test::CliResult r = test::runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_THAT(r.err, StartsWith("myoshell: error: ")) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_THAT(r.err, Not(HasSubstr("Run with --help"))) << args;
  }
  EXPECT_THAT(test::runCli("head --size 10").err, HasSubstr("--size: must be in [64, 4096], got 10"));
  EXPECT_THAT(test::runCli("drive take.csv --out o --face -2").err, HasSubstr("--face: must be ≥ 0, got -2"));
}

TEST(CliOptions, HelpAndVersionExitZeroOnStdout) {
  const test::CliResult h = test::runCli("run --help");
  EXPECT_EQ(h.exitCode, 0);
  EXPECT_THAT(h.out, HasSubstr("Usage: myoshell run [OPTIONS] scene"));  // not argv[0]'s path
  EXPECT_EQ(h.err, "");
  const test::CliResult v = test::runCli("--version");
  EXPECT_EQ(v.exitCode, 0);
  EXPECT_EQ(v.out, "myoshell 0.1.0\n");
}

TEST(CliOptions, CheckPrintsTheValidatedSceneAsJson) {
  const fs::path scene = test::sourceDir() / "tests" / "bad_inputs" / "scene_small.json";
  const test::CliResult text = test::runCli("check '" + scene.string() + "'");
  ASSERT_EQ(text.exitCode, 0) << text.merged;
  const test::CliResult json = test::runCli("check --json '" + scene.string() + "'");
  ASSERT_EQ(json.exitCode, 0) << json.merged;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["ok"], true);
  EXPECT_EQ(j["file"], scene.string());
  EXPECT_EQ(j["scene"], nlohmann::json::parse(text.out));  // the scene with every default, as the text prints it
  EXPECT_EQ(j["scene"]["name"], "scene_small");
  // A bad scene: exit 2 and the message on stderr, nothing on stdout.
  const test::CliResult bad =
      test::runCli("check --json '" + (test::sourceDir() / "tests" / "bad_inputs" / "scene_roi_alpha.json").string() + "'");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_EQ(bad.out, "");
  EXPECT_THAT(bad.err, HasSubstr("key 'roi_alpha': must be > 1 (got 1)"));
}

TEST(CliOptions, FiguresListTheFilesWrittenAsJson) {
  const fs::path dir = fs::temp_directory_path() / ("myo_figures_json_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const test::CliResult r =
      test::runCli("figures --json --only fig26,fig27 --size 64 --software --out '" + (dir / "fig").string() +
                   "' --data '" + (dir / "nodata").string() + "' --cache '" + (dir / "cache").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // nothing but the JSON on stdout
  ASSERT_EQ(j["written"].size(), 1u);
  EXPECT_EQ(j["written"][0], (dir / "fig" / "fig26_transition.png").string());
  EXPECT_TRUE(fs::exists(j["written"][0].get<std::string>()));
  ASSERT_EQ(j["skipped"].size(), 1u);
  EXPECT_EQ(j["skipped"][0]["figure"], "fig27");
  EXPECT_THAT(j["skipped"][0]["reason"].get<std::string>(), HasSubstr((dir / "nodata" / "ict" / "head_skin.obj").string()));
  EXPECT_TRUE(j.contains("peak_rss_mb"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace myo
