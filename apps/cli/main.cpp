// `myoshell`: the command line. The only place (with the viewer) that prints to the user and exits.
#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"

namespace myo::cli {

namespace {
std::vector<std::pair<std::string, CommandSetup>>& registry() {
  static std::vector<std::pair<std::string, CommandSetup>> commands;
  return commands;
}
}  // namespace

CommandRegistrar::CommandRegistrar(const std::string& name, CommandSetup setup) {
  registry().emplace_back(name, std::move(setup));
}

}  // namespace myo::cli

namespace {

// A command-line fault (an unknown option, a missing argument, a value out of range) on the one
// `myoshell: error:` line every other error uses, pointing at the command's --help.
int parseFailure(const CLI::ParseError& e, const std::string& command) {
  std::string what = e.what();
  if (!what.empty() && what.back() == '\n') what.pop_back();
  fmt::print(stderr, "myoshell: error: {} (see myoshell {}--help)\n", what, command.empty() ? "" : command + " ");
  return myo::cli::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace myo::cli;
  // Named here, not after argv[0]: --help prints the same usage lines however it is started
  // (docs/cli.md holds them, tests/cli/cli_doc_test.cpp compares).
  CLI::App app{"myoshell: muscle-driven facial animation with discrete shells and modal warping", "myoshell"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "myoshell 0.1.0");

  // Register commands in name order so `--help` lists them alphabetically.
  auto commands = registry();
  std::sort(commands.begin(), commands.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::map<CLI::App*, std::function<int()>> runners;
  for (auto& [name, setup] : commands) {
    auto before = app.get_subcommands([](CLI::App*) { return true; });
    auto run = setup(app);
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
      if (std::find(before.begin(), before.end(), sub) == before.end()) runners[sub] = run;
  }

  // A first word that is neither an option nor a command: say so by name (CLI11 would only say
  // that a subcommand is required).
  std::string command;
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const auto& [name, setup] : commands) known |= name == argv[1];
    if (!known) {
      fmt::print(stderr, "myoshell: error: unknown command '{}' (see myoshell --help)\n", argv[1]);
      return kExitBadInput;
    }
    command = argv[1];
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version: printed on stdout
    return parseFailure(e, command);
  } catch (const myo::InputError& e) {  // a setting applied while parsing (addThreadsOption)
    fmt::print(stderr, "myoshell: error: {}\n", e.what());
    return kExitBadInput;
  }

  try {
    for (CLI::App* sub : app.get_subcommands())
      if (auto it = runners.find(sub); it != runners.end()) return it->second();
    fmt::print(stderr, "myoshell: error: no command given (see myoshell --help)\n");
    return kExitBadInput;
  } catch (const myo::InputError& e) {
    fmt::print(stderr, "myoshell: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const myo::IoError& e) {  // run-time: a full disk, a file-size limit (path and OS reason)
    fmt::print(stderr, "myoshell: error: {}\n", e.what());
    return kExitFailure;
  } catch (const std::exception& e) {
    fmt::print(stderr, "myoshell: error: {}\n", e.what());
    return kExitFailure;
  }
}
