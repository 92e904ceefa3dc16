#include "common_options.h"

#include <memory>

#include "myoshell/core/parallel.h"
#include "option_checks.h"

namespace myo::cli {

namespace {
void addFileOptions(CLI::App& sub, HeadOptions& head, const HeadHelp& notes) {
  head.landmarksOption =
      sub.add_option("--landmarks", head.landmarks, "Landmark file of an OBJ head" + notes.landmarks +
                         " (docs/heads.md; without one an OBJ's are found automatically and kept in the cache folder)");
  head.unitsOption = sub.add_option("--units", head.units,
                                    "Length unit of an OBJ head, m, mm or cm (scaled to cm on load; default cm, or, with "
                                    "automatic landmarks, the unit inferred from its size)" + notes.units);
}
}  // namespace

void addHeadOptions(CLI::App& sub, HeadOptions& head, const HeadHelp& notes) {
  head.headOption = sub.add_option("--head", head.head,
                                   "The head: 'default' (the built-in head), an OBJ file or a folder "
                                   "like ../shared/data/ict" + notes.head + "; default: " + notes.headDefault);
  addFileOptions(sub, head, notes);
}

void addHeadFileOptions(CLI::App& sub, HeadOptions& head) { addFileOptions(sub, head, {}); }

HeadFiles headFiles(const HeadOptions& head) { return resolveHeadArgument(head.head, head.landmarks, "", head.units); }

FitHeadOptions fitHeadOptions(const HeadOptions& head, const std::string& library) {
  FitHeadOptions o;
  o.head = head.head;
  o.landmarks = head.landmarks;
  o.units = head.units;
  o.library = library;
  o.headGiven = head.headGiven();
  o.unitsGiven = head.unitsGiven();
  return o;
}

void addLibraryOption(CLI::App& sub, std::string& library) {
  sub.add_option("--library", library,
                 "Muscles: face (the whole face's 40, docs/muscles.md), builtin (the built-in ten: the thesis's "
                 "eight, placed anatomically, and the lips' two rings) or a library file; default: " + library);
}

void addCacheOption(CLI::App& sub, std::string& cacheDir) {
  sub.add_option("--cache", cacheDir,
                 "Basis cache folder, which also keeps automatic landmarks (default: $MYOSHELL_CACHE, "
                 "$XDG_CACHE_HOME/myoshell or ~/.cache/myoshell)");
}

void addDataOption(CLI::App& sub, std::string& dataDir) {
  sub.add_option("--data", dataDir,
                 "Data folder holding ict/ (default: $MYOSHELL_DATA, or ../shared/data beside the source tree)");
}

void addScenesOption(CLI::App& sub, std::string& scenesDir) {
  sub.add_option("--scenes", scenesDir, "Folder of the thesis scenes (default: the shipped scenes/thesis)");
}

namespace {
CLI::Option* threadsOption(CLI::App& sub, int& threads, const std::string& help) {
  return sub.add_option("--threads", threads, help)->check(wholeAtLeast(0, "0 = every core"));
}
}  // namespace

void addThreadsOption(CLI::App& sub) {
  auto threads = std::make_shared<int>(0);
  threadsOption(sub, *threads,
                "Threads for the precompute and independent work (0 = every hardware thread, the default; the output "
                "does not depend on it)");
  // Applied once the command's arguments are parsed, before it runs; the other commands keep one thread.
  sub.parse_complete_callback([threads] { setParallelThreads(*threads); });
}

void addThreadsOption(CLI::App& sub, int& threads, const std::string& help) { threadsOption(sub, threads, help); }

void addJsonFlag(CLI::App& sub, bool& json) {
  sub.add_flag("--json", json, "Print the result as JSON instead of text (its keys: docs/cli.md)");
}

void addGlbToleranceOption(CLI::App& sub, double& toleranceMm) {
  sub.add_option("--glb-tolerance", toleranceMm,
                 "the GLB's largest vertex error in any frame, mm: fewer morph targets (a smaller file) for a larger "
                 "one (docs/exports.md)")
      ->check(numberAbove(0))
      ->capture_default_str();
}

}  // namespace myo::cli
