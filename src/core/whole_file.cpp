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
  // A regular file is read in one go into a buffer of its size (a basis cache file is tens of MB:
  // no stream copies); whatever else there is (a pipe, a file that grew meanwhile) the stream's way.
  std::string data;
  if (std::filesystem::is_regular_file(path, ec)) {
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size > 0) {
      data.resize(static_cast<size_t>(size));
      in.read(data.data(), static_cast<std::streamsize>(size));
      data.resize(static_cast<size_t>(in.gcount()));
    }
  }
  if (in) {
    std::ostringstream os;
    os << in.rdbuf();
    data += os.str();
  }
  if (in.bad()) throw InputError("cannot read", path);
  return data;
}

std::optional<std::string> tryReadWholeFile(const std::string& path) {
  try {
    return readWholeFile(path);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace myo
