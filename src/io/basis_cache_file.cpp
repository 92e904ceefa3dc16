#include "myoshell/io/basis_cache_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
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

namespace {

// The lock files this process holds, over all FileBasisCache objects: flock locks belong to an open
// file description, so a second object of this process locking a file the first holds would wait
// for itself. (Process state, as the locks themselves are.)
std::mutex& heldLocksMutex() {
  static std::mutex m;
  return m;
}
std::set<std::string>& heldLockPaths() {
  static std::set<std::string> paths;
  return paths;
}

}  // namespace

FileBasisCache::FileBasisCache(std::filesystem::path directory, Access access)
    : dir_(std::move(directory)), access_(access) {
  std::error_code ec;
  if (access_ == Access::ReadOnly) {
    if (!std::filesystem::is_directory(dir_, ec))
      throw InputError("the read-only basis cache directory " + dir_.string() + " is not a folder" +
                       (ec ? " (" + ec.message() + ")" : std::string()));
    return;
  }
  std::filesystem::create_directories(dir_, ec);
  if (!ec && !std::filesystem::is_directory(dir_)) ec = std::make_error_code(std::errc::not_a_directory);
  if (ec) throw InputError("cannot create the basis cache directory " + dir_.string() + " (" + ec.message() + ")");
}

FileBasisCache::~FileBasisCache() {
  std::lock_guard<std::mutex> g(heldLocksMutex());
  for (const auto& [hex, fd] : held_) {
    heldLockPaths().erase((dir_ / (hex + ".lock")).string());
    ::close(fd);  // releases the flock
  }
}

std::filesystem::path FileBasisCache::pathFor(const BasisKey& key) const {
  return dir_ / (key.hex() + ".myobasis");
}

std::filesystem::path FileBasisCache::lockPathFor(const BasisKey& key) const {
  return dir_ / (key.hex() + ".lock");
}

std::optional<ModalBasis> FileBasisCache::read(const BasisKey& key, bool* rejected) {
  const auto path = pathFor(key);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::string why;
  std::optional<ModalBasis> b = readBasisFile(path, key, &why);
  if (!b) {
    *rejected = true;
    lastRejection_ = path.string() + ": " + why;
  }
  return b;
}

bool FileBasisCache::lock(const BasisKey& key, bool* blocked) {
  *blocked = false;
  const std::string path = lockPathFor(key).string();
  {
    std::lock_guard<std::mutex> g(heldLocksMutex());
    if (!heldLockPaths().insert(path).second) {
      lockNote_ = path + " is held by another cache object of this process; computing without the lock";
      return false;
    }
  }
  const auto giveUp = [&](const std::string& what, int error) {
    lockNote_ = what + " " + path + " (" + std::strerror(error) +
                "); computing without the lock: the entries stay whole (atomic rename), but processes "
                "starting at once may compute the same basis";
    std::lock_guard<std::mutex> g(heldLocksMutex());
    heldLockPaths().erase(path);
    return false;
  };
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return giveUp("cannot create the lock file", errno);
  int rc = ::flock(fd, LOCK_EX | LOCK_NB);
  if (rc != 0 && errno == EWOULDBLOCK) {
    *blocked = true;
    do rc = ::flock(fd, LOCK_EX);
    while (rc != 0 && errno == EINTR);
  }
  if (rc != 0) {
    const int error = errno;
    ::close(fd);
    return giveUp("cannot lock", error);
  }
  held_[key.hex()] = fd;
  return true;
}

void FileBasisCache::unlock(const BasisKey& key) {
  const auto it = held_.find(key.hex());
  if (it == held_.end()) return;
  ::close(it->second);  // releases the flock; the (empty) lock file stays, as waiters may hold it open
  held_.erase(it);
  std::lock_guard<std::mutex> g(heldLocksMutex());
  heldLockPaths().erase(lockPathFor(key).string());
}

void FileBasisCache::removeStaleTemporaries(const BasisKey& key) const {
  // writeFileAtomically's temporaries of this key: ".<hex>.myobasis.<pid>.<n>.tmp". With the key's
  // lock held no other process writes it, so those of other processes were left by a killed writer.
  std::string prefix(1, '.');  // (appends: gcc 12 warns falsely on "." + string)
  prefix.append(key.hex()).append(".myobasis.");
  std::string own = prefix;
  own.append(std::to_string(::getpid())).append(".");
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(dir_, ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) == 0 && name.rfind(own, 0) != 0 && name.size() > 4 &&
        name.compare(name.size() - 4, 4, ".tmp") == 0)
      removeQuietly(it->path().string());
  }
}

std::optional<ModalBasis> FileBasisCache::load(const BasisKey& key) {
  bool rejected = false;  // an unusable file met (counted once per load)
  std::optional<ModalBasis> b = read(key, &rejected);
  if (!b && access_ == Access::ReadWrite && !held_.count(key.hex())) {
    bool blocked = false;
    if (lock(key, &blocked)) {
      // Another process may have stored it since the first read (while we waited, or just before).
      b = read(key, &rejected);
      if (b) {
        unlock(key);
        if (blocked) {
          stats_.rejected += rejected;
          ++stats_.waited;
          return b;
        }
      } else {
        removeStaleTemporaries(key);
      }
    }
  }
  stats_.rejected += rejected;
  if (b) {
    ++stats_.hits;
    return b;
  }
  ++stats_.misses;
  stats_.missedKeys.push_back(key.hex());
  return std::nullopt;
}

BasisCache::Reader FileBasisCache::reader() const {
  return [dir = dir_](const BasisKey& key) { return readBasisFile(dir / (key.hex() + ".myobasis"), key); };
}

void FileBasisCache::store(const BasisKey& key, const ModalBasis& basis) {
  if (access_ == Access::ReadOnly) {
    lastStoreError_ = "the basis cache folder " + dir_.string() + " is read-only: the computed basis is not kept";
    return;
  }
  try {
    writeBasisFile(pathFor(key), key, basis);
    ++stats_.stores;
  } catch (const InputError& e) {
    // A cache is an optimization: a read-only or full disk must not stop a build.
    lastStoreError_ = e.what();
  } catch (const IoError& e) {  // a full disk, a file-size limit
    lastStoreError_ = e.what();
  }
  unlock(key);  // after the rename: a waiter that wakes finds the file whole
}

}  // namespace myo
