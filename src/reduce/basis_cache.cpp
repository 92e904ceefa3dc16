#include "myoshell/reduce/basis_cache.h"

#include <cstdio>

namespace myo {

namespace {
constexpr uint64_t kFnvPrime = 0x100000001b3ULL;

uint64_t splitmix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
}  // namespace

uint64_t fnv1a64(const void* data, size_t size, uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t h = seed;
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= kFnvPrime;
  }
  return h;
}

std::string BasisKey::hex() const {
  char buf[33];
  std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(words[0]),
                static_cast<unsigned long long>(words[1]));
  return buf;
}

KeyHasher& KeyHasher::bytes(const void* data, size_t size) {
  // Lane a: FNV-1a; lane b: FNV-1a with another basis, then a splitmix finalizer per call so that
  // the two lanes are not the same function of the input. Both in one pass (two independent
  // chains): the same values as fnv1a64 twice, in about half the time.
  const auto* p = static_cast<const unsigned char*>(data);
  uint64_t a = a_, b = b_;
  for (size_t i = 0; i < size; ++i) {
    a = (a ^ p[i]) * kFnvPrime;
    b = (b ^ p[i]) * kFnvPrime;
  }
  a_ = a;
  b_ = splitmix64(b ^ (size * 0x9e3779b97f4a7c15ULL));
  return *this;
}

KeyHasher& KeyHasher::str(std::string_view s) {
  uint64_t n = s.size();
  bytes(&n, sizeof n);
  return bytes(s.data(), s.size());
}

BasisKey KeyHasher::key() const {
  BasisKey k;
  k.words = {splitmix64(a_), b_};
  return k;
}

}  // namespace myo
