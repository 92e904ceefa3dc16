// The options many commands share, declared here once so that every command names, describes and
// checks them the same way, and turned here into the settings they choose:
//   --head, --landmarks, --units   the head (io/head_files.h: 'default', an OBJ file or a folder)
//   --library                      the muscle library (default: the whole face, defaultMuscleLibrary())
//   --cache, --data, --scenes      folders, relative to the current directory (resources.h)
//   --threads                      the threads of the precompute and independent work (core/parallel.h)
//   --json                         machine-readable output (docs/cli.md lists each command's keys)
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "myoshell/io/fit_head.h"
#include "myoshell/io/head_files.h"

namespace myo::cli {

// --head, --landmarks and --units as given. The defaults are the built-in head and cm.
struct HeadOptions {
  std::string head = "default";
  std::string landmarks;
  std::string units = "cm";
  const CLI::Option* headOption = nullptr;
  const CLI::Option* landmarksOption = nullptr;
  const CLI::Option* unitsOption = nullptr;

  bool headGiven() const { return headOption && headOption->count() > 0; }
  bool unitsGiven() const { return unitsOption && unitsOption->count() > 0; }
  bool anyGiven() const { return headGiven() || unitsGiven() || (landmarksOption && landmarksOption->count() > 0); }
};

// What a command adds to the shared help of the head options, where it reads them differently
// (a rig's base mesh as the head when no --head is given; an OBJ target in the head's unit).
struct HeadHelp {
  std::string headDefault = "default";  // what the head is without --head
  std::string head;       // appended to --head's help
  std::string landmarks;  // appended to --landmarks' help
  std::string units;      // appended to --units' help
};

// --head, --landmarks and --units.
void addHeadOptions(CLI::App& sub, HeadOptions& head, const HeadHelp& notes = {});
// --landmarks and --units alone (`head`, whose head is its positional argument).
void addHeadFileOptions(CLI::App& sub, HeadOptions& head);
// The files they name (resolveHeadArgument: its InputErrors name the options); an OBJ without
// --landmarks is first given its automatic landmark file by resolveHeadLandmarks (head_landmarks.h).
HeadFiles headFiles(const HeadOptions& head);
// The head and muscles of a fitting command (io/fit_head.h).
FitHeadOptions fitHeadOptions(const HeadOptions& head, const std::string& library);

// --library; its default is `library`'s value when it is added.
void addLibraryOption(CLI::App& sub, std::string& library);

// --cache DIR (resources.h, openBasisCache).
void addCacheOption(CLI::App& sub, std::string& cacheDir);
// --data DIR: the data folder (resources.h, dataDir).
void addDataOption(CLI::App& sub, std::string& dataDir);
// --scenes DIR: the folder of the thesis scenes (resources.h, thesisScenesDir).
void addScenesOption(CLI::App& sub, std::string& scenesDir);

// --threads N, set (setParallelThreads) as soon as the command's arguments are parsed: 0, the
// default, is every hardware thread; the output does not depend on it.
void addThreadsOption(CLI::App& sub);
// --threads N kept in `threads` and not applied (bench measures single-threaded steps), with the
// same check and its own help.
void addThreadsOption(CLI::App& sub, int& threads, const std::string& help);

// --json.
void addJsonFlag(CLI::App& sub, bool& json);

// --glb-tolerance MM: the animation GLB's largest vertex error in any frame (> 0; default 0.05 mm).
void addGlbToleranceOption(CLI::App& sub, double& toleranceMm);

}  // namespace myo::cli
