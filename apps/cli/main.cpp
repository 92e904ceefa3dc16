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
#include "myoshell/core/parallel.h"

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

int main(int argc, char** argv) {
  using namespace myo::cli;
  CLI::App app{"myoshell: muscle-driven facial animation with discrete shells and modal warping"};
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
  // --threads on the commands that build a face (its eigen-solves and static responses) or fit many
  // targets: every hardware thread by default. The output is the same bytes for every N
  // (core/parallel.h); `bench` measures the single-threaded step and keeps its own option.
  int threads = 0;
  const std::vector<std::string> threaded{"drive", "fit", "fit-rig", "pose", "render", "rig", "run"};
  auto isThreaded = [&](const CLI::App* sub) { return std::find(threaded.begin(), threaded.end(), sub->get_name()) != threaded.end(); };
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    if (isThreaded(sub))
      sub->add_option("--threads", threads,
                      "Threads for the precompute and independent work (0 = every hardware thread, the default; "
                      "the output does not depend on it)")
          ->check(CLI::NonNegativeNumber);

  // A first word that is neither an option nor a command: say so by name (CLI11 would only say
  // that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const auto& [name, setup] : commands) known |= name == argv[1];
    if (!known) {
      fmt::print(stderr, "myoshell: error: unknown command '{}' (see myoshell --help)\n", argv[1]);
      return kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    for (CLI::App* sub : app.get_subcommands())
      if (isThreaded(sub)) myo::setParallelThreads(threads);  // the others keep one thread
    for (CLI::App* sub : app.get_subcommands())
      if (auto it = runners.find(sub); it != runners.end()) return it->second();
    fmt::print(stderr, "myoshell: no command given (see --help)\n");
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
