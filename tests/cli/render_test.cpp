// `myoshell render`: frames and a contact sheet through OpenGL (or the software fallback), what the
// pictures show, overlays, and bad option values (exit 2, the option and value named, no output).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/picture.h"

namespace myo {
namespace {

namespace fs = std::filesystem;
using test::Picture;
using test::readPicture;
using test::differingPixels;

// Both zygomatici contract from frame 0 to frame 2 (10 frames per second): a smile.
const char* kSmileScene = R"({
  "name": "smile", "model": "thesis",
  "muscles": {"use": ["zygomaticus_major_left", "zygomaticus_major_right"]},
  "gravity": {"enabled": false},
  "numerics": {"skin_modes": 8},
  "duration": 0.3, "fps": 10,
  "timeline": {"activations": {
    "zygomaticus_major_left":  [{"t": 0, "value": 0}, {"t": 0.2, "value": 1}],
    "zygomaticus_major_right": [{"t": 0, "value": 0}, {"t": 0.2, "value": 1}]}}
})";

class RenderCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_render_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "smile.json") << kSmileScene;
    scene_ = (dir_ / "smile.json").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string render(const std::string& out, const std::string& args) const {
    return "render '" + scene_ + "' --out '" + (dir_ / out).string() + "' --cache '" + (dir_ / "cache").string() +
           "' " + args;
  }
  fs::path dir_;
  std::string scene_;
};

TEST_F(RenderCommand, SmileMovesTheMouthAndNotTheForehead) {
  const auto r = test::runCli(render("gl", "--frames 0:3:3 --size 128x128 --sheet 2 --json"));
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], nlohmann::json::array({0, 3}));
  EXPECT_EQ(j["sheet_frames"], nlohmann::json::array({0, 3}));
  // OpenGL unless this machine has none, and then a one-line warning says so.
  const bool fellBack = r.err.find("myoshell: warning: using the software renderer: ") != std::string::npos;
  EXPECT_EQ(j["renderer"].get<std::string>().rfind(fellBack ? "software" : "opengl", 0), 0u) << r.merged;

  const fs::path png = dir_ / "gl" / "png";
  EXPECT_TRUE(fs::exists(png / "smile_0000.png"));
  EXPECT_TRUE(fs::exists(png / "smile_0003.png"));
  EXPECT_FALSE(fs::exists(png / "smile_0001.png"));
  EXPECT_FALSE(fs::exists(png / "smile_0002.png"));
  ASSERT_TRUE(fs::exists(dir_ / "gl" / "smile_sheet.png"));
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "gl"))
    EXPECT_NE(e.path().extension(), ".tmp") << "half-written file left: " << e.path();

  const Picture neutral = readPicture(png / "smile_0000.png"), smile = readPicture(png / "smile_0003.png");
  ASSERT_EQ(neutral.width, 128);
  ASSERT_EQ(neutral.height, 128);
  ASSERT_EQ(smile.width, 128);
  // Front view framed on the rest head: the mouth is about 60–75 % down, the forehead 8–16 %.
  EXPECT_GT(differingPixels(neutral, smile, 38, 77, 90, 96), 40);
  EXPECT_LE(differingPixels(neutral, smile, 45, 10, 83, 20), 2);
  const Picture sheet = readPicture(dir_ / "gl" / "smile_sheet.png");
  EXPECT_GT(sheet.width, 2 * 128);  // two tiles side by side

  // The software renderer draws nearly the same pictures.
  const auto sw = test::runCli(render("sw", "--frames 3:3 --size 128x128 --sheet 0 --software"));
  ASSERT_EQ(sw.exitCode, 0) << sw.merged;
  EXPECT_NE(sw.out.find("drawn by software"), std::string::npos) << sw.out;
  EXPECT_FALSE(fs::exists(dir_ / "sw" / "smile_sheet.png"));  // --sheet 0
  const Picture soft = readPicture(dir_ / "sw" / "png" / "smile_0003.png");
  ASSERT_EQ(soft.width, 128);
  EXPECT_LT(differingPixels(smile, soft, 0, 0, 128, 128), 128 * 128 / 30);
}

// Frames are painted in order and their PNGs encoded side by side: the files are the same bytes on
// one thread and on three (the software renderer: the same pixels on every machine).
TEST_F(RenderCommand, ThePngsAreTheSameBytesOnOneThreadAndOnThree) {
  for (const char* threads : {"1", "3"}) {
    const auto r = test::runCli(render(std::string("t") + threads, std::string("--frames 0:3 --size 96x96 --sheet 2 --software --threads ") + threads));
    ASSERT_EQ(r.exitCode, 0) << r.merged;
  }
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  int compared = 0;
  for (const char* name : {"png/smile_0000.png", "png/smile_0001.png", "png/smile_0002.png", "png/smile_0003.png", "smile_sheet.png"}) {
    const std::string one = bytes(dir_ / "t1" / name);
    EXPECT_GT(one.size(), 100u) << name;
    EXPECT_TRUE(one == bytes(dir_ / "t3" / name)) << name;
    ++compared;
  }
  EXPECT_EQ(compared, 5);
}

