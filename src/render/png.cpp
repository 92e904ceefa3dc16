#include "myoshell/render/png.h"

#include <stb_image_write.h>  // declarations only; libstb provides the implementation
#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo {

void writePng(const std::string& path, const Image& image) {
  namespace fs = std::filesystem;
  MYO_CHECK(image.width > 0 && image.height > 0,
            "cannot write an empty image (" << image.width << "×" << image.height << ")");
  MYO_CHECK_EQ(image.pixels.size(), static_cast<size_t>(image.width) * image.height * 3);
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError("cannot write picture: it is a folder", path);
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  const int ok = stbi_write_png(tmp.c_str(), image.width, image.height, 3, image.pixels.data(),
                                image.width * 3);
  if (!ok) {
    fs::remove(tmp, ec);
    throw InputError("cannot write picture", path);
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw InputError("cannot write picture (" + why + ")", path);
  }
}

}  // namespace myo
