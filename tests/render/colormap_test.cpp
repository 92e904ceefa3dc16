// Colour maps, scalar colours and the colour bar.
#include <gtest/gtest.h>

#include "myoshell/render/colormap.h"
#include "myoshell/render/text.h"

namespace myo {
namespace {

double luma(const Rgb& c) { return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z(); }

TEST(Colormap, ViridisEndpointsAndMonotonicLuminance) {
  EXPECT_TRUE(colormap(0.0).isApprox(Rgb(0x44, 0x01, 0x54) / 255.0));
  EXPECT_TRUE(colormap(1.0).isApprox(Rgb(0xfd, 0xe7, 0x25) / 255.0));
  EXPECT_TRUE(colormap(-3.0).isApprox(colormap(0.0)));  // clamped
  EXPECT_TRUE(colormap(7.0).isApprox(colormap(1.0)));
  double previous = -1;
  for (int i = 0; i <= 200; ++i) {
    const double l = luma(colormap(i / 200.0));
    EXPECT_GT(l, previous) << "at " << i / 200.0;
    previous = l;
  }
}

TEST(Colormap, BlueWhiteRedIsDiverging) {
  const Rgb lo = colormap(0.0, ColorMap::blueWhiteRed), mid = colormap(0.5, ColorMap::blueWhiteRed),
            hi = colormap(1.0, ColorMap::blueWhiteRed);
  EXPECT_GT(lo.z(), 2 * lo.x());
  EXPECT_GT(hi.x(), 2 * hi.z());
  EXPECT_GT(mid.minCoeff(), 0.9);
  EXPECT_GT(luma(mid), luma(colormap(0.25, ColorMap::blueWhiteRed)));
  EXPECT_GT(luma(mid), luma(colormap(0.75, ColorMap::blueWhiteRed)));
}

TEST(Colormap, ScalarColorsMapTheRange) {
  VecX v(3);
  v << 2.0, 4.0, 3.0;
  const MatX3 C = scalarColors(v, 2.0, 4.0);
  ASSERT_EQ(C.rows(), 3);
  EXPECT_TRUE(C.row(0).transpose().isApprox(colormap(0.0)));
  EXPECT_TRUE(C.row(1).transpose().isApprox(colormap(1.0)));
  EXPECT_TRUE(C.row(2).transpose().isApprox(colormap(0.5)));
}

TEST(ColorBar, DrawsTheRampAndItsLabels) {
  Image im(200, 60, Rgb(1, 1, 1));
  ColorBar bar;
  bar.x = 20, bar.y = 10, bar.width = 160, bar.height = 10;
  bar.min = -1.5, bar.max = 2;
  bar.label = "cm";
  drawColorBar(im, bar);
  EXPECT_LT((im.at(20, 15) - colormap(0.0)).norm(), 0.01);
  EXPECT_LT((im.at(179, 15) - colormap(1.0)).norm(), 0.01);
  // Labels under the bar: some dark pixels at the left, the right and the middle.
  auto inkIn = [&](int x0, int x1) {
    int n = 0;
    for (int y = 22; y < 35; ++y)
      for (int x = x0; x < x1; ++x) n += im.at(x, y).sum() < 0.5;
    return n;
  };
  EXPECT_GT(inkIn(20, 45), 10);    // "-1.5"
  EXPECT_GT(inkIn(170, 181), 5);   // "2"
  EXPECT_GT(inkIn(90, 110), 5);    // "cm"
  EXPECT_EQ(inkIn(50, 85), 0);
}

TEST(Text, GlyphsAndWidths) {
  EXPECT_EQ(textWidth("", 2), 0);
  EXPECT_EQ(textWidth("ab", 1), 11);
  EXPECT_EQ(textWidth("ab\nxyz", 2), 34);
  EXPECT_EQ(textHeight(3), 21);
  Image im(40, 10, Rgb(1, 1, 1));
  EXPECT_EQ(drawText(im, 1, 1, "-", Rgb::Zero(), 1), 5);
  for (int x = 1; x < 6; ++x) EXPECT_EQ(im.at(x, 4), Rgb::Zero());  // '-' is row 3 of 7
  EXPECT_EQ(im.at(1, 1), Rgb(1, 1, 1));
  // Characters without a glyph draw as '?'.
  Image a(10, 10, Rgb(1, 1, 1)), b(10, 10, Rgb(1, 1, 1));
  drawText(a, 0, 0, "~");
  drawText(b, 0, 0, "?");
  EXPECT_EQ(a.pixels, b.pixels);
}

}  // namespace
}  // namespace myo
