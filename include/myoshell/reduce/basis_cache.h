// The basis cache interface: precomputed modal bases keyed by a hash of everything they depend
// on. `reduce` declares it; `io` implements it with files (io/basis_cache_file.h), so `face` can
// build with a cache without knowing about files (DESIGN.md, layers).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "myoshell/reduce/modal_basis.h"

namespace myo {

// A 128-bit content key (two independent 64-bit hashes of the same bytes).
struct BasisKey {
  std::array<uint64_t, 2> words{0, 0};
  // 32 lowercase hex digits; used as the cache file name.
  std::string hex() const;
  friend bool operator==(const BasisKey&, const BasisKey&) = default;
};

// Incremental 128-bit hash of raw bytes: lane 0 is FNV-1a 64, lane 1 is FNV-1a 64 with another
// offset basis followed by a splitmix64 finalizer per block. Not cryptographic; collisions are
// ~2^-64 for accidental inputs, which is what a cache needs.
class KeyHasher {
 public:
  KeyHasher& bytes(const void* data, size_t size);
  KeyHasher& str(std::string_view s);  // length-prefixed
  template <class T>
  KeyHasher& pod(const T& value) {
    return bytes(&value, sizeof(T));
  }
  BasisKey key() const;

 private:
  uint64_t a_ = 0xcbf29ce484222325ULL;
  uint64_t b_ = 0x84222325cbf29ce4ULL;
};

// 64-bit FNV-1a of a byte range (used as the payload checksum of cache files).
uint64_t fnv1a64(const void* data, size_t size, uint64_t seed = 0xcbf29ce484222325ULL);

// Where computed bases are kept between runs. load() returns nothing when the key is unknown or
// the stored copy is unusable (an implementation must never return a corrupt basis); store()
// may fail silently (a cache is an optimization) but must never leave a partial entry that a
// later load() would accept.
class BasisCache {
 public:
  virtual ~BasisCache() = default;
  virtual std::optional<ModalBasis> load(const BasisKey& key) = 0;
  virtual void store(const BasisKey& key, const ModalBasis& basis) = 0;
  // A loader that stays valid after this object is gone, for what a model may need later (a
  // basis it skipped at start-up); empty when the cache cannot give one (the caller rebuilds).
  using Reader = std::function<std::optional<ModalBasis>(const BasisKey&)>;
  virtual Reader reader() const { return {}; }
};

}  // namespace myo
