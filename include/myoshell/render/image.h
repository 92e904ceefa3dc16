// A picture in memory: width × height pixels of 8-bit RGB, row 0 at the top. Colours passed to the
// render layer are `Rgb` triples in [0, 1] (sRGB-encoded, like the bytes they become).
#pragma once

#include <cstdint>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

using Rgb = Vec3;  // red, green, blue in [0, 1]; values outside are clamped when stored

struct Image {
  int width = 0;   // pixels
  int height = 0;  // pixels
  std::vector<std::uint8_t> pixels;  // width·height·3 bytes, row-major from the top-left, RGB

  Image() = default;
  // A width × height image filled with `background`. Both sizes must be ≥ 0.
  Image(int width, int height, const Rgb& background = Rgb(1, 1, 1));

  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  // Pixel (x, y) as [0, 1] components; (x, y) must be inside.
  Rgb at(int x, int y) const;
  // Stores `c` at (x, y), clamped to [0, 1]; does nothing outside the image.
  void set(int x, int y, const Rgb& c);
  // Blends: pixel = (1 − alpha)·pixel + alpha·c, alpha in [0, 1]; does nothing outside.
  void blend(int x, int y, const Rgb& c, double alpha);
  // Fills the rectangle [x, x + w) × [y, y + h), clipped to the image.
  void fillRect(int x, int y, int w, int h, const Rgb& c);
};

// Copies `src` into `dst` with its top-left corner at (x, y), clipped to `dst`.
void blit(Image& dst, const Image& src, int x, int y);

// Box-filter downsampling by an integer `factor` ≥ 1 (supersampled rendering: draw at factor× the
// size, then downsample). The result is ⌊width/factor⌋ × ⌊height/factor⌋.
Image downsample(const Image& image, int factor);

}  // namespace myo
