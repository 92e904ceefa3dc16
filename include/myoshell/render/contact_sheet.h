// Contact sheets: several pictures tiled into one, with optional captions.
#pragma once

#include <string>
#include <vector>

#include "myoshell/render/image.h"

namespace myo {

struct ContactSheetStyle {
  int columns = 3;               // tiles per row, ≥ 1
  int gap = 8;                   // pixels around and between tiles
  int captionScale = 2;          // bitmap-font magnification of captions (text.h)
  Rgb background = Rgb(1, 1, 1);
  Rgb textColor = Rgb::Zero();
};

// Tiles `images` row by row into cells of the largest tile's size (each tile centred in its cell).
// With `captions` (empty, or one per image; "" for none) every cell gets a caption strip below
// its tile of textHeight(captionScale) + gap pixels, the caption centred in it.
// Size: width = c·cellWidth + (c + 1)·gap with c = min(columns, count), height = rows·cellHeight +
// (rows + 1)·gap with rows = ⌈count/columns⌉. No images: an empty (0×0) image.
Image contactSheet(const std::vector<Image>& images, const std::vector<std::string>& captions = {},
                   const ContactSheetStyle& style = {});

// Appends a caption strip under `image` (its text centred, `scale` font magnification).
Image withCaption(const Image& image, const std::string& caption, int scale = 2,
                  const Rgb& background = Rgb(1, 1, 1), const Rgb& textColor = Rgb::Zero());

}  // namespace myo