TEST_F(RenderCommand, RoiOverlayPaintsAHeatMapAndPinsAreMarked) {
  const auto plain = test::runCli(render("plain", "--frames 0:0 --size 128x128 --sheet 0"));
  const auto roi = test::runCli(render("roi", "--frames 0:0 --size 128x128 --sheet 0 --overlay roi,pins"));
  ASSERT_EQ(plain.exitCode, 0) << plain.merged;
  ASSERT_EQ(roi.exitCode, 0) << roi.merged;
  const Picture a = readPicture(dir_ / "plain" / "png" / "smile_0000.png");
  const Picture b = readPicture(dir_ / "roi" / "png" / "smile_0000.png");
  ASSERT_EQ(a.width, 128);
  ASSERT_EQ(b.width, 128);
  // Viridis greens and blues (g or b well above r) never occur on the bare skin.
  auto heat = [](const Picture& p) {
    int n = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) n += p.at(x, y)[1] > p.at(x, y)[0] + 30 || p.at(x, y)[2] > p.at(x, y)[0] + 60;
    return n;
  };
  EXPECT_EQ(heat(a), 0);
  EXPECT_GT(heat(b), 100);
  // Pins: yellow discs (r and g high, b low) along the face's rim.
  auto yellow = [](const Picture& p) {
    int n = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) n += p.at(x, y)[0] > 200 && p.at(x, y)[1] > 170 && p.at(x, y)[2] < 80;
    return n;
  };
  EXPECT_EQ(yellow(a), 0);
  EXPECT_GT(yellow(b), 50);
}

TEST_F(RenderCommand, BadOptionValuesExitTwoNamingOptionAndValueAndWriteNothing) {
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--frames 0:x", "myoshell: error: --frames '0:x': expected A:B or A:B:STEP (frame numbers, e.g. 0:30:5)"},
      {"--frames 2:1", "myoshell: error: --frames '2:1': expected 0 <= A <= B"},
      {"--frames 0:3:0", "myoshell: error: --frames '0:3:0': STEP must be at least 1"},
      {"--frames 0:9", "myoshell: error: --frames '0:9': the scene's frames are 0 to 3"},
      {"--size 128by128", "myoshell: error: --size '128by128': expected WxH in pixels (e.g. 640x480) or N for NxN"},
      {"--size 8x8", "myoshell: error: --size '8x8': each side must be 16 to 4096 pixels"},
      {"--overlay muscles,wrinkles",
       "myoshell: error: --overlay 'wrinkles': unknown overlay (use muscles, roi, displacement, pins)"},
      {"--overlay roi,displacement",
       "myoshell: error: --overlay 'roi,displacement': both colour the skin; choose one"},
      {"--view top", "myoshell: error: unknown view 'top' (use front, three-quarter, profile or back)"},
  };
  for (const auto& c : cases) {
    const auto r = test::runCli(render("out", c.args));
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_EQ(r.err, std::string(c.message) + "\n") << c.args;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << c.args;
    EXPECT_FALSE(fs::exists(dir_ / "cache")) << c.args << ": no work before the options are checked";
  }
}


std::string firstBytes(const fs::path& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(n, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(n));
  return bytes.substr(0, static_cast<size_t>(in.gcount()));
}

TEST_F(RenderCommand, VideoWritesAnMp4AndAGifOfTheDrawnFrames) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg is not installed";
  const auto r = test::runCli(render("video", "--size 96x96 --sheet 0 --video"));
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const fs::path mp4 = dir_ / "video" / "smile.mp4", gif = dir_ / "video" / "smile.gif";
  ASSERT_TRUE(fs::exists(mp4)) << r.merged;
  EXPECT_EQ(firstBytes(mp4, 8).substr(4), "ftyp");
  EXPECT_EQ(firstBytes(gif, 6), "GIF89a");
  // ffprobe counts the frames: all four (0.3 s at 10 fps, both ends included).
  const fs::path count = dir_ / "frames.txt";
  const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                            "-of csv=p=0 '" + mp4.string() + "' > '" + count.string() + "'";
  ASSERT_EQ(std::system(probe.c_str()), 0);
  std::ifstream in(count);
  int frames = 0;
  in >> frames;
  EXPECT_EQ(frames, 4);
  for (const auto& entry : fs::directory_iterator(dir_ / "video"))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(RenderCommand, VideoWithoutFfmpegSaysSoBeforeAnyWork) {
  const fs::path log = dir_ / "noff.log";
  const std::string cmd = "PATH=/nonexistent '" + test::cliPath() + "' " + render("noff", "--video") + " > '" +
                          log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("myoshell: error: --video needs the ffmpeg program, which is not on PATH"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(dir_ / "noff"));
}

}  // namespace
}  // namespace myo
