// MP4 and GIF output through ffmpeg: what ffprobe and ffmpeg read back, odd sizes, and every way
// of failing (missing folder, ffmpeg missing or dying mid-stream, abandoned writers) leaving nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"
#include "myoshell/render/video.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

#define MYO_REQUIRE_FFMPEG()                                                                           \
  do {                                                                                                 \
    if (!::myo::ffmpegAvailable())                                                                     \
      GTEST_SKIP() << "ffmpeg not found on PATH (install the Debian package ffmpeg): video test skipped"; \
  } while (0)

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs a shell command and returns its standard output (binary-safe).
std::string capture(const std::string& command) {
  std::string out;
  FILE* p = ::popen(command.c_str(), "r");
  if (!p) return out;
  char buf[65536];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  ::pclose(p);
  return out;
}

// ffprobe's description of the first video stream, key → value.
std::map<std::string, std::string> probe(const fs::path& video) {
  const std::string text = capture(
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,width,height,pix_fmt,nb_read_frames -of default=noprint_wrappers=1 " +
      shellQuote("file:" + video.string()));
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq != std::string::npos) out[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return out;
}

// Frame `index` of a video decoded by ffmpeg to rgb24 bytes (empty on failure).
std::string decodeFrame(const fs::path& video, int index) {
  return capture("ffmpeg -v error -nostdin -i " + shellQuote("file:" + video.string()) + " -vf " +
                 shellQuote("select=eq(n\\," + std::to_string(index) + ")") + " -vframes 1 -f rawvideo -pix_fmt rgb24 pipe:1");
}

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.push_back(fs::relative(e.path(), dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

constexpr int kWidth = 96, kHeight = 64, kSquare = 16;
// Frame k of the test clip: a red 16×16 square at (8 + 3k, 20 + k) on light grey.
Image squareFrame(int k) {
  Image im(kWidth, kHeight, Rgb(0.9, 0.9, 0.9));
  im.fillRect(8 + 3 * k, 20 + k, kSquare, kSquare, Rgb(1, 0, 0));
  return im;
}

// Centre and count of the red pixels of an rgb24 frame.
struct RedBlob {
  double x = 0, y = 0;
  int count = 0;
};
RedBlob redBlob(const std::string& rgb, int width, int height) {
  RedBlob b;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto* p = reinterpret_cast<const unsigned char*>(rgb.data()) + 3 * (static_cast<size_t>(y) * width + x);
      if (p[0] > 160 && p[1] < 110 && p[2] < 110) {
        b.x += x;
        b.y += y;
        ++b.count;
      }
    }
  if (b.count > 0) {
    b.x /= b.count;
    b.y /= b.count;
  }
  return b;
}

// Sets PATH for the life of the object.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& value) {
    if (const char* old = std::getenv("PATH")) old_ = old;
    ::setenv("PATH", value.c_str(), 1);
  }
  ~ScopedPath() { ::setenv("PATH", old_.c_str(), 1); }

 private:
  std::string old_;
};

class Video : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("myo_video_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(Video, Mp4HoldsEveryFrameAndTheSquareWhereItWasDrawn) {
  MYO_REQUIRE_FFMPEG();
  // A folder and a file name that a shell or ffmpeg would misread if they were not passed verbatim.
  const fs::path folder = dir_ / "it's a \"video\" folder";
  fs::create_directories(folder);
  const fs::path path = folder / "-clip: one.mp4";
  {
    VideoWriter w(path.string(), kWidth, kHeight, VideoOptions{10, 18});
    for (int k = 0; k < 20; ++k) w.addFrame(squareFrame(k));
    EXPECT_EQ(w.frameCount(), 20);
    w.finish();
  }
  ASSERT_TRUE(fs::exists(path));
  EXPECT_EQ(listing(folder), std::vector<std::string>{path.filename().string()}) << "temporary file left behind";

  const auto info = probe(path);
  EXPECT_EQ(info.count("codec_name") ? info.at("codec_name") : "", "h264");
  EXPECT_EQ(info.count("pix_fmt") ? info.at("pix_fmt") : "", "yuv420p");
  EXPECT_EQ(info.count("width") ? info.at("width") : "", std::to_string(kWidth));
  EXPECT_EQ(info.count("height") ? info.at("height") : "", std::to_string(kHeight));
  EXPECT_EQ(info.count("nb_read_frames") ? info.at("nb_read_frames") : "", "20");

  // +faststart: the index (moov) comes before the media data (mdat).
  const std::string bytes = readBytes(path);
  const size_t moov = bytes.find("moov"), mdat = bytes.find("mdat");
  ASSERT_NE(moov, std::string::npos);
  ASSERT_NE(mdat, std::string::npos);
  EXPECT_LT(moov, mdat);

  // The square is where frame k drew it: centre (8 + 3k + 7.5, 20 + k + 7.5).
  for (int k : {0, 10, 19}) {
    const std::string rgb = decodeFrame(path, k);
    ASSERT_EQ(rgb.size(), size_t(kWidth) * kHeight * 3) << "frame " << k;
    const RedBlob b = redBlob(rgb, kWidth, kHeight);
    EXPECT_NEAR(b.count, kSquare * kSquare, 60) << "frame " << k;
    EXPECT_NEAR(b.x, 8 + 3 * k + 7.5, 1.0) << "frame " << k;
    EXPECT_NEAR(b.y, 20 + k + 7.5, 1.0) << "frame " << k;
  }
}

