#include "myoshell/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"

namespace myo {

namespace fs = std::filesystem;

namespace {

// The target itself is unusable (a folder, a missing folder, no permission): the user's input.
[[noreturn]] void fail(const std::string& what, const std::string& reason, const std::string& path) {
  throw InputError(what + " (" + reason + ")", path);
}

// `error` (an errno) while making the file: the system's failure or the path's fault, as
// isRunTimeIoFailure says.
[[noreturn]] void failToCreate(const std::string& what, int error, const std::string& path) {
  if (isRunTimeIoFailure(error)) throw IoError(what + " (" + std::strerror(error) + ")", path);
  fail(what, std::strerror(error), path);
}

// A failure once the temporary file is open (writing, flushing, syncing, closing, renaming): the
// path was usable, so it is the system's (a full disk, a file-size limit, an I/O error).
[[noreturn]] void failWhileWriting(const std::string& what, const std::string& reason, const std::string& path) {
  throw IoError(what + " (" + reason + ")", path);
}

}  // namespace

bool isRunTimeIoFailure(int error) {
  switch (error) {
    case ENOSPC: case EDQUOT: case EFBIG: case EIO: case EMFILE: case ENFILE: case ENOMEM: return true;
    default: return false;
  }
}

std::string temporaryPathBeside(const std::string& target, const std::string& suffix) {
  // pid and a per-process counter: unique among threads and among processes writing one folder
  // (several runs may share a basis cache).
  static std::atomic<unsigned> counter{0};
  const fs::path p(target);
  std::ostringstream name;  // (ostringstream: gcc 12 warns falsely on chained string appends)
  name << '.' << p.filename().string() << '.' << ::getpid() << '.' << counter++ << ".tmp" << suffix;
  return (p.parent_path() / name.str()).string();
}

void removeQuietly(const std::string& path) noexcept {
  try {
    std::error_code ec;
    fs::remove(path, ec);
  } catch (...) {  // (fs::path construction may allocate)
  }
}

void renameIntoPlace(const std::string& tmp, const std::string& target, const std::string& what) {
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    removeQuietly(tmp);
    failWhileWriting(what, "cannot rename the temporary file into place: " + ec.message(), target);
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::FILE*)>& write,
                         const std::string& what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail(what, "it is a folder", path);
  const std::string tmp = temporaryPathBeside(path);
  std::FILE* out = std::fopen(tmp.c_str(), "wb");
  if (!out) failToCreate(what, errno, path);
  try {
    errno = 0;  // so that a stream error below reports the write's own errno
    write(out);
  } catch (...) {
    std::fclose(out);
    removeQuietly(tmp);
    throw;
  }
  // The first failure's errno: a stream error, the flush of the buffer, the sync to disk, close.
  int error = 0;
  if (std::ferror(out)) error = errno ? errno : EIO;
  if (!error && std::fflush(out) != 0) error = errno;
  if (!error && ::fsync(::fileno(out)) != 0) error = errno;
  if (std::fclose(out) != 0 && !error) error = errno;
  if (error) {
    removeQuietly(tmp);
    failWhileWriting(what, std::strerror(error), path);
  }
  renameIntoPlace(tmp, path, what);
}

void writeFileAtomically(const std::string& path, std::string_view bytes, const std::string& what) {
  writeFileAtomically(
      path, [&](std::FILE* out) { std::fwrite(bytes.data(), 1, bytes.size(), out); }, what);
}

}  // namespace myo
