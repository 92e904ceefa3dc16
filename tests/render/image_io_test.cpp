// Images: writePng, downsampling, contact sheets, captions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "myoshell/core/errors.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/png.h"
#include "myoshell/render/text.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_render_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::uint32_t bigEndian(const std::string& s, size_t at) {
  std::uint32_t v = 0;
  for (size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

TEST(WritePng, WritesASignedPngOfTheRightSize) {
  const fs::path dir = scratch("png");
  Image im(37, 21, Rgb(0.2, 0.4, 0.6));
  im.set(3, 4, Rgb(1, 0, 0));
  const fs::path path = dir / "picture.png";
  writePng(path.string(), im);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(bigEndian(bytes, 16), 37u);
  EXPECT_EQ(bigEndian(bytes, 20), 21u);
  EXPECT_EQ(bytes[24], 8);  // bit depth
  EXPECT_EQ(bytes[25], 2);  // colour type: RGB
  EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND");
  // Only the picture is left in the folder (the temporary file was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(WritePng, AFolderOrMissingFolderIsAnInputErrorAndLeavesNoFile) {
  const fs::path dir = scratch("png_errors");
  const fs::path folder = dir / "sub";
  fs::create_directories(folder);
  const Image im(4, 4);
  try {
    writePng(folder.string(), im);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), folder.string());
  }
  EXPECT_THROW(writePng((dir / "missing" / "x.png").string(), im), InputError);
  EXPECT_TRUE(fs::is_directory(folder));
  EXPECT_TRUE(fs::is_empty(folder));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // just sub/
}

TEST(Image, DownsampleAveragesBlocks) {
  Image im(4, 2, Rgb::Zero());
  im.set(0, 0, Rgb(1, 1, 1));
  im.set(1, 1, Rgb(1, 1, 1));
  const Image small = downsample(im, 2);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_NEAR(small.at(0, 0).x(), 0.5, 0.003);
  EXPECT_EQ(small.at(1, 0), Rgb::Zero());
}

TEST(ContactSheet, TilesImagesInRowsWithGapsAndCaptions) {
  std::vector<Image> tiles;
  for (int k = 0; k < 4; ++k) tiles.emplace_back(30, 20, Rgb(0, k / 4.0, 1));
  tiles.emplace_back(25, 10, Rgb(1, 0, 0));  // smaller: centred in its cell
  ContactSheetStyle style;
  style.columns = 3;
  style.gap = 4;
  const Image sheet = contactSheet(tiles, {}, style);
  EXPECT_EQ(sheet.width, 3 * 30 + 4 * 4);
  EXPECT_EQ(sheet.height, 2 * 20 + 3 * 4);
  EXPECT_EQ(sheet.at(4, 4), tiles[0].at(0, 0));
  EXPECT_EQ(sheet.at(3, 4), Rgb(1, 1, 1));               // gap
  EXPECT_EQ(sheet.at(4, 4 + 24), tiles[3].at(0, 0));       // row 2, column 1
  EXPECT_EQ(sheet.at(38 + 15, 28 + 10), Rgb(1, 0, 0));     // row 2, column 2: small tile's centre

  style.captionScale = 1;
  const Image captioned = contactSheet(tiles, {"(a)", "(b)", "", "(d)", "(e) zygomaticus"}, style);
  EXPECT_EQ(captioned.width, sheet.width);
  EXPECT_EQ(captioned.height, 2 * (20 + 7 + 4) + 3 * 4);
  EXPECT_EQ(contactSheet({}, {}, style).width, 0);
  EXPECT_THROW(contactSheet(tiles, {"only one"}, style), CheckError);

  const Image fig = withCaption(tiles[0], "Fig. 18 (a)", 1);
  EXPECT_EQ(fig.width, std::max(30, textWidth("Fig. 18 (a)", 1) + 8));
  EXPECT_GT(fig.height, 20 + 7);
}

}  // namespace
}  // namespace myo
