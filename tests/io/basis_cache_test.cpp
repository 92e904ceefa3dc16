// The file basis cache: bit-identical round trip; corrupt, truncated and foreign files rejected;
// the per-key lock that processes sharing a folder take; a read-only folder.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <random>

#include "myoshell/core/errors.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

struct CacheDir {
  fs::path path;
  CacheDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("myo_basis_cache_test_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~CacheDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

DiscreteShell stripShell() {
  TriMesh m = gridMesh(6.0, 1.5, 12, 3);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V(i, 2) = 0.02 * m.V(i, 0) * m.V(i, 0);
  return DiscreteShell(m.V, m.F, buildEdgeTable(m.F, m.vertexCount()), ShellMaterial{});
}

const std::vector<int> kPins = {0, 13, 26, 39, 1, 14, 27, 40};

void expectBitIdentical(const ModalBasis& a, const ModalBasis& b) {
  EXPECT_EQ(a.fullVertexCount, b.fullVertexCount);
  EXPECT_EQ(a.freeVertices, b.freeVertices);
  EXPECT_EQ(a.solver, b.solver);
  ASSERT_EQ(a.Phi.size(), b.Phi.size());
  ASSERT_EQ(a.Psi.size(), b.Psi.size());
  EXPECT_EQ(std::memcmp(a.Phi.data(), b.Phi.data(), sizeof(double) * a.Phi.size()), 0);
  EXPECT_EQ(std::memcmp(a.Psi.data(), b.Psi.data(), sizeof(double) * a.Psi.size()), 0);
  EXPECT_EQ(std::memcmp(a.lambda.data(), b.lambda.data(), sizeof(double) * a.lambda.size()), 0);
  EXPECT_EQ(std::memcmp(a.freeMass.data(), b.freeMass.data(), sizeof(double) * a.freeMass.size()), 0);
}

std::vector<char> readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeAll(const fs::path& p, const std::vector<char>& data) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

TEST(BasisCache, RoundTripIsBitIdenticalAndSkipsTheSolve) {
  CacheDir dir;
  FileBasisCache cache(dir.path / "cache");
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 8;
  const ModalBasis first = computeModalBasis(shell, kPins, s, &cache);
  EXPECT_FALSE(first.fromCache);
  EXPECT_EQ(cache.stats().misses, 1);
  EXPECT_EQ(cache.stats().stores, 1);
  const fs::path file = cache.pathFor(modalBasisKey(shell, kPins, s));
  EXPECT_TRUE(fs::exists(file));
  // No temporary files are left behind: the entry, and the key's (empty) lock file.
  int files = 0;
  for (const auto& e : fs::directory_iterator(cache.directory()))
    files += e.is_regular_file() && e.path().extension() != ".lock";
  EXPECT_EQ(files, 1);

  const ModalBasis second = computeModalBasis(shell, kPins, s, &cache);
  EXPECT_TRUE(second.fromCache);
  EXPECT_EQ(cache.stats().hits, 1);
  expectBitIdentical(first, second);

  // Another setting is another key: a miss, computed and stored beside the first.
  s.modeCount = 9;
  EXPECT_FALSE(computeModalBasis(shell, kPins, s, &cache).fromCache);
  EXPECT_EQ(cache.stats().misses, 2);
}

TEST(BasisCache, AStoreFailingForTheSystemIsNotFatalAndKeepsItsReason) {
  // A file-size limit (as a full disk): the store fails with EFBIG, the basis is still returned,
  // the reason is kept and no temporary file is left.
  CacheDir dir;
  FileBasisCache cache(dir.path / "cache");
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 8;
  rlimit saved{};
  ::getrlimit(RLIMIT_FSIZE, &saved);
  const sighandler_t oldHandler = ::signal(SIGXFSZ, SIG_IGN);
  rlimit lowered = saved;
  lowered.rlim_cur = 512;
  ::setrlimit(RLIMIT_FSIZE, &lowered);
  const ModalBasis basis = computeModalBasis(shell, kPins, s, &cache);
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, oldHandler);
  EXPECT_EQ(basis.modeCount(), 8);
  EXPECT_EQ(cache.stats().stores, 0);
  const std::string file = cache.pathFor(modalBasisKey(shell, kPins, s)).string();
  EXPECT_EQ(cache.lastStoreError(), file + ": cannot write the basis cache file (File too large)");
  for (const auto& e : fs::directory_iterator(cache.directory()))  // the key's lock file only
    EXPECT_EQ(e.path().extension(), ".lock") << e.path();
}

TEST(BasisCache, CorruptTruncatedAndForeignFilesAreRebuilt) {
  CacheDir dir;
  FileBasisCache cache(dir.path);
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 6;
  const BasisKey key = modalBasisKey(shell, kPins, s);
  const ModalBasis ref = computeModalBasis(shell, kPins, s, &cache);
  const fs::path file = cache.pathFor(key);
  const std::vector<char> good = readAll(file);
  ASSERT_GT(good.size(), 64u);

  auto expectRebuilt = [&](const std::vector<char>& bad, const std::string& reason) {
    writeAll(file, bad);
    const int rejectedBefore = cache.stats().rejected;
    const ModalBasis b = computeModalBasis(shell, kPins, s, &cache);
    EXPECT_FALSE(b.fromCache) << reason;
    EXPECT_EQ(cache.stats().rejected, rejectedBefore + 1) << reason;
    EXPECT_NE(cache.lastRejection().find(reason), std::string::npos) << cache.lastRejection();
    expectBitIdentical(ref, b);
    // The rebuilt basis was written back, and is now trusted.
    EXPECT_TRUE(computeModalBasis(shell, kPins, s, &cache).fromCache) << reason;
  };

  std::vector<char> flipped = good;  // one payload byte inside Φ
  flipped[good.size() / 2] ^= 0x10;
  expectRebuilt(flipped, "checksum mismatch");

  std::vector<char> truncated(good.begin(), good.end() - 17);
  expectRebuilt(truncated, "payload is");

  expectRebuilt(std::vector<char>(good.begin(), good.begin() + 20), "truncated header");

  std::vector<char> longer = good;
  longer.push_back(0);
  expectRebuilt(longer, "payload is");

  std::vector<char> badMagic = good;
  badMagic[0] = 'X';
  expectRebuilt(badMagic, "bad magic");

  std::vector<char> badVersion = good;
  badVersion[8] ^= 0x7f;
  expectRebuilt(badVersion, "format version");

  // A valid file for another key placed under this key's name.
  ModalSettings other = s;
  other.modeCount = 7;
  const BasisKey otherKey = modalBasisKey(shell, kPins, other);
  writeBasisFile(file, otherKey, computeModalBasis(shell, kPins, other));
  expectRebuilt(readAll(file), "another key");

  // Direct reads report why.
  std::string why;
  EXPECT_FALSE(readBasisFile(dir.path / "missing.myobasis", key, &why).has_value());
  EXPECT_EQ(why, "no file");
  EXPECT_TRUE(readBasisFile(file, key, &why).has_value());
}

// Whether another open file description could take `path`'s lock now (it is free).
bool lockIsFree(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);
  return free;
}

