// Colour maps for scalar fields on meshes (displacement magnitude, activation, error…), and a
// colour bar with min/max labels.
#pragma once

#include <string>

#include "myoshell/core/types.h"
#include "myoshell/render/image.h"

namespace myo {

enum class ColorMap {
  viridis,       // perceptual, dark purple → yellow (matplotlib's, its 11 published samples)
  blueWhiteRed,  // diverging, dark blue → near-white → dark red (ColorBrewer RdBu, 11 classes)
};

// The colour of `value` in [0, 1] (clamped; NaN gives mid grey), piecewise linear between the
// map's control points.
Rgb colormap(double value, ColorMap map = ColorMap::viridis);

// Per-vertex colours (n×3) of `values` (n) mapped linearly from [min, max] to [0, 1]; min < max.
MatX3 scalarColors(const VecX& values, double min, double max, ColorMap map = ColorMap::viridis);

struct ColorBar {
  int x = 10, y = 10;             // top-left corner of the bar, pixels
  int width = 200, height = 12;   // pixels; the bar runs from min (left) to max (right)
  double min = 0, max = 1;        // values at the two ends, printed under the bar ("%.3g")
  ColorMap map = ColorMap::viridis;
  std::string label;              // printed centred under the bar, e.g. "displacement cm"
  int textScale = 1;              // bitmap font magnification
  Rgb textColor = Rgb::Zero();
};
// Draws the bar with a 1-pixel frame in textColor and its labels below it.
void drawColorBar(Image& image, const ColorBar& bar);

}  // namespace myo
