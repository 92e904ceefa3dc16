#include "myoshell/render/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "myoshell/core/check.h"
#include "myoshell/render/text.h"

namespace myo {
namespace {

using Stops = std::array<std::uint32_t, 11>;  // 0xRRGGBB at 0, 0.1, …, 1

// matplotlib viridis (van der Walt & Smith) sampled at 0, 0.1, …, 1.
constexpr Stops kViridis = {0x440154, 0x482475, 0x414487, 0x355f8d, 0x2a788e, 0x21918c,
                            0x22a884, 0x44bf70, 0x7ad151, 0xbddf26, 0xfde725};
// ColorBrewer RdBu, 11 classes, from blue to red.
constexpr Stops kBlueWhiteRed = {0x053061, 0x2166ac, 0x4393c3, 0x92c5de, 0xd1e5f0, 0xf7f7f7,
                                 0xfddbc7, 0xf4a582, 0xd6604d, 0xb2182b, 0x67001f};

Rgb hex(std::uint32_t c) { return Rgb((c >> 16) & 0xff, (c >> 8) & 0xff, c & 0xff) / 255.0; }

}  // namespace

Rgb colormap(double value, ColorMap map) {
  if (std::isnan(value)) return Rgb::Constant(0.5);
  const Stops& s = map == ColorMap::viridis ? kViridis : kBlueWhiteRed;
  const double t = std::clamp(value, 0.0, 1.0) * (s.size() - 1);
  const int i = std::min(static_cast<int>(t), static_cast<int>(s.size()) - 2);
  const double w = t - i;
  return (1 - w) * hex(s[i]) + w * hex(s[i + 1]);
}

MatX3 scalarColors(const VecX& values, double min, double max, ColorMap map) {
  MYO_CHECK(min < max, "colour range [" << min << ", " << max << "]");
  MatX3 C(values.size(), 3);
  for (Eigen::Index i = 0; i < values.size(); ++i)
    C.row(i) = colormap((values[i] - min) / (max - min), map).transpose();
  return C;
}

void drawColorBar(Image& image, const ColorBar& bar) {
  const int w = std::max(bar.width, 2), h = std::max(bar.height, 1);
  for (int i = 0; i < w; ++i)
    image.fillRect(bar.x + i, bar.y, 1, h, colormap(static_cast<double>(i) / (w - 1), bar.map));
  // Frame.
  image.fillRect(bar.x - 1, bar.y - 1, w + 2, 1, bar.textColor);
  image.fillRect(bar.x - 1, bar.y + h, w + 2, 1, bar.textColor);
  image.fillRect(bar.x - 1, bar.y, 1, h, bar.textColor);
  image.fillRect(bar.x + w, bar.y, 1, h, bar.textColor);
  char lo[32], hi[32];
  std::snprintf(lo, sizeof lo, "%.3g", bar.min);
  std::snprintf(hi, sizeof hi, "%.3g", bar.max);
  const int ty = bar.y + h + 2 + bar.textScale;
  drawText(image, bar.x, ty, lo, bar.textColor, bar.textScale);
  drawText(image, bar.x + w - textWidth(hi, bar.textScale), ty, hi, bar.textColor, bar.textScale);
  if (!bar.label.empty())
    drawText(image, bar.x + (w - textWidth(bar.label, bar.textScale)) / 2, ty, bar.label,
             bar.textColor, bar.textScale);
}

}  // namespace myo
