#include "myoshell/render/png.h"

#include <stb_image_write.h>  // declarations only; libstb provides the implementation

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "myoshell/core/atomic_file.h"
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
  writeFileAtomically(
      path,
      [&](std::FILE* out) {
        // stb encodes in memory and hands over the bytes (the same bytes stbi_write_png writes).
        auto put = [](void* file, void* data, int size) {
          std::fwrite(data, 1, static_cast<size_t>(size), static_cast<std::FILE*>(file));
        };
        if (!stbi_write_png_to_func(put, out, image.width, image.height, 3, image.pixels.data(), image.width * 3))
          throw InputError("cannot write picture (PNG encoding failed)", path);
      },
      "cannot write picture");
}

}  // namespace myo
