// The viewer's window under Xvfb, driven by scripts: a contracted zygomaticus changes the face
// in the picture, the panel is drawn, and without a display it fails with a clear message.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "myoshell/fit/arkit_names.h"
#include "myoshell/io/live_packets.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/performance_file.h"

#include "support/picture.h"

#include <Eigen/Core>

namespace {

namespace fs = std::filesystem;
using myo::test::Picture;
using myo::test::readPicture;
using myo::test::differingPixels;
using Vec3 = Eigen::Vector3d;

struct ViewerRun {
  int exitCode = -1;
  std::string output;  // stdout and stderr
};

fs::path windowScratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_view_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// Runs `prefix myoshell-view ARGS` in `dir`, output captured.
ViewerRun runViewer(const std::string& prefix, const std::string& args, const fs::path& dir) {
  const fs::path log = dir / "viewer.log";
  // One basis cache for every run of this test program: the eigen-solves happen once.
  const fs::path cache = fs::path(testing::TempDir()) / "myo_view_cache";
  // xvfb-run keeps its auth file in a temporary folder of $TMPDIR and exits 5 when it cannot clean
  // it up (seen once under ctest -j2, with another X test beside it): each run gets a folder of its own.
  const fs::path tmp = dir.parent_path() / (dir.filename().string() + "_xvfb_tmp");
  fs::create_directories(tmp);
  // The viewer's own exit status goes to a file: xvfb-run's cleanup failing (exit 5, seen under
  // load with its own TMPDIR too) must not hide what the viewer returned.
  const fs::path code = dir / "viewer.exit";
  fs::remove(code);
  const std::string inner = "'" + std::string(MYO_VIEWER_PATH) + "' --cache '" + cache.string() + "' " + args +
                            " > '" + log.string() + "' 2>&1; echo $? > '" + code.string() + "'";
  std::string quoted;  // inner, single-quoted for sh -c
  for (char c : inner) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const std::string cmd = "cd '" + dir.string() + "' && TMPDIR='" + tmp.string() + "' " + prefix + " sh -c '" + quoted + "'";
  const int status = std::system(cmd.c_str());
  ViewerRun run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (std::ifstream codeIn(code); codeIn) codeIn >> run.exitCode;
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

bool haveXvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }
const char* kXvfb = "xvfb-run -a -s '-screen 0 1280x1024x24'";

TEST(ViewerWindow, AScriptedSmileChangesTheFaceAndThePanelIsDrawn) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup --test installs xvfb and xauth)";
  const fs::path dir = windowScratch("smile");
  std::ofstream(dir / "neutral.txt") << "show muscles off\nadvance 10\nscreenshot neutral.png\n";
  std::ofstream(dir / "smile.txt") << "# the left zygomaticus, full\nset zygomaticus_major_left 1\nadvance 10\n"
                                      "screenshot smile.png\n";
  for (const char* name : {"neutral", "smile"}) {
    const ViewerRun run = runViewer(kXvfb, std::string("--size 960x720 --script ") + name + ".txt", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    ASSERT_TRUE(fs::exists(dir / (std::string(name) + ".png"))) << run.output;
  }
  const Picture neutral = readPicture(dir / "neutral.png"), smile = readPicture(dir / "smile.png");
  ASSERT_EQ(neutral.width, 960);
  ASSERT_EQ(neutral.height, 720);
  ASSERT_EQ(smile.width, 960);
  // The panel (top-left, ImGui's window): text and sliders, not a flat background.
  int panelInk = 0;
  const unsigned char* background = neutral.at(neutral.width - 2, neutral.height - 2);
  for (int y = 10; y < 300; ++y)
    for (int x = 10; x < 350; ++x)
      if (std::abs(neutral.at(x, y)[0] - background[0]) > 40) ++panelInk;
  EXPECT_GT(panelInk, 2000);
  // The face (right of the panel): the smile moved the mouth; both runs drew the same panel layout.
  const int faceChanged = differingPixels(neutral, smile, 380, 0, smile.width, smile.height);
  EXPECT_GT(faceChanged, 150) << "the contracted zygomaticus left the picture unchanged";
  // The lower face changes more than the upper face (the forehead stays).
  const int upper = differingPixels(neutral, smile, 380, 0, smile.width, smile.height / 3);
  EXPECT_LT(upper, faceChanged / 4);
}

