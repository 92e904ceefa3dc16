#include "myoshell/render/contact_sheet.h"

#include <algorithm>

#include "myoshell/core/check.h"
#include "myoshell/render/text.h"

namespace myo {

Image contactSheet(const std::vector<Image>& images, const std::vector<std::string>& captions,
                   const ContactSheetStyle& style) {
  MYO_CHECK(style.columns >= 1, "contact sheet columns " << style.columns);
  MYO_CHECK(captions.empty() || captions.size() == images.size(),
            captions.size() << " captions for " << images.size() << " images");
  if (images.empty()) return Image();
  const int gap = std::max(style.gap, 0);
  int tileW = 0, tileH = 0;
  for (const Image& im : images) tileW = std::max(tileW, im.width), tileH = std::max(tileH, im.height);
  const int captionH = captions.empty() ? 0 : textHeight(style.captionScale) + gap;
  const int cols = std::min<int>(style.columns, static_cast<int>(images.size()));
  const int rows = (static_cast<int>(images.size()) + style.columns - 1) / style.columns;
  const int cellW = tileW, cellH = tileH + captionH;
  Image sheet(cols * cellW + (cols + 1) * gap, rows * cellH + (rows + 1) * gap, style.background);
  for (size_t k = 0; k < images.size(); ++k) {
    const int c = static_cast<int>(k) % style.columns, r = static_cast<int>(k) / style.columns;
    const int x = gap + c * (cellW + gap), y = gap + r * (cellH + gap);
    const Image& im = images[k];
    blit(sheet, im, x + (tileW - im.width) / 2, y + (tileH - im.height) / 2);
    if (!captions.empty() && !captions[k].empty())
      drawText(sheet, x + (cellW - textWidth(captions[k], style.captionScale)) / 2,
               y + tileH + gap / 2, captions[k], style.textColor, style.captionScale);
  }
  return sheet;
}

Image withCaption(const Image& image, const std::string& caption, int scale, const Rgb& background,
                  const Rgb& textColor) {
  const int pad = 2 * std::max(scale, 1) + 2;
  const int w = std::max(image.width, textWidth(caption, scale) + 2 * pad);
  Image out(w, image.height + textHeight(scale) + 2 * pad, background);
  blit(out, image, (w - image.width) / 2, 0);
  drawText(out, (w - textWidth(caption, scale)) / 2, image.height + pad, caption, textColor, scale);
  return out;
}

}  // namespace myo
