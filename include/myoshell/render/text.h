// Text with a tiny built-in 5×7 bitmap font (ASCII letters, digits and . , : ; - + = / % ( ) ' _ !
// ? *; any other character draws as '?'), for captions and colour-bar labels. Each glyph cell is
// 6×8 font pixels (one column and one row of spacing), magnified by an integer `scale`.
#pragma once

#include <string_view>

#include "myoshell/render/image.h"

namespace myo {

// Width and height in image pixels of `text` on one line at `scale` ≥ 1.
int textWidth(std::string_view text, int scale = 1);
int textHeight(int scale = 1);

// Draws `text` with its top-left corner at pixel (x, y), clipped to the image; '\n' starts a new
// line. Returns the width in pixels of the longest line.
int drawText(Image& image, int x, int y, std::string_view text, const Rgb& color = Rgb::Zero(),
             int scale = 1);

}  // namespace myo