// A script's grab is the script's: the window released every grab while no mouse button was down,
// so `grab`/`pull`/`advance` left the default scene (anatomical model, built-in head) at rest and the
// screenshot byte-identical. The grabbed corner must move along the pull, and `release` let it go.
TEST(ViewerWindow, AScriptedDragMovesTheGrabbedSkinAlongThePull) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = windowScratch("drag");
  std::ofstream(dir / "drag.txt") << "show panel off\nadvance 2\nscreenshot before.png\n"
                                     "grab mouth_corner_left\npull 200000 0 0\nadvance 30\n"
                                     "probe mouth_corner_left\nscreenshot after.png\n"
                                     "release\nadvance 60\nprobe mouth_corner_left\n";
  const ViewerRun run = runViewer(kXvfb, "--size 480x360 --script drag.txt", dir);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  // "probe mouth_corner_left (vertex N): displacement X Y Z cm, |u| L cm", pulled then let go.
  std::vector<Vec3> probes;
  for (size_t at = run.output.find("probe mouth_corner_left"); at != std::string::npos;
       at = run.output.find("probe mouth_corner_left", at + 1)) {
    std::istringstream in(run.output.substr(run.output.find("displacement", at) + 12));
    Vec3 u;
    in >> u.x() >> u.y() >> u.z();
    ASSERT_TRUE(in) << run.output;
    probes.push_back(u);
  }
  ASSERT_EQ(probes.size(), 2u) << run.output;
  EXPECT_GT(probes[0].x(), 0.2) << run.output;                  // cm: more than 2 mm along +x
  EXPECT_GT(probes[0].normalized().x(), 0.7) << run.output;     // mostly along the pull
  EXPECT_LT(probes[1].norm(), 0.1 * probes[0].norm()) << run.output;  // released: it springs back
  const Picture before = readPicture(dir / "before.png"), after = readPicture(dir / "after.png");
  ASSERT_EQ(after.width, 480);
  EXPECT_GT(differingPixels(before, after, 0, 0, after.width, after.height), 200);
}

// --library face: the whole face on the built-in head without a scene. The medial frontalis (only
// in the whole face) lifts the inner brow; with a scene, --library is refused before any display.
TEST(ViewerWindow, LibraryFaceGivesTheWholeFacesSliders) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = windowScratch("library");
  std::ofstream(dir / "brow.txt") << "show panel off\nset frontalis_medial_left 1\nadvance 90\nprobe left_brow_inner\n";
  const ViewerRun run = runViewer(kXvfb, "--size 320x240 --library face --script brow.txt", dir);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const size_t at = run.output.find("probe left_brow_inner");
  ASSERT_NE(at, std::string::npos) << run.output;
  std::istringstream in(run.output.substr(run.output.find("displacement", at) + 12));
  Vec3 u;
  in >> u.x() >> u.y() >> u.z();
  ASSERT_TRUE(in) << run.output;
  EXPECT_GT(u.y(), 0.05) << run.output;  // cm: the brow rises more than half a millimetre

  std::ofstream(dir / "scene.json") << R"({"name": "s"})";
  const ViewerRun both = runViewer("env -u DISPLAY -u WAYLAND_DISPLAY", "scene.json --library face", dir);
  EXPECT_EQ(both.exitCode, 2) << both.output;
  EXPECT_NE(both.output.find("myoshell-view: error: --library chooses the muscles of the built-in head or a performance"),
            std::string::npos)
      << both.output;
}

// An OBJ given where a scene goes was read as YAML and refused with "key '(document)': must be an
// object": it must say that the viewer takes a scene and how to write one for the OBJ, before any
// display is needed.
TEST(ViewerWindow, AnObjHeadIsRefusedWithHowToMakeItsScene) {
  const fs::path dir = windowScratch("obj");
  std::ofstream(dir / "my_head.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const ViewerRun run = runViewer("env -u DISPLAY -u WAYLAND_DISPLAY", "my_head.obj", dir);
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("myoshell-view: error: 'my_head.obj' is a mesh, not a scene"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find(R"({"obj": "my_head.obj", "landmarks": )"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("(document)"), std::string::npos) << run.output;
}

TEST(ViewerWindow, ScreenshotModeWritesThePictureAndExits) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = windowScratch("screenshot");
  const ViewerRun run = runViewer(kXvfb, "--size 640x480 --screenshot shot.png --frames 5", dir);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("wrote shot.png"), std::string::npos) << run.output;
  const Picture shot = readPicture(dir / "shot.png");
  EXPECT_EQ(shot.width, 640);
  EXPECT_EQ(shot.height, 480);
}

