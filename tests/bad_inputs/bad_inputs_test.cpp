// The bad-input catalogue (tests/bad_inputs/cases.json): every case exits with its code, names the
// fault in its message, and leaves no output file behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

bool isEmptyTree(const fs::path& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (!entry.is_directory()) return false;
  return true;
}

TEST(BadInputs, EveryCaseFailsCleanlyWithItsMessage) {
  const fs::path dir = test::sourceDir() / "tests" / "bad_inputs";
  std::ifstream in(dir / "cases.json");
  const auto catalogue = nlohmann::json::parse(in);
  const fs::path scratch = fs::temp_directory_path() / ("myo_bad_inputs_" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  fs::create_directories(scratch / "cache");
  const fs::path file = scratch / "a_regular_file";
  std::ofstream(file) << "not a folder";
  int ran = 0;
  for (const auto& c : catalogue["cases"]) {
    const std::string name = c["name"];
    if (name.size() > 4 && name.substr(name.size() - 4) == "_ict" && !test::haveSharedData()) continue;
    const fs::path out = scratch / ("out_" + name);
    fs::create_directories(out);
    std::string args = c["args"];
    args = replaceAll(args, "{dir}", dir.string());
    args = replaceAll(args, "{out}", out.string());
    args = replaceAll(args, "{file}", file.string());
    args = replaceAll(args, "{cache}", (scratch / "cache").string());
    args = replaceAll(args, "{shared}", test::sharedDataDir().string());
    // "program": "myoshell-view" runs the viewer (without a display: its bad input fails first).
    const std::string program = c.value("program", "myoshell");
    test::CliResult r;
    if (program == "myoshell-view") {
#ifdef MYO_VIEWER_PATH
      if (!fs::exists(MYO_VIEWER_PATH)) continue;  // not built (the sanitized CI build leaves it out)
      r = test::runProgram(MYO_VIEWER_PATH, args, {}, "env -u DISPLAY -u WAYLAND_DISPLAY");
#else
      continue;
#endif
    } else {
      ASSERT_EQ(program, "myoshell") << name;
      r = test::runCli(args);
    }
    EXPECT_EQ(r.exitCode, c["exit"].get<int>()) << name << ": " << r.merged;
    EXPECT_NE(r.merged.find(c["expect"].get<std::string>()), std::string::npos)
        << name << ": expected \"" << c["expect"].get<std::string>() << "\" in: " << r.merged;
    EXPECT_TRUE(isEmptyTree(out)) << name << ": left a file in " << out;
    ++ran;
  }
  EXPECT_GE(ran, 30);
  fs::remove_all(scratch);
}

TEST(BadInputs, ReliabilityDocListsEveryCase) {
  // docs/RELIABILITY.md's catalogue table has one row per case: "| `name` | … | `expect` | exit |".
  const fs::path root = test::sourceDir();
  std::ifstream in(root / "tests" / "bad_inputs" / "cases.json");
  const auto catalogue = nlohmann::json::parse(in);
  std::ifstream docIn(root / "docs" / "RELIABILITY.md");
  ASSERT_TRUE(docIn.good());
  std::vector<std::string> rows;
  for (std::string line; std::getline(docIn, line);)
    if (line.rfind("| `", 0) == 0) rows.push_back(line);
  for (const auto& c : catalogue["cases"]) {
    const std::string name = c["name"];
    std::string expect = replaceAll(c["expect"].get<std::string>(), "|", "\\|");
    const std::string tail = " | " + std::to_string(c["exit"].get<int>()) + " |";
    const auto row = std::find_if(rows.begin(), rows.end(), [&](const std::string& r) {
      return r.rfind("| `" + name + "` |", 0) == 0;
    });
    ASSERT_NE(row, rows.end()) << name << " has no row in docs/RELIABILITY.md";
    EXPECT_NE(row->find("`" + expect + "`"), std::string::npos) << name << ": " << *row;
    EXPECT_TRUE(row->size() >= tail.size() && row->compare(row->size() - tail.size(), tail.size(), tail) == 0)
        << name << ": " << *row;
  }
}

TEST(BadInputs, AnOverlongLineIsRefusedWithItsLineNumber) {
  // A 20 MB line, made here rather than stored: readers cap lines at 16 MiB and say so.
  const fs::path scratch = fs::temp_directory_path() / ("myo_long_line_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  const fs::path obj = scratch / "long.obj";
  {
    std::ofstream f(obj);
    f << "v 0 0 0\nv 1 0 0\n# " << std::string(20u << 20, 'x') << "\nv 0 1 0\nf 1 2 3\n";
  }
  const test::CliResult r = test::runCli("info '" + obj.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.merged;
  EXPECT_NE(r.merged.find("long.obj:3: line 3 is longer than 16 MiB"), std::string::npos) << r.merged;
  fs::remove_all(scratch);
}

}  // namespace
}  // namespace myo
