// The one atomic writer and the one whole-file reader: exact bytes, exact errors, nothing left
// behind on failure.
#include "myoshell/core/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"
#include "myoshell/core/whole_file.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / (std::string("myo_atomic_") + info->name() + "_" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  int entries() const { return static_cast<int>(std::distance(fs::directory_iterator(path_), fs::directory_iterator())); }

 private:
  fs::path path_;
};

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AtomicFile, WritesExactBytesAndReplacesTheTarget) {
  TempDir dir;
  const std::string path = (dir / "a.bin").string();
  const std::string bytes("one\0two\n\xff", 9);
  writeFileAtomically(path, bytes);
  EXPECT_EQ(readWholeFile(path), bytes);
  writeFileAtomically(path, [](std::FILE* out) { std::fputs("replaced", out); });
  EXPECT_EQ(readWholeFile(path), "replaced");
  EXPECT_EQ(dir.entries(), 1) << "a temporary file was left behind";
}

TEST(AtomicFile, FailureNamesThePathAndLeavesNothing) {
  TempDir dir;
  const std::string missing = (dir / "no_folder" / "a.txt").string();
  EXPECT_EQ(errorOf([&] { writeFileAtomically(missing, "x", "cannot write thing"); }),
            missing + ": cannot write thing (No such file or directory)");
  fs::create_directory(dir / "sub");
  EXPECT_EQ(errorOf([&] { writeFileAtomically((dir / "sub").string(), "x"); }),
            (dir / "sub").string() + ": cannot write file (it is a folder)");
  // A writer that throws: the exception passes through, the old file stays whole, no temporary.
  const std::string path = (dir / "keep.txt").string();
  writeFileAtomically(path, "old");
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::FILE* out) {
                                     std::fputs("half", out);
                                     throw std::runtime_error("stop");
                                   }),
               std::runtime_error);
  EXPECT_EQ(readWholeFile(path), "old");
  EXPECT_EQ(dir.entries(), 2);  // sub, keep.txt
}

// RLIMIT_FSIZE lowered (soft limit only, restored on leaving) with SIGXFSZ ignored: a write past
// the limit fails with EFBIG, as on a full disk, instead of killing the process.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    oldHandler_ = ::signal(SIGXFSZ, SIG_IGN);
    rlimit lowered = saved_;
    lowered.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &lowered);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    ::signal(SIGXFSZ, oldHandler_);
  }

 private:
  rlimit saved_{};
  sighandler_t oldHandler_ = SIG_DFL;
};

TEST(AtomicFile, ASystemFailureIsAnIoErrorNamingThePathAndTheReason) {
  TempDir dir;
  const std::string path = (dir / "big.bin").string();
  writeFileAtomically(path, "old");
  {
    FileSizeLimit limit(1000);
    try {
      writeFileAtomically(path, std::string(100000, 'x'), "cannot write thing");
      FAIL() << "expected IoError";
    } catch (const IoError& e) {  // not an InputError: the CLI exits 1
      EXPECT_EQ(std::string(e.what()), path + ": cannot write thing (File too large)");
      EXPECT_EQ(e.path(), path);
    }
  }
  EXPECT_EQ(readWholeFile(path), "old");  // the old file whole, no temporary
  EXPECT_EQ(dir.entries(), 1);
  EXPECT_TRUE(isRunTimeIoFailure(ENOSPC));
  EXPECT_TRUE(isRunTimeIoFailure(EFBIG));
  EXPECT_FALSE(isRunTimeIoFailure(ENOENT));
  EXPECT_FALSE(isRunTimeIoFailure(EACCES));
}

TEST(AtomicFile, TemporaryNamesAreHiddenUniqueAndBesideTheTarget) {
  const std::string a = temporaryPathBeside("/x/y/out.mp4", ".mp4"), b = temporaryPathBeside("/x/y/out.mp4", ".mp4");
  EXPECT_NE(a, b);
  EXPECT_EQ(fs::path(a).parent_path(), fs::path("/x/y"));
  EXPECT_THAT(fs::path(a).filename().string(), ::testing::StartsWith(".out.mp4." + std::to_string(::getpid()) + "."));
  EXPECT_THAT(a, ::testing::EndsWith(".tmp.mp4"));
}

TEST(WholeFile, ReadsBytesAndNamesTheFault) {
  TempDir dir;
  const std::string path = (dir / "f.txt").string();
  std::ofstream(path, std::ios::binary) << std::string("a\0b", 3);
  EXPECT_EQ(readWholeFile(path), std::string("a\0b", 3));
  const std::string missing = (dir / "nope.txt").string();
  EXPECT_EQ(errorOf([&] { readWholeFile(missing); }), missing + ": cannot open (No such file or directory)");
  EXPECT_EQ(errorOf([&] { readWholeFile(missing, "cannot open scene file"); }), missing + ": cannot open scene file");
  EXPECT_THAT(errorOf([&] { readWholeFile((dir / "").string()); }), HasSubstr("cannot open: is a directory"));
  EXPECT_FALSE(tryReadWholeFile(missing).has_value());
  EXPECT_EQ(tryReadWholeFile(path).value_or(""), std::string("a\0b", 3));
}

}  // namespace
}  // namespace myo