TEST(ViewerWindow, WithoutADisplayItSaysSoAndExitsCleanly) {
  const fs::path dir = windowScratch("nodisplay");
  const ViewerRun run = runViewer("env -u DISPLAY -u WAYLAND_DISPLAY", "--screenshot never.png", dir);
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("myoshell-view: error: cannot open a window:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("xvfb-run -a"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "never.png"));
}

TEST(ViewerWindow, ABadScriptNamesItsLineAndLeavesNoPicture) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = windowScratch("badscript");
  std::ofstream(dir / "bad.txt") << "set zygomaticus_major_left 1\nset buccinator 0.5\nscreenshot out.png\n";
  const ViewerRun run = runViewer(kXvfb, "--size 320x240 --script bad.txt", dir);
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("bad.txt:2: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("buccinator"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  const ViewerRun usage = runViewer("", "--size 10x10", dir);
  EXPECT_EQ(usage.exitCode, 2);
  EXPECT_NE(usage.output.find("myoshell-view: error: --size '10x10' is not WxH with sides in [64, 8192]"), std::string::npos)
      << usage.output;
}

// --live SPEC: a bad spec and a port in use are refused (exit 2) before any display is needed.
TEST(ViewerWindow, ABadLiveSpecOrAPortInUseIsRefused) {
  const fs::path dir = windowScratch("live_bad");
  for (const char* spec : {"osc", "livelink:", "vmc:70000", "livelink:12a", "LiveLink"}) {
    const ViewerRun run = runViewer("env -u DISPLAY -u WAYLAND_DISPLAY", std::string("--live ") + spec, dir);
    EXPECT_EQ(run.exitCode, 2) << spec << ": " << run.output;
    EXPECT_NE(run.output.find(std::string("myoshell-view: error: --live: expected vmc[:PORT] or livelink[:PORT] (got '") +
                              spec + "')"),
              std::string::npos)
        << run.output;
  }
  myo::LiveSource taken({myo::LiveProtocol::LiveLink, "127.0.0.1", 0});
  const ViewerRun busy = runViewer("env -u DISPLAY -u WAYLAND_DISPLAY",
                                   "--live livelink:" + std::to_string(taken.port()), dir);
  EXPECT_EQ(busy.exitCode, 2) << busy.output;
  EXPECT_NE(busy.output.find("myoshell-view: error: port " + std::to_string(taken.port()) +
                             " on 127.0.0.1 is in use (another receiver is listening; choose another port)"),
            std::string::npos)
      << busy.output;
}

// --live livelink:PORT under Xvfb while a sender streams the recorded Live Link take: the viewer
// takes the frames, the sliders of the muscles it maps and the jaw show them, and it counts them.
TEST(ViewerWindow, ALiveStreamDrivesTheSliders) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
  const fs::path dir = windowScratch("live");
  const myo::Performance take =
      myo::readPerformanceFile(std::string(MYO_SOURCE_DIR) + "/tests/anim/performances/livelink_take.csv");
  std::vector<myo::LiveFrame> frames(take.times.size());
  const auto& names = myo::arkitNames();
  for (const myo::PerformanceChannel& c : take.channels) {
    const auto k = static_cast<size_t>(std::find(names.begin(), names.end(), c.name) - names.begin());
    for (size_t i = 0; i < frames.size(); ++i) frames[i].weights[k] = c.values[i];
  }
  int port = 0;
  {
    const myo::LiveSource probe({myo::LiveProtocol::LiveLink, "127.0.0.1", 0});  // a free port, let go
    port = probe.port();
  }
  // The sender streams at 200 frames per second until the viewer is done (UDP: what is sent before
  // the viewer listens is lost, as from a tracker).
  std::atomic<bool> done{false};
  std::thread sender([&] {
    myo::LiveSender to("127.0.0.1", port);
    for (int i = 0; !done.load(); ++i) {
      to.send(myo::encodeLiveLinkPacket(frames[static_cast<size_t>(i) % frames.size()], {i, 0.0f, 60, 1}));
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  std::ofstream(dir / "live.txt") << "advance 20\nsliders\nscreenshot live.png\n";
  const ViewerRun run =
      runViewer(kXvfb, "--size 960x720 --live livelink:" + std::to_string(port) + " --script live.txt", dir);
  done = true;
  sender.join();
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const auto value = [&](const std::string& key) {  // a line "KEY X …" of the output
    const size_t at = run.output.find("\n" + key + " ");
    if (at == std::string::npos) return -1.0;
    return std::stod(run.output.substr(at + key.size() + 2));
  };
  EXPECT_GT(value("slider zygomaticus_major_left"), 0.05) << run.output;  // the take smiles (mouthSmileLeft 0.34)
  EXPECT_GT(value("jaw"), 0.5) << run.output;                             // degrees: jawOpen 0.21 opens the jaw
  const size_t summary = run.output.find("myoshell-view: live livelink: ");
  ASSERT_NE(summary, std::string::npos) << run.output;
  std::istringstream in(run.output.substr(summary + 30));
  long packets = 0, taken = 0;
  std::string word;
  in >> packets >> word >> taken;
  EXPECT_GT(packets, 0) << run.output;
  EXPECT_GE(taken, 1) << run.output;
  EXPECT_TRUE(fs::exists(dir / "live.png"));
}

}  // namespace
