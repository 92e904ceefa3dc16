// docs/cli.md holds every command's --help (written there by scripts/make_cli_doc): each block must
// be the program's output exactly, so the reference and the program cannot drift apart, and every
// command `myoshell --help` lists must have one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

const char* kRegenerate = "scripts/make_cli_doc build/bin/myoshell build/bin/myoshell-view";

std::string readDoc() {
  std::ifstream in(test::sourceDir() / "docs" / "cli.md", std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What a block holds: the help, its trailing blank lines dropped (as the script writes it).
std::string block(const std::string& command, std::string help) {
  while (!help.empty() && help.back() == '\n') help.pop_back();
  return "<!-- begin help: " + command + " -->\n```text\n" + help + "\n```\n<!-- end help: " + command + " -->\n";
}

// The command's block as docs/cli.md has it, "" when it has none.
std::string docBlock(const std::string& doc, const std::string& command) {
  const std::string begin = "<!-- begin help: " + command + " -->\n", end = "<!-- end help: " + command + " -->\n";
  const size_t a = doc.find(begin), b = doc.find(end);
  return a == std::string::npos || b == std::string::npos || b < a ? "" : doc.substr(a, b + end.size() - a);
}

// The commands `myoshell --help` lists under "Subcommands:".
std::vector<std::string> commands(const std::string& help) {
  std::vector<std::string> out;
  std::istringstream in(help.substr(help.find("Subcommands:\n") + 13));
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("  ", 0) == 0 && line.find_first_not_of(' ') != std::string::npos)
      out.push_back(line.substr(2, line.find(' ', 2) - 2));
  return out;
}

void expectDocumented(const std::string& doc, const std::string& command, const test::CliResult& help) {
  ASSERT_EQ(help.exitCode, 0) << command << " --help: " << help.merged;
  const std::string found = docBlock(doc, command);
  ASSERT_FALSE(found.empty()) << "docs/cli.md has no help block for `" << command
                              << "`: add its section with empty markers and run " << kRegenerate;
  EXPECT_EQ(found, block(command, help.out))
      << "docs/cli.md: the options of `" << command << "` are stale; regenerate them with " << kRegenerate;
}

TEST(CliDoc, EveryCommandsHelpIsInTheReferenceExactly) {
  const std::string doc = readDoc();
  ASSERT_FALSE(doc.empty()) << "docs/cli.md is missing";
  const test::CliResult top = test::runCli("--help");
  expectDocumented(doc, "myoshell", top);
  const std::vector<std::string> listed = commands(top.out);
  ASSERT_EQ(listed.size(), 21u) << top.out;  // info energy modes validate head landmarks pose fit fit-rig rig muscles drive live send run check demo paths bench figures render
  for (const std::string& c : listed) {
    expectDocumented(doc, c, test::runCli(c + " --help"));
    EXPECT_NE(doc.find("\n## myoshell " + c + "\n"), std::string::npos) << "docs/cli.md: no section `## myoshell " << c << "`";
  }
}

TEST(CliDoc, TheViewersHelpIsInTheReferenceExactly) {
  const std::string doc = readDoc();
  const test::CliResult help = test::runProgram(MYO_VIEWER_PATH, "--help");
  expectDocumented(doc, "myoshell-view", help);
  EXPECT_NE(doc.find("\n## myoshell-view\n"), std::string::npos);
}

}  // namespace
}  // namespace myo
