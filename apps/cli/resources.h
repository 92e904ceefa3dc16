// Where `myoshell` and `myoshell-view` find their files, whatever the current folder:
//  - shipped scenes: beside the executable. Run from a build tree (<build>/bin/myoshell), the
//    source tree's scenes/; installed (<prefix>/bin/myoshell), <prefix>/share/myoshell/scenes
//    (put there by `cmake --install`).
//  - the data folder (the team's data beside the project: the ICT head of bench's `ict` rows and
//    fig. 27): --data DIR, else $MYOSHELL_DATA, else, from a build tree, the source tree's
//    ../shared/data; installed, none.
//  - the basis cache: --cache DIR, else $MYOSHELL_CACHE, else $XDG_CACHE_HOME/myoshell (an
//    absolute XDG_CACHE_HOME only, as the XDG spec says), else ~/.cache/myoshell.
// A folder named by an option or a variable is relative to the current directory, and resolved
// to an absolute path here: the commands re-root scene-relative paths at other folders, which must
// not capture it (`bench --data ../shared/data` run from the source tree).
// docs/paths.md describes them; `myoshell paths` prints what they resolve to.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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
// The thesis scenes of bench and figures: `option` (--scenes) if not empty, else the shipped scenes/thesis.
ResolvedPath thesisScenesDir(const std::string& option);
// The basis cache folder by the precedence above; `option` is --cache ("" when not given).
ResolvedPath cacheDir(const std::string& option, const EnvLookup& env = processEnv());

// The basis cache of a command that builds a face, at cacheDir(option). It never stops the
// command: when the folder cannot be made or read, `program` prints one warning naming the folder
// and the OS's reason, and the bases are computed without a cache; a folder it cannot write (a
// shared, read-only cache) is read without locks and never written; a basis that cannot be stored
// warns once the same way. Processes sharing the folder lock each key while one of them computes it
// (io/basis_cache_file.h, docs/batch.md).
std::unique_ptr<BasisCache> openBasisCache(const std::string& option, const std::string& program = "myoshell");

// What the basis caches opened by openBasisCache did in this process (for --json's basis_cache).
struct BasisCacheActivity {
  bool requested = false; // the command asked for a cache (openBasisCache)
  bool enabled = false;   // a cache folder was usable
  bool readOnly = false;  // ... and read-only
  int hits = 0;           // bases read without waiting
  int waited = 0;         // bases read after waiting for another process computing them
  int computed = 0;       // bases this process computed (cache misses)
  int stored = 0;         // bases it stored
  int rejected = 0;       // unusable entries met (then recomputed)
  std::vector<std::string> computedKeys;  // the keys (hex) of the computed bases
};
const BasisCacheActivity& basisCacheActivity();

// The thesis scenes name the ICT head through the team's data folder beside the project
// (`../../../shared/data/ict/head_skin.obj`). Each head path with a `shared/data/` part is re-rooted
// at `data` (data / the rest), so the scenes work from an installed copy or another folder.
// Paths without that part are left alone.
void useDataDir(SceneDesc& scene, const std::filesystem::path& data);

}  // namespace myo::cli
