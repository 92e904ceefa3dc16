#include "myoshell/io/basis_cache_file.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/reduce/modal_analysis.h"

namespace myo {

namespace {

constexpr char kMagic[8] = {'M', 'Y', 'O', 'B', 'A', 'S', 'I', 'S'};
constexpr uint32_t kHeaderSize = 64;

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t headerSize;
  uint64_t key0, key1;
  uint32_t fullVertexCount;
  uint32_t freeCount;
  uint32_t modeCount;
  uint32_t reserved;
  uint64_t payloadBytes;
  uint64_t checksum;
};
static_assert(sizeof(Header) == kHeaderSize, "cache header layout");

class Writer {
 public:
  template <class T>
  void raw(const T* p, size_t count) {
    const auto* b = reinterpret_cast<const char*>(p);
    buf_.insert(buf_.end(), b, b + sizeof(T) * count);
  }
  std::vector<char>& bytes() { return buf_; }

 private:
  std::vector<char> buf_;
};

class Reader {
 public:
  Reader(const char* p, size_t n) : p_(p), n_(n) {}
  template <class T>
  bool raw(T* out, size_t count) {
    const size_t bytes = sizeof(T) * count;
    if (bytes > n_ - pos_) return false;
    std::memcpy(out, p_ + pos_, bytes);
    pos_ += bytes;
    return true;
  }
  bool atEnd() const { return pos_ == n_; }

 private:
  const char* p_;
  size_t n_;
  size_t pos_ = 0;
};

std::vector<char> payloadOf(const ModalBasis& b) {
  Writer w;
  w.raw(b.freeVertices.data(), b.freeVertices.size());
  w.raw(b.lambda.data(), b.lambda.size());
  w.raw(b.freeMass.data(), b.freeMass.size());
  w.raw(b.Phi.data(), b.Phi.size());
  w.raw(b.Psi.data(), b.Psi.size());
  const uint32_t len = static_cast<uint32_t>(b.solver.size());
  w.raw(&len, 1);
  w.raw(b.solver.data(), b.solver.size());
  return std::move(w.bytes());
}

bool reject(std::string* why, const std::string& reason) {
  if (why) *why = reason;
  return false;
}

}  // namespace

void writeBasisFile(const std::filesystem::path& path, const BasisKey& key, const ModalBasis& basis) {
  const std::vector<char> payload = payloadOf(basis);
  Header h{};
  std::memcpy(h.magic, kMagic, 8);
  h.version = kModalBasisFormatVersion;
  h.headerSize = kHeaderSize;
  h.key0 = key.words[0];
  h.key1 = key.words[1];
  h.fullVertexCount = static_cast<uint32_t>(basis.fullVertexCount);
  h.freeCount = static_cast<uint32_t>(basis.freeCount());
  h.modeCount = static_cast<uint32_t>(basis.modeCount());
  h.payloadBytes = payload.size();
  h.checksum = fnv1a64(payload.data(), payload.size());

  writeFileAtomically(
      path.string(),
      [&](std::FILE* out) {
        std::fwrite(&h, sizeof h, 1, out);
        std::fwrite(payload.data(), 1, payload.size(), out);
      },
      "cannot write the basis cache file");
}