TEST(BasisCache, AMissHoldsTheKeysLockUntilTheStore) {
  CacheDir dir;
  FileBasisCache cache(dir.path);
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 6;
  const BasisKey key = modalBasisKey(shell, kPins, s);
  EXPECT_FALSE(cache.load(key).has_value());
  ASSERT_TRUE(fs::exists(cache.lockPathFor(key)));
  EXPECT_FALSE(lockIsFree(cache.lockPathFor(key))) << "another process would wait";
  EXPECT_FALSE(cache.load(key).has_value()) << "the holder asking again does not wait for itself";
  EXPECT_EQ(cache.stats().misses, 2);
  EXPECT_EQ(cache.stats().missedKeys, (std::vector<std::string>{key.hex(), key.hex()}));
  cache.store(key, computeModalBasis(shell, kPins, s));
  EXPECT_TRUE(lockIsFree(cache.lockPathFor(key)));
  EXPECT_TRUE(cache.load(key).has_value());
  EXPECT_TRUE(lockIsFree(cache.lockPathFor(key))) << "a hit takes no lock";
  EXPECT_TRUE(cache.lockNote().empty()) << cache.lockNote();
}

TEST(BasisCache, ACacheDestroyedAfterAMissWithoutStoringReleasesTheLock) {
  CacheDir dir;
  const BasisKey key = KeyHasher().str("never stored").key();
  fs::path lockPath;
  {
    FileBasisCache cache(dir.path);
    EXPECT_FALSE(cache.load(key).has_value());
    lockPath = cache.lockPathFor(key);
    EXPECT_FALSE(lockIsFree(lockPath));
  }
  EXPECT_TRUE(lockIsFree(lockPath));
}

