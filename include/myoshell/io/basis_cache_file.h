// The on-disk basis cache: one binary file per key in a cache directory.
//
// File "<dir>/<key.hex()>.myobasis", little-endian:
//   header (64 bytes): magic "MYOBASIS" (8) | format version u32 | header size u32 |
//                      key (2×u64) | fullVertexCount u32 | free count f u32 | modes d u32 |
//                      reserved u32 | payload bytes u64 | payload FNV-1a 64 checksum u64
//   payload: freeVertices (f×i32) | lambda (d×f64) | freeMass (f×f64) | Phi (3f·d f64, column-major)
//            | Psi (3f·d f64, column-major) | solver name (u32 length + bytes)
// Written to a temporary name in the same directory and renamed into place, so a reader never
// sees a partial file. On load, a wrong magic/version/key/size, a short or long file, or a checksum
// mismatch makes load() return nothing (the caller recomputes and overwrites); the reason is kept
// in lastRejection() and counted in stats().
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "myoshell/reduce/basis_cache.h"

namespace myo {

// Writes / reads one basis file (see above). readBasisFile returns nothing and sets *why when the
// file is missing or unusable for `key`.
void writeBasisFile(const std::filesystem::path& path, const BasisKey& key, const ModalBasis& basis);
std::optional<ModalBasis> readBasisFile(const std::filesystem::path& path, const BasisKey& key,
                                        std::string* why = nullptr);

class FileBasisCache : public BasisCache {
 public:
  // Creates the directory if needed (throws InputError naming it and the OS's reason if it cannot).
  explicit FileBasisCache(std::filesystem::path directory);

  std::optional<ModalBasis> load(const BasisKey& key) override;
  void store(const BasisKey& key, const ModalBasis& basis) override;
  Reader reader() const override;  // reads this directory's files (no statistics)

  std::filesystem::path pathFor(const BasisKey& key) const;
  const std::filesystem::path& directory() const { return dir_; }

  struct Stats {
    int hits = 0;      // loads that returned a basis
    int misses = 0;    // loads with no file
    int rejected = 0;  // loads that found an unusable file (corrupt, truncated, other key, …)
    int stores = 0;    // successful stores
  };
  const Stats& stats() const { return stats_; }
  // Why the last rejected file was rejected ("" if none was).
  const std::string& lastRejection() const { return lastRejection_; }
  // Why the last store failed, naming the file and the OS's reason ("" if none did). A failed
  // store is not an error: the basis is simply not kept.
  const std::string& lastStoreError() const { return lastStoreError_; }

 private:
  std::filesystem::path dir_;
  Stats stats_;
  std::string lastRejection_;
  std::string lastStoreError_;
};

}  // namespace myo
