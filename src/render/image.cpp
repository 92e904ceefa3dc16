#include "myoshell/render/image.h"

#include <algorithm>

#include "myoshell/core/check.h"

namespace myo {
namespace {
std::uint8_t toByte(double v) {
  return static_cast<std::uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5);
}
}  // namespace

Image::Image(int w, int h, const Rgb& background) : width(w), height(h) {
  MYO_CHECK(w >= 0 && h >= 0, "image size " << w << "×" << h);
  pixels.resize(static_cast<size_t>(w) * h * 3);
  const std::uint8_t r = toByte(background[0]), g = toByte(background[1]), b = toByte(background[2]);
  for (size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = r;
    pixels[i + 1] = g;
    pixels[i + 2] = b;
  }
}

Rgb Image::at(int x, int y) const {
  MYO_CHECK(contains(x, y), "pixel (" << x << ", " << y << ") outside " << width << "×" << height);
  const std::uint8_t* p = &pixels[(static_cast<size_t>(y) * width + x) * 3];
  return Rgb(p[0], p[1], p[2]) / 255.0;
}

void Image::set(int x, int y, const Rgb& c) {
  if (!contains(x, y)) return;
  std::uint8_t* p = &pixels[(static_cast<size_t>(y) * width + x) * 3];
  for (int k = 0; k < 3; ++k) p[k] = toByte(c[k]);
}

void Image::blend(int x, int y, const Rgb& c, double alpha) {
  if (!contains(x, y)) return;
  alpha = std::clamp(alpha, 0.0, 1.0);
  set(x, y, (1.0 - alpha) * at(x, y) + alpha * c);
}

void Image::fillRect(int x, int y, int w, int h, const Rgb& c) {
  const int x0 = std::max(0, x), y0 = std::max(0, y);
  const int x1 = std::min(width, x + w), y1 = std::min(height, y + h);
  for (int j = y0; j < y1; ++j)
    for (int i = x0; i < x1; ++i) set(i, j, c);
}

void blit(Image& dst, const Image& src, int x, int y) {
  for (int j = 0; j < src.height; ++j) {
    const int ty = y + j;
    if (ty < 0 || ty >= dst.height) continue;
    for (int i = 0; i < src.width; ++i) {
      const int tx = x + i;
      if (tx < 0 || tx >= dst.width) continue;
      const size_t s = (static_cast<size_t>(j) * src.width + i) * 3;
      const size_t d = (static_cast<size_t>(ty) * dst.width + tx) * 3;
      for (int k = 0; k < 3; ++k) dst.pixels[d + k] = src.pixels[s + k];
    }
  }
}

Image downsample(const Image& image, int factor) {
  MYO_CHECK(factor >= 1, "downsample factor " << factor);
  if (factor == 1) return image;
  Image out(image.width / factor, image.height / factor);
  const int n = factor * factor;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int k = 0; k < 3; ++k) {
        int sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i)
            sum += image.pixels[(static_cast<size_t>(y * factor + j) * image.width + (x * factor + i)) * 3 + k];
        out.pixels[(static_cast<size_t>(y) * out.width + x) * 3 + k] =
            static_cast<std::uint8_t>((sum + n / 2) / n);
      }
  return out;
}

}  // namespace myo
