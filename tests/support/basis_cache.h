// One basis cache shared by the library tests of a ctest run. ctest sets MYOSHELL_CACHE to
// <build>/test_cache (tests/CMakeLists.txt), as it does for the CLI tests, so an eigen-solve is paid
// by the first test process that needs it and read back, bit for bit, by the others (the cache's
// own correctness is tested in tests/io). Run outside ctest (no variable), nothing is cached.
#pragma once

#include <cstdlib>
#include <memory>

#include "myoshell/io/basis_cache_file.h"

namespace myo::test {

inline BasisCache* sharedBasisCache() {
  static const std::unique_ptr<FileBasisCache> cache = []() -> std::unique_ptr<FileBasisCache> {
    const char* dir = std::getenv("MYOSHELL_CACHE");
    if (dir == nullptr || *dir == '\0') return nullptr;
    return std::make_unique<FileBasisCache>(dir);
  }();
  return cache.get();
}

}  // namespace myo::test
