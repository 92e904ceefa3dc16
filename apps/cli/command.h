// How a `myoshell` subcommand plugs into the CLI: each cmd_*.cpp registers itself with a static
// CommandRegistrar, so adding a command touches no other file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace myo::cli {

// Exit codes of the CLI (docs/cli.md). An interrupted run exits 128 + the signal (130, 143).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,     // a numerical or run-time failure
  kExitBadInput = 2,    // bad arguments or bad input files
  kExitMeshFaults = 3,  // `info` found faults in the mesh
};

// A command adds its subcommand to the app and returns the function that runs it (returning an
// exit code). The function may throw myo::InputError (→ exit 2) or other exceptions (→ exit 1).
using CommandSetup = std::function<std::function<int()>(CLI::App& app)>;

struct CommandRegistrar {
  CommandRegistrar(const std::string& name, CommandSetup setup);
};

}  // namespace myo::cli
