#include "myoshell/core/whole_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "myoshell/core/errors.h"

namespace myo {

std::string readWholeFile(const std::string& path, const std::string& cannotOpen) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError("cannot open: is a directory", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(cannotOpen.empty() ? std::string("cannot open (") + std::strerror(errno) + ")" : cannotOpen, path);
  std::ostringstream os;
  os << in.rdbuf();
  if (in.bad()) throw InputError("cannot read", path);
  return os.str();
}

std::optional<std::string> tryReadWholeFile(const std::string& path) {
  try {
    return readWholeFile(path);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace myo