// A child process that loads `key` (a miss: it takes the lock), tells the parent through a pipe,
// then either stores `basis` after `holdMs` or waits to be killed.
pid_t missingChild(const fs::path& dir, const BasisKey& key, const ModalBasis* basis, int holdMs) {
  int fds[2];
  if (::pipe(fds) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    FileBasisCache cache(dir);
    const bool miss = !cache.load(key).has_value();
    const char c = miss ? 'm' : 'h';
    if (::write(fds[1], &c, 1) != 1) ::_exit(3);
    if (!basis) for (;;) ::pause();
    ::usleep(holdMs * 1000);
    cache.store(key, *basis);
    ::_exit(0);
  }
  ::close(fds[1]);
  char c = 0;
  const bool told = ::read(fds[0], &c, 1) == 1 && c == 'm';
  ::close(fds[0]);
  return told ? pid : -1;
}

TEST(BasisCache, AWaiterReadsWhatTheHolderStoredInsteadOfComputingIt) {
  CacheDir dir;
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 6;
  const BasisKey key = modalBasisKey(shell, kPins, s);
  const ModalBasis ref = computeModalBasis(shell, kPins, s);
  const pid_t child = missingChild(dir.path, key, &ref, 1500);
  ASSERT_GT(child, 0);
  FileBasisCache cache(dir.path);
  const ModalBasis b = computeModalBasis(shell, kPins, s, &cache);  // blocks until the child stores
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(b.fromCache);
  EXPECT_EQ(cache.stats().misses, 0);
  EXPECT_EQ(cache.stats().stores, 0);
  EXPECT_EQ(cache.stats().waited + cache.stats().hits, 1);
  expectBitIdentical(ref, b);
}

TEST(BasisCache, AHolderKilledMidComputationHandsTheKeyOnAndItsTemporaryIsRemoved) {
  CacheDir dir;
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 6;
  const BasisKey key = modalBasisKey(shell, kPins, s);
  const pid_t child = missingChild(dir.path, key, nullptr, 0);
  ASSERT_GT(child, 0);
  // What a writer killed mid-write leaves: a half temporary beside the entry.
  const fs::path stale = dir.path / ("." + key.hex() + ".myobasis." + std::to_string(child) + ".0.tmp");
  writeAll(stale, std::vector<char>(100, 'x'));
  EXPECT_FALSE(lockIsFree(dir.path / (key.hex() + ".lock")));
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  FileBasisCache cache(dir.path);
  const ModalBasis b = computeModalBasis(shell, kPins, s, &cache);
  EXPECT_FALSE(b.fromCache);
  EXPECT_EQ(cache.stats().misses, 1);
  EXPECT_EQ(cache.stats().stores, 1);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(readBasisFile(cache.pathFor(key), key).has_value());
}