TEST_F(Video, OddSizesArePaddedByRepeatingTheLastColumnAndRow) {
  MYO_REQUIRE_FFMPEG();
  const fs::path path = dir_ / "odd.mp4";
  Image im(33, 25, Rgb(1, 1, 1));
  im.fillRect(32, 0, 1, 20, Rgb(0, 0, 1));  // last column blue (rows 0–19)
  im.fillRect(0, 24, 28, 1, Rgb(0, 0.8, 0));  // last row green (columns 0–27)
  VideoWriter w(path.string(), 33, 25, VideoOptions{5, 10});
  w.addFrame(im);
  w.addFrame(im);
  w.finish();
  const auto info = probe(path);
  EXPECT_EQ(info.count("width") ? info.at("width") : "", "34");
  EXPECT_EQ(info.count("height") ? info.at("height") : "", "26");
  EXPECT_EQ(info.count("nb_read_frames") ? info.at("nb_read_frames") : "", "2");
  const std::string rgb = decodeFrame(path, 0);
  ASSERT_EQ(rgb.size(), 34u * 26u * 3u);
  auto px = [&](int x, int y, int c) { return static_cast<unsigned char>(rgb[3 * (y * 34 + x) + c]); };
  // The padding column 33 repeats the blue column; the padding row 25 repeats the green row.
  EXPECT_LT(px(33, 10, 0), 90);
  EXPECT_GT(px(33, 10, 2), 160);
  EXPECT_LT(px(10, 25, 0), 90);
  EXPECT_GT(px(10, 25, 1), 140);
  EXPECT_LT(px(10, 25, 2), 90);
}

TEST_F(Video, GifFromTheMp4HasTheRequestedWidth) {
  MYO_REQUIRE_FFMPEG();
  const fs::path mp4 = dir_ / "clip.mp4", gif = dir_ / "clip anim.gif";
  {
    VideoWriter w(mp4.string(), kWidth, kHeight, VideoOptions{10});
    for (int k = 0; k < 12; ++k) w.addFrame(squareFrame(k));
    w.finish();
  }
  makeGif(mp4.string(), gif.string(), 48, 5);
  const std::string bytes = readBytes(gif);
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 6), "GIF89a");
  const int width = static_cast<unsigned char>(bytes[6]) | static_cast<unsigned char>(bytes[7]) << 8;
  const int height = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  EXPECT_EQ(width, 48);
  EXPECT_EQ(height, 32);  // the 3:2 aspect ratio kept
  EXPECT_EQ(listing(dir_), (std::vector<std::string>{"clip anim.gif", "clip.mp4"})) << "palette or temporary left";
}

