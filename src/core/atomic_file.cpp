#include "myoshell/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "myoshell/core/errors.h"

namespace myo {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& reason, const std::string& path) {
  throw InputError(what + " (" + reason + ")", path);
}

}  // namespace

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
    fail(what, "cannot rename the temporary file into place: " + ec.message(), target);
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::FILE*)>& write,
                         const std::string& what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail(what, "it is a folder", path);
  const std::string tmp = temporaryPathBeside(path);
  std::FILE* out = std::fopen(tmp.c_str(), "wb");
  if (!out) fail(what, std::strerror(errno), path);
  try {
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
    fail(what, std::strerror(error), path);
  }
  renameIntoPlace(tmp, path, what);
}

void writeFileAtomically(const std::string& path, std::string_view bytes, const std::string& what) {
  writeFileAtomically(
      path, [&](std::FILE* out) { std::fwrite(bytes.data(), 1, bytes.size(), out); }, what);
}

}  // namespace myo
