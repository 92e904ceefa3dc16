// Where `myoshell` and `myoshell-view` find their files, whatever the current folder:
//  - shipped scenes: beside the executable. Run from a build tree (<build>/bin/myoshell), the
//    source tree's scenes/; installed (<prefix>/bin/myoshell), <prefix>/share/myoshell/scenes
//    (put there by `cmake --install`).
//  - the data folder (the team's data beside the project: the ICT head of bench's `ict` rows and
//    fig. 27): --data DIR, else $MYOSHELL_DATA, else, from a build tree, the source tree's
//    ../shared/data; installed, none.
//  - the basis cache: --cache DIR, else $MYOSHELL_CACHE, else $XDG_CACHE_HOME/myoshell (an
//    absolute XDG_CACHE_HOME only, as the XDG spec says), else ~/.cache/myoshell.
// docs/paths.md describes them; `myoshell paths` prints what they resolve to.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "myoshell/anim/scene.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo::cli {

// Reads an environment variable; nullptr when unset. Tests pass their own.
using EnvLookup = std::function<const char*(const char*)>;
EnvLookup processEnv();

// A resolved folder and where it came from ("--cache", "$MYOSHELL_CACHE", "build tree", …);
// dir is empty when nothing names one (no HOME, no data folder for an installed program).
struct ResolvedPath {
  std::filesystem::path dir;
  std::string source;
};

// The folder of the shipped scenes (scenes/demo.json, scenes/thesis/…) for this executable.
ResolvedPath shippedScenesDir();
// The data folder: `option` (--data) if not empty, else $MYOSHELL_DATA, else the build tree's default.
ResolvedPath dataDir(const std::string& option, const EnvLookup& env = processEnv());
// The basis cache folder by the precedence above; `option` is --cache ("" when not given).
ResolvedPath cacheDir(const std::string& option, const EnvLookup& env = processEnv());

// The basis cache of a command that builds a face, at cacheDir(option). It never stops the
// command: when the folder cannot be made or written, `program` prints one warning naming the
// folder and the OS's reason, and the bases are computed without a cache; a basis that cannot be
// stored warns once the same way.
std::unique_ptr<BasisCache> openBasisCache(const std::string& option, const std::string& program = "myoshell");

// The thesis scenes name the ICT head through the team's data folder beside the project
// (`../../../shared/data/ict/head_skin.obj`). Each head path with a `shared/data/` part is re-rooted
// at `data` (data / the rest), so the scenes work from an installed copy or another folder.
// Paths without that part are left alone.
void useDataDir(SceneDesc& scene, const std::filesystem::path& data);

}  // namespace myo::cli