TEST_F(Video, GifOfAMissingVideoNamesItAndWritesNothing) {
  const fs::path mp4 = dir_ / "absent.mp4";
  try {
    makeGif(mp4.string(), (dir_ / "x.gif").string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(mp4.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(Video, AbandonedWriterLeavesNoFile) {
  MYO_REQUIRE_FFMPEG();
  const fs::path path = dir_ / "abandoned.mp4";
  {
    VideoWriter w(path.string(), kWidth, kHeight);
    // Feed frames until ffmpeg has opened its temporary output (writes block while it lags, so this
    // needs a few pipe-fulls at most); the destructor must then remove it.
    bool started = false;
    for (int k = 0; k < 400 && !started; ++k) {
      w.addFrame(squareFrame(k % 20));
      started = !listing(dir_).empty();
    }
    ASSERT_TRUE(started) << "ffmpeg never created its temporary file";
    EXPECT_EQ(listing(dir_)[0].rfind(".abandoned.mp4.", 0), 0u) << listing(dir_)[0];
    EXPECT_FALSE(fs::exists(path));
  }
  { VideoWriter w(path.string(), kWidth, kHeight); }  // no frame at all
  EXPECT_TRUE(fs::is_empty(dir_)) << ::testing::PrintToString(listing(dir_));
}

TEST_F(Video, UnwritablePathsNameThePathAndLeaveNothing) {
  MYO_REQUIRE_FFMPEG();
  const fs::path missing = dir_ / "no such folder" / "x.mp4";
  try {
    VideoWriter w(missing.string(), kWidth, kHeight);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(missing.parent_path()));
  const fs::path folder = dir_ / "a folder.mp4";
  fs::create_directories(folder);
  try {
    VideoWriter w(folder.string(), kWidth, kHeight);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"a folder.mp4"});
}

TEST_F(Video, SizeMismatchThrowsAndTheWriterStaysUsable) {
  MYO_REQUIRE_FFMPEG();
  const fs::path path = dir_ / "sizes.mp4";
  VideoWriter w(path.string(), kWidth, kHeight);
  try {
    w.addFrame(Image(kWidth + 1, kHeight));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("97×64"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(w.frameCount(), 0);
  w.addFrame(squareFrame(0));
  w.finish();
  EXPECT_EQ(probe(path)["nb_read_frames"], "1");
}

TEST_F(Video, MissingFfmpegIsAnInputError) {
  const fs::path empty = dir_ / "empty bin";
  fs::create_directories(empty);
  const fs::path path = dir_ / "x.mp4";
  ScopedPath scoped(empty.string());
  EXPECT_FALSE(ffmpegAvailable());
  try {
    VideoWriter w(path.string(), kWidth, kHeight);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ffmpeg"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"empty bin"});
}

// An `ffmpeg` that answers -version but dies as soon as it is asked to encode: the writer must turn
// the broken pipe into an InputError quoting it (SIGPIPE must not kill the test) and leave nothing.
TEST_F(Video, FfmpegDyingMidStreamIsAnIoErrorQuotingIt) {  // a run-time failure: exit 1, not 2
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  {
    std::ofstream script(bin / "ffmpeg");
    script << "#!/bin/sh\n"
              "if [ \"$1\" = -version ]; then echo 'ffmpeg version fake'; exit 0; fi\n"
              "echo 'fake ffmpeg: the encoder exploded' >&2\n"
              "exit 3\n";
  }
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  const fs::path path = out / "doomed.mp4";
  ScopedPath scoped(bin.string() + ":/usr/bin:/bin");
  ASSERT_TRUE(ffmpegAvailable());
  std::string message;
  try {
    VideoWriter w(path.string(), 256, 256);
    const Image frame(256, 256);  // 196 kB, three times a pipe's buffer
    for (int k = 0; k < 50; ++k) w.addFrame(frame);
    w.finish();
  } catch (const IoError& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << "no IoError";
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("the encoder exploded"), std::string::npos) << message;
  EXPECT_NE(message.find("status 3"), std::string::npos) << message;
  EXPECT_TRUE(fs::is_empty(out)) << ::testing::PrintToString(listing(out));
}

TEST_F(Video, FinishWithoutFramesOrTwiceIsACheckError) {
  MYO_REQUIRE_FFMPEG();
  const fs::path path = dir_ / "none.mp4";
  {
    VideoWriter w(path.string(), kWidth, kHeight);
    EXPECT_THROW(w.finish(), CheckError);
  }
  EXPECT_TRUE(fs::is_empty(dir_));
  VideoWriter w(path.string(), kWidth, kHeight);
  w.addFrame(squareFrame(0));
  w.finish();
  EXPECT_THROW(w.finish(), CheckError);
  EXPECT_THROW(w.addFrame(squareFrame(1)), CheckError);
  EXPECT_TRUE(fs::exists(path));
}

}  // namespace
}  // namespace myo
