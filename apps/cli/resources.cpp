#include "resources.h"

#include <fmt/core.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <system_error>

#include "myoshell/core/errors.h"
#include "myoshell/io/basis_cache_file.h"

// Set by apps/cli/CMakeLists.txt: the source tree, the build tree's bin/ folder and the team's data
// folder beside the source tree.
#ifndef MYO_SOURCE_TREE
#error "MYO_SOURCE_TREE must be defined (apps/cli/CMakeLists.txt)"
#endif

namespace myo::cli {

namespace fs = std::filesystem;

namespace {

fs::path canonicalOrSelf(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return ec ? p : c;
}

// True when this executable is the one in the build tree (not an installed copy).
bool runFromBuildTree(fs::path* exeDir) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return false;  // no /proc: treat as installed, whose layout is relative to nothing known
  *exeDir = exe.parent_path();
  return canonicalOrSelf(*exeDir) == canonicalOrSelf(MYO_BUILD_BIN_DIR);
}

const char* nonEmpty(const char* s) { return s && *s ? s : nullptr; }

// A basis cache that keeps nothing (the cache folder is unusable).
class NoBasisCache : public BasisCache {
 public:
  std::optional<ModalBasis> load(const BasisKey&) override { return std::nullopt; }
  void store(const BasisKey&, const ModalBasis&) override {}
};

// The file cache, warning once when a basis cannot be stored.
class WarningBasisCache : public BasisCache {
 public:
  WarningBasisCache(fs::path dir, std::string program) : files_(std::move(dir)), program_(std::move(program)) {}
  std::optional<ModalBasis> load(const BasisKey& key) override { return files_.load(key); }
  Reader reader() const override { return files_.reader(); }
  void store(const BasisKey& key, const ModalBasis& basis) override {
    files_.store(key, basis);
    if (!warned_ && !files_.lastStoreError().empty()) {
      warned_ = true;
      fmt::print(stderr, "{}: warning: the basis cache keeps nothing: {}\n", program_, files_.lastStoreError());
    }
  }

 private:
  FileBasisCache files_;
  std::string program_;
  bool warned_ = false;
};

}  // namespace

EnvLookup processEnv() {
  return [](const char* name) { return std::getenv(name); };
}

ResolvedPath shippedScenesDir() {
  fs::path exeDir;
  if (runFromBuildTree(&exeDir)) return {fs::path(MYO_SOURCE_TREE) / "scenes", "source tree"};
  if (exeDir.empty()) return {fs::path(MYO_SOURCE_TREE) / "scenes", "source tree (no /proc/self/exe)"};
  return {exeDir.parent_path() / "share" / "myoshell" / "scenes", "installed"};
}

ResolvedPath dataDir(const std::string& option, const EnvLookup& env) {
  if (!option.empty()) return {option, "--data"};
  if (const char* d = nonEmpty(env("MYOSHELL_DATA"))) return {d, "$MYOSHELL_DATA"};
  fs::path exeDir;
  if (runFromBuildTree(&exeDir)) return {(fs::path(MYO_SHARED_TREE) / "data").lexically_normal(), "source tree's ../shared/data"};
  return {{}, "none (give --data DIR or set MYOSHELL_DATA)"};
}

ResolvedPath cacheDir(const std::string& option, const EnvLookup& env) {
  if (!option.empty()) return {option, "--cache"};
  if (const char* d = nonEmpty(env("MYOSHELL_CACHE"))) return {d, "$MYOSHELL_CACHE"};
  // The XDG base-directory spec: a relative XDG_CACHE_HOME is invalid and ignored.
  if (const char* x = nonEmpty(env("XDG_CACHE_HOME")); x && fs::path(x).is_absolute())
    return {fs::path(x) / "myoshell", "$XDG_CACHE_HOME"};
  if (const char* h = nonEmpty(env("HOME"))) return {fs::path(h) / ".cache" / "myoshell", "$HOME/.cache"};
  return {{}, "none (no --cache, MYOSHELL_CACHE, XDG_CACHE_HOME or HOME)"};
}

std::unique_ptr<BasisCache> openBasisCache(const std::string& option, const std::string& program) {
  const ResolvedPath where = cacheDir(option);
  const auto off = [&](const std::string& why) -> std::unique_ptr<BasisCache> {
    fmt::print(stderr, "{}: warning: no basis cache ({}); the bases are computed and not kept\n", program, why);
    return std::make_unique<NoBasisCache>();
  };
  if (where.dir.empty()) return off("no folder: " + where.source);
  std::unique_ptr<WarningBasisCache> cache;
  try {
    cache = std::make_unique<WarningBasisCache>(where.dir, program);
  } catch (const InputError& e) {
    return off(e.what());
  }
  // The folder exists: can we add files to it? (A read-only folder or file system.)
  if (::access(where.dir.c_str(), W_OK | X_OK) != 0)
    return off("cannot write into the basis cache folder " + where.dir.string() + " (" + std::strerror(errno) + ")");
  return cache;
}

void useDataDir(SceneDesc& scene, const fs::path& data) {
  for (std::string* p : {&scene.head.obj, &scene.head.landmarks, &scene.head.gravityPins, &scene.head.skull}) {
    const std::string generic = fs::path(*p).generic_string();
    const std::string key = "shared/data/";
    const size_t at = generic.find(key);
    if (at == std::string::npos || (at > 0 && generic[at - 1] != '/')) continue;
    *p = (data / generic.substr(at + key.size())).string();
  }
}

}  // namespace myo::cli