std::optional<ModalBasis> readBasisFile(const std::filesystem::path& path, const BasisKey& key,
                                        std::string* why) {
  const std::optional<std::string> bytes = tryReadWholeFile(path.string());
  if (!bytes) {
    reject(why, "no file");
    return std::nullopt;
  }
  const std::string& data = *bytes;
  if (data.size() < kHeaderSize) {
    reject(why, "truncated header");
    return std::nullopt;
  }
  Header h;
  std::memcpy(&h, data.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, 8) != 0) return reject(why, "bad magic"), std::nullopt;
  if (h.version != kModalBasisFormatVersion || h.headerSize != kHeaderSize)
    return reject(why, "format version " + std::to_string(h.version) + " is not " +
                           std::to_string(kModalBasisFormatVersion)),
           std::nullopt;
  if (h.key0 != key.words[0] || h.key1 != key.words[1])
    return reject(why, "the file holds another key"), std::nullopt;
  if (data.size() - kHeaderSize != h.payloadBytes)
    return reject(why, "payload is " + std::to_string(data.size() - kHeaderSize) + " bytes, header says " +
                           std::to_string(h.payloadBytes)),
           std::nullopt;
  const char* payload = data.data() + kHeaderSize;
  if (fnv1a64(payload, h.payloadBytes) != h.checksum) return reject(why, "checksum mismatch"), std::nullopt;
  const uint64_t f = h.freeCount, d = h.modeCount;
  const uint64_t expected = 4 * f + 8 * d + 8 * f + 2 * 8 * 3 * f * d + 4;
  if (h.payloadBytes < expected || f == 0 || d == 0 || f > h.fullVertexCount)
    return reject(why, "inconsistent sizes"), std::nullopt;

  ModalBasis b;
  b.fullVertexCount = static_cast<int>(h.fullVertexCount);
  b.freeVertices.resize(f);
  b.lambda.resize(d);
  b.freeMass.resize(f);
  b.Phi.resize(3 * f, d);
  b.Psi.resize(3 * f, d);
  Reader r(payload, h.payloadBytes);
  uint32_t len = 0;
  bool ok = r.raw(b.freeVertices.data(), f) && r.raw(b.lambda.data(), d) && r.raw(b.freeMass.data(), f) &&
            r.raw(b.Phi.data(), 3 * f * d) && r.raw(b.Psi.data(), 3 * f * d) && r.raw(&len, 1);
  if (ok) {
    b.solver.resize(len);
    ok = r.raw(b.solver.data(), len) && r.atEnd();
  }
  if (!ok) return reject(why, "inconsistent sizes"), std::nullopt;
  for (size_t i = 0; i < f; ++i)
    if (b.freeVertices[i] < 0 || b.freeVertices[i] >= b.fullVertexCount ||
        (i > 0 && b.freeVertices[i] <= b.freeVertices[i - 1]))
      return reject(why, "free vertex list is not sorted and in range"), std::nullopt;
  b.fromCache = true;
  return b;
}

FileBasisCache::FileBasisCache(std::filesystem::path directory) : dir_(std::move(directory)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (!ec && !std::filesystem::is_directory(dir_)) ec = std::make_error_code(std::errc::not_a_directory);
  if (ec) throw InputError("cannot create the basis cache directory " + dir_.string() + " (" + ec.message() + ")");
}

std::filesystem::path FileBasisCache::pathFor(const BasisKey& key) const {
  return dir_ / (key.hex() + ".myobasis");
}

std::optional<ModalBasis> FileBasisCache::load(const BasisKey& key) {
  const auto path = pathFor(key);
  if (!std::filesystem::exists(path)) {
    ++stats_.misses;
    return std::nullopt;
  }
  std::string why;
  std::optional<ModalBasis> b = readBasisFile(path, key, &why);
  if (!b) {
    ++stats_.rejected;
    lastRejection_ = path.string() + ": " + why;
    return std::nullopt;
  }
  ++stats_.hits;
  return b;
}

BasisCache::Reader FileBasisCache::reader() const {
  return [dir = dir_](const BasisKey& key) { return readBasisFile(dir / (key.hex() + ".myobasis"), key); };
}

void FileBasisCache::store(const BasisKey& key, const ModalBasis& basis) {
  try {
    writeBasisFile(pathFor(key), key, basis);
    ++stats_.stores;
  } catch (const InputError& e) {
    // A cache is an optimization: a read-only or full disk must not stop a build.
    lastStoreError_ = e.what();
  } catch (const IoError& e) {  // a full disk, a file-size limit
    lastStoreError_ = e.what();
  }
}

}  // namespace myo
