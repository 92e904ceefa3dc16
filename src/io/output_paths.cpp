#include "myoshell/io/output_paths.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "myoshell/core/errors.h"

namespace myo {

namespace fs = std::filesystem;

namespace {

// Why files cannot be added to `dir` (an existing folder), or "" when they can. access() asks the
// kernel with the process's own rights, so a read-only file system counts too.
std::string notWritable(const fs::path& dir) {
  if (::access(dir.c_str(), W_OK | X_OK) == 0) return {};
  return std::strerror(errno);
}

}  // namespace

void checkOutputFile(const std::string& path, const std::string& option, const std::string& what) {
  if (path.empty()) return;
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError(option + ": is a folder; give the " + what + " to write", path);
  if (!p.has_filename()) throw InputError(option + ": names a folder (it ends in '/'); give the " + what + " to write", path);
  if (fs::exists(p, ec) && !fs::is_regular_file(p, ec))
    throw InputError(option + ": exists and is not a regular file; give the " + what + " to write", path);
  const fs::path parent = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::exists(parent, ec)) throw InputError(option + ": no such folder '" + parent.string() + "'");
  if (!fs::is_directory(parent, ec)) throw InputError(option + ": '" + parent.string() + "' is not a folder", path);
  if (const std::string why = notWritable(parent); !why.empty())
    throw InputError(option + ": cannot write into the folder '" + parent.string() + "' (" + why + ")", path);
}

void checkOutputFolder(const std::string& path, const std::string& option) {
  if (path.empty()) throw InputError(option + ": an empty folder name");
  const fs::path p(path);
  std::error_code ec;
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) throw InputError(option + ": output path exists and is not a folder", path);
    if (const std::string why = notWritable(p); !why.empty())
      throw InputError(option + ": cannot write into the output folder (" + why + ")", path);
    return;
  }
  // The nearest existing parent is where the missing folders will be made.
  fs::path parent = fs::absolute(p, ec).lexically_normal();
  while (parent.has_relative_path() && !fs::exists(parent, ec)) parent = parent.parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(option + ": cannot create the output folder: '" + parent.string() + "' is not a folder", path);
  if (const std::string why = notWritable(parent); !why.empty())
    throw InputError(option + ": cannot create the output folder in '" + parent.string() + "' (" + why + ")", path);
}

}  // namespace myo
