#include <fstream>
#include <system_error>

#include "export_file.h"
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo::detail {

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path tmp = path.string() + ".tmp";
  bool ok = false;
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (f) {
      f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      f.close();
      ok = static_cast<bool>(f);
    }
  }
  std::error_code ec;
  if (ok) fs::rename(tmp, path, ec);
  if (!ok || ec) {
    fs::remove(tmp, ec);
    throw InputError("cannot write file", path.string());
  }
}

void checkFrames(const AnimationFrames& frames) {
  MYO_CHECK(!frames.positions.empty(), "an animation export needs at least one frame");
  MYO_CHECK(frames.rest.rows() > 0, "an animation export needs a rest mesh");
  for (size_t k = 0; k < frames.positions.size(); ++k)
    MYO_CHECK(frames.positions[k].rows() == frames.rest.rows(),
              "frame " << k << " has " << frames.positions[k].rows() << " vertices, the rest mesh "
                       << frames.rest.rows());
}

}  // namespace myo::detail
