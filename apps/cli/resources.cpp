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

// What the basis caches of this process did (basisCacheActivity()).
BasisCacheActivity& activity() {
  static BasisCacheActivity a;
  return a;
}

// The file cache, warning once when a basis cannot be stored, once when it works without a lock,
// and for every unusable entry it meets (which is then recomputed).
class WarningBasisCache : public BasisCache {
 public:
  WarningBasisCache(fs::path dir, FileBasisCache::Access access, std::string program)
      : files_(std::move(dir), access), program_(std::move(program)) {
    activity().enabled = true;
    activity().readOnly = activity().readOnly || files_.readOnly();
  }
  std::optional<ModalBasis> load(const BasisKey& key) override {
    const FileBasisCache::Stats before = files_.stats();
    std::optional<ModalBasis> b = files_.load(key);
    const FileBasisCache::Stats& now = files_.stats();
    BasisCacheActivity& a = activity();
    a.hits += now.hits - before.hits;
    a.waited += now.waited - before.waited;
    a.rejected += now.rejected - before.rejected;
    if (now.misses > before.misses) {
      ++a.computed;
      a.computedKeys.push_back(now.missedKeys.back());
    }
    if (now.rejected > before.rejected)
      fmt::print(stderr, "{}: warning: ignoring an unusable basis cache entry, recomputing it: {}\n", program_,
                 files_.lastRejection());
    if (!warnedLock_ && !files_.lockNote().empty()) {
      warnedLock_ = true;
      fmt::print(stderr, "{}: warning: basis cache without a lock: {}\n", program_, files_.lockNote());
    }
    return b;
  }
  Reader reader() const override { return files_.reader(); }
  void store(const BasisKey& key, const ModalBasis& basis) override {
    const int storesBefore = files_.stats().stores;
    files_.store(key, basis);
    activity().stored += files_.stats().stores - storesBefore;
    if (!warned_ && !files_.lastStoreError().empty()) {
      warned_ = true;
      fmt::print(stderr, "{}: warning: the basis cache keeps nothing: {}\n", program_, files_.lastStoreError());
    }
  }

 private:
  FileBasisCache files_;
  std::string program_;
  bool warned_ = false;
  bool warnedLock_ = false;
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
  if (!option.empty()) return {fs::absolute(option), "--data"};
  if (const char* d = nonEmpty(env("MYOSHELL_DATA"))) return {fs::absolute(d), "$MYOSHELL_DATA"};
  fs::path exeDir;
  if (runFromBuildTree(&exeDir)) return {(fs::path(MYO_SHARED_TREE) / "data").lexically_normal(), "source tree's ../shared/data"};
  return {{}, "none (give --data DIR or set MYOSHELL_DATA)"};
}

ResolvedPath thesisScenesDir(const std::string& option) {
  if (!option.empty()) return {fs::absolute(option), "--scenes"};
  const ResolvedPath shipped = shippedScenesDir();
  return {shipped.dir / "thesis", shipped.source};
}

ResolvedPath cacheDir(const std::string& option, const EnvLookup& env) {
  if (!option.empty()) return {fs::absolute(option), "--cache"};
  if (const char* d = nonEmpty(env("MYOSHELL_CACHE"))) return {fs::absolute(d), "$MYOSHELL_CACHE"};
  // The XDG base-directory spec: a relative XDG_CACHE_HOME is invalid and ignored.
  if (const char* x = nonEmpty(env("XDG_CACHE_HOME")); x && fs::path(x).is_absolute())
    return {fs::path(x) / "myoshell", "$XDG_CACHE_HOME"};
  if (const char* h = nonEmpty(env("HOME"))) return {fs::path(h) / ".cache" / "myoshell", "$HOME/.cache"};
  return {{}, "none (no --cache, MYOSHELL_CACHE, XDG_CACHE_HOME or HOME)"};
}

std::unique_ptr<BasisCache> openBasisCache(const std::string& option, const std::string& program) {
  const ResolvedPath where = cacheDir(option);
  activity().requested = true;
  const auto off = [&](const std::string& why) -> std::unique_ptr<BasisCache> {
    fmt::print(stderr, "{}: warning: no basis cache ({}); the bases are computed and not kept\n", program, why);
    return std::make_unique<NoBasisCache>();
  };
  if (where.dir.empty()) return off("no folder: " + where.source);
  // An existing folder we cannot add files to (a read-only folder or file system, a shared cache
  // built beforehand) is read without locks and never written.
  std::error_code ec;
  if (fs::is_directory(where.dir, ec) && ::access(where.dir.c_str(), W_OK | X_OK) != 0) {
    if (::access(where.dir.c_str(), R_OK | X_OK) != 0)
      return off("cannot read the basis cache folder " + where.dir.string() + " (" + std::strerror(errno) + ")");
    return std::make_unique<WarningBasisCache>(where.dir, FileBasisCache::Access::ReadOnly, program);
  }
  try {
    return std::make_unique<WarningBasisCache>(where.dir, FileBasisCache::Access::ReadWrite, program);
  } catch (const InputError& e) {
    return off(e.what());
  }
}

const BasisCacheActivity& basisCacheActivity() { return activity(); }

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
