// `myoshell figures`: a thesis figure drawn through the shared painter, the same picture by OpenGL
// and by the software renderer, and an unknown figure named.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_runner.h"
#include "support/picture.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using test::Picture;
using test::readPicture;
using test::differingPixels;

TEST(FiguresCommand, Fig26IsTheSamePictureThroughOpenGLAndSoftware) {
  const fs::path dir = fs::temp_directory_path() / ("myo_figures_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string common = "--only fig26 --size 96 --scenes '" + (test::sourceDir() / "scenes" / "thesis").string() +
                             "' --cache '" + (dir / "cache").string() + "'";
  const auto gl = test::runCli("figures --out '" + (dir / "gl").string() + "' " + common);
  ASSERT_EQ(gl.exitCode, 0) << gl.merged;
  const auto sw = test::runCli("figures --software --out '" + (dir / "sw").string() + "' " + common);
  ASSERT_EQ(sw.exitCode, 0) << sw.merged;
  const Picture a = readPicture(dir / "gl" / "fig26_transition.png"), b = readPicture(dir / "sw" / "fig26_transition.png");
  ASSERT_GT(a.width, 96);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  // Same layout, captions and colours: the renderers differ only along silhouettes (anti-aliasing).
  double sum = 0.0;
  for (size_t i = 0; i < a.rgb.size(); ++i) sum += std::abs(a.rgb[i] - b.rgb[i]);
  EXPECT_LT(sum / a.rgb.size(), 4.0) << "mean absolute difference per channel, levels";
  fs::remove_all(dir);
}

TEST(FiguresCommand, AnUnknownFigureIsNamed) {
  const auto r = test::runCli("figures --out /nonexistent/never --only fig99");  // from any folder
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("unknown figure 'fig99'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists("/nonexistent/never"));
  const auto noScenes = test::runCli("figures --out /nonexistent/never --scenes /nonexistent/scenes");
  EXPECT_EQ(noScenes.exitCode, 2);
  EXPECT_NE(noScenes.err.find("/nonexistent/scenes: no thesis scenes here"), std::string::npos) << noScenes.err;
  EXPECT_FALSE(fs::exists("/nonexistent/never"));
}

}  // namespace
}  // namespace myo
