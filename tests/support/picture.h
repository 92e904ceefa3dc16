// PNG pictures read back in tests (Debian's stb_image), and a pixel-difference count.
#pragma once

#include <stb/stb_image.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace myo::test {

struct Picture {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // width·height·3 bytes, row 0 at the top
  const unsigned char* at(int x, int y) const { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
};

// The picture at `path`, or an empty one (0×0) when it cannot be read.
inline Picture readPicture(const std::filesystem::path& path) {
  Picture p;
  int channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &p.width, &p.height, &channels, 3);
  if (data) {
    p.rgb.assign(data, data + 3 * static_cast<size_t>(p.width) * p.height);
    stbi_image_free(data);
  }
  return p;
}

// Pixels of the box [x0, x1) × [y0, y1) whose colour differs by more than `levels` in a channel.
inline int differingPixels(const Picture& a, const Picture& b, int x0, int y0, int x1, int y1, int levels = 24) {
  int count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(a.at(x, y)[c] - b.at(x, y)[c]) > levels) {
          ++count;
          break;
        }
  return count;
}

}  // namespace myo::test