TEST(BasisCache, TwoCacheObjectsOfOneProcessDoNotWaitForEachOther) {
  CacheDir dir;
  const BasisKey key = KeyHasher().str("one process").key();
  FileBasisCache a(dir.path), b(dir.path);
  EXPECT_FALSE(a.load(key).has_value());
  EXPECT_FALSE(b.load(key).has_value());  // would block forever if it locked
  EXPECT_NE(b.lockNote().find("held by another cache object of this process"), std::string::npos) << b.lockNote();
  EXPECT_TRUE(a.lockNote().empty());
}

TEST(BasisCache, WithoutALockTheCacheStillComputesAndStoresWholeEntries) {
  // The lock file cannot be made (a folder in its place; on a network file system flock itself may
  // fail, EOPNOTSUPP or ENOLCK, and takes the same path): atomic rename alone.
  CacheDir dir;
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 6;
  const BasisKey key = modalBasisKey(shell, kPins, s);
  FileBasisCache cache(dir.path);
  fs::create_directories(cache.lockPathFor(key));
  const ModalBasis b = computeModalBasis(shell, kPins, s, &cache);
  EXPECT_FALSE(b.fromCache);
  EXPECT_NE(cache.lockNote().find("cannot create the lock file " + cache.lockPathFor(key).string()), std::string::npos)
      << cache.lockNote();
  EXPECT_NE(cache.lockNote().find("computing without the lock"), std::string::npos) << cache.lockNote();
  EXPECT_EQ(cache.stats().stores, 1);
  EXPECT_TRUE(computeModalBasis(shell, kPins, s, &cache).fromCache);
}

TEST(BasisCache, AReadOnlyCacheReadsWithoutLocksAndNeverWrites) {
  CacheDir dir;
  const DiscreteShell shell = stripShell();
  ModalSettings s;
  s.modeCount = 6;
  const BasisKey key = modalBasisKey(shell, kPins, s);
  writeBasisFile(dir.path / (key.hex() + ".myobasis"), key, computeModalBasis(shell, kPins, s));
  FileBasisCache cache(dir.path, FileBasisCache::Access::ReadOnly);
  EXPECT_TRUE(cache.readOnly());
  EXPECT_TRUE(computeModalBasis(shell, kPins, s, &cache).fromCache);
  s.modeCount = 7;  // not in the cache: computed, and not kept
  EXPECT_FALSE(computeModalBasis(shell, kPins, s, &cache).fromCache);
  EXPECT_EQ(cache.stats().hits, 1);
  EXPECT_EQ(cache.stats().misses, 1);
  EXPECT_EQ(cache.stats().stores, 0);
  EXPECT_NE(cache.lastStoreError().find("is read-only"), std::string::npos) << cache.lastStoreError();
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir.path)) {
    ++files;
    EXPECT_EQ(e.path().extension(), ".myobasis") << "no lock or temporary file: " << e.path();
  }
  EXPECT_EQ(files, 1);
  EXPECT_THROW(FileBasisCache(dir.path / "missing", FileBasisCache::Access::ReadOnly), InputError);
}

TEST(BasisCache, KeyHashIsStable) {
  // Pinned values: the key format is part of the cache format (bump kModalBasisFormatVersion
  // rather than changing the hash).
  KeyHasher h;
  h.str("abc").pod(int32_t{42});
  const BasisKey k = h.key();
  EXPECT_EQ(k.hex().size(), 32u);
  KeyHasher h2;
  h2.str("abc").pod(int32_t{42});
  EXPECT_EQ(h2.key(), k);
  KeyHasher h3;
  h3.str("abd").pod(int32_t{42});
  EXPECT_NE(h3.key().words[0], k.words[0]);
  EXPECT_NE(h3.key().words[1], k.words[1]);
  EXPECT_EQ(fnv1a64("", 0), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cULL);  // the FNV-1a 64 test vector
}

}  // namespace
}  // namespace myo
