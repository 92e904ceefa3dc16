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
//
// Many processes may share one cache folder (a batch of jobs starting cold at once; docs/batch.md).
// Each key has a lock file "<dir>/<key.hex()>.lock" locked with POSIX flock(2), which the kernel
// releases when its holder exits or is killed. load() reads without a lock; when it finds no usable
// file it takes the key's lock (blocking while another process holds it), reads again, and
//  - finds the file another process stored meanwhile: unlocks and returns it (stats().waited when it
//    had to block, stats().hits otherwise);
//  - finds nothing: returns nothing and keeps the lock, so the caller computes the basis alone;
//    store() writes it (atomically, as above) and unlocks. A caller that never stores after such a
//    miss (its build failed) keeps the lock until this object is destroyed or the process ends.
// So each basis is computed once among the processes sharing the folder, and a holder killed mid-
// computation hands the key to the next waiter. Stale temporary files of the key (from a killed
// writer) are removed while the lock is held.
// Where flock is unavailable (EOPNOTSUPP, ENOLCK, EINVAL: some network file systems; or the lock
// file cannot be created), the cache works without locks: the atomic rename still keeps every
// entry whole, but processes starting at once may compute the same basis (lockNote() says why).
// A read-only cache (Access::ReadOnly: a folder this process cannot write) is read without locks
// and never written: store() keeps nothing and says so in lastStoreError().
// Locks are per open file description: two FileBasisCache objects of one process on one folder do
// not block each other (the second computes without the lock) rather than deadlock.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/reduce/basis_cache.h"

namespace myo {

// Writes / reads one basis file (see above). readBasisFile returns nothing and sets *why when the
// file is missing or unusable for `key`.
void writeBasisFile(const std::filesystem::path& path, const BasisKey& key, const ModalBasis& basis);
std::optional<ModalBasis> readBasisFile(const std::filesystem::path& path, const BasisKey& key,
                                        std::string* why = nullptr);

class FileBasisCache : public BasisCache {
 public:
  enum class Access {
    ReadWrite,  // stores bases, locking per key (see above)
    ReadOnly,   // only reads, without locks; store() keeps nothing
  };
  // Creates the directory if needed (throws InputError naming it and the OS's reason if it cannot;
  // with Access::ReadOnly the directory must exist).
  explicit FileBasisCache(std::filesystem::path directory, Access access = Access::ReadWrite);
  ~FileBasisCache() override;
  FileBasisCache(const FileBasisCache&) = delete;
  FileBasisCache& operator=(const FileBasisCache&) = delete;

  std::optional<ModalBasis> load(const BasisKey& key) override;
  void store(const BasisKey& key, const ModalBasis& basis) override;
  Reader reader() const override;  // reads this directory's files (no statistics)

  std::filesystem::path pathFor(const BasisKey& key) const;
  std::filesystem::path lockPathFor(const BasisKey& key) const;
  const std::filesystem::path& directory() const { return dir_; }
  bool readOnly() const { return access_ == Access::ReadOnly; }

  struct Stats {
    int hits = 0;      // loads that returned a basis without waiting for another process
    int waited = 0;    // loads that blocked on another process's lock, then read what it stored
    int misses = 0;    // loads that returned nothing (the caller computes the basis)
    int rejected = 0;  // unusable files met (corrupt, truncated, other key, …); the load goes on as a miss
    int stores = 0;    // successful stores
    std::vector<std::string> missedKeys;  // the keys (hex) of the misses, in order
  };
  const Stats& stats() const { return stats_; }
  // Why the last rejected file was rejected ("" if none was).
  const std::string& lastRejection() const { return lastRejection_; }
  // Why the last store failed, naming the file and the OS's reason ("" if none did). A failed
  // store is not an error: the basis is simply not kept.
  const std::string& lastStoreError() const { return lastStoreError_; }
  // Why the cache last worked without a lock, naming the lock file and the OS's reason ("" if it
  // never did).
  const std::string& lockNote() const { return lockNote_; }

 private:
  // Takes the lock of `key` (blocking); returns false when it could not (lockNote_ says why).
  // *blocked: whether another process held it.
  bool lock(const BasisKey& key, bool* blocked);
  void unlock(const BasisKey& key);
  void removeStaleTemporaries(const BasisKey& key) const;
  std::optional<ModalBasis> read(const BasisKey& key, bool* rejected);

  std::filesystem::path dir_;
  Access access_;
  std::map<std::string, int> held_;  // key hex → open lock file descriptor (locked)
  Stats stats_;
  std::string lastRejection_;
  std::string lastStoreError_;
  std::string lockNote_;
};

}  // namespace myo
