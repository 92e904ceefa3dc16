// PNG output of an `Image` (8-bit RGB, deflate-compressed), written with Debian's stb_image_write.
#pragma once

#include <string>

#include "myoshell/render/image.h"

namespace myo {

// Writes `image` to `path` as PNG. The bytes go to a temporary file next to `path` that is then
// renamed, so a reader never sees a half-written picture. Throws InputError naming `path` when it
// cannot be written (a folder, a missing parent folder, no permission); no file is left behind.
// The image must be non-empty.
void writePng(const std::string& path, const Image& image);

}  // namespace myo
