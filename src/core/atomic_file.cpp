#include "myoshell/core/atomic_file.h"

#include <filesystem>
#include <fstream>

#include "myoshell/core/errors.h"

namespace myo {

void writeFileAtomically(const std::string& path, const std::string& bytes, const std::string& what) {
  namespace fs = std::filesystem;
  const fs::path tmp = path + ".tmp";
  bool written = false;
  {
    std::ofstream out(tmp, std::ios::binary);
    out << bytes;
    written = static_cast<bool>(out);
  }
  std::error_code ec;
  if (written) fs::rename(tmp, path, ec);
  if (!written || ec) {
    fs::remove(tmp, ec);
    throw InputError(what, path);
  }
}

}  // namespace myo
