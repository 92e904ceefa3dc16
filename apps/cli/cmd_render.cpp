// `myoshell render SCENE --out DIR`: simulates a scene and writes pictures of chosen frames
// (DIR/png/<scene>_NNNN.png) and a contact sheet (DIR/<scene>_sheet.png), with overlays, through
// OpenGL (a headless EGL context) or, when that is unavailable or --software, the software
// renderer (docs/rendering.md).
#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "resources.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/core/timer.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/face_picture.h"
#include "myoshell/render/png.h"
#include "myoshell/render/video.h"
#include "myoshell/thesis/simulator.h"
#include "option_checks.h"
#include "scene_runner.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct RenderCommandOptions {
  std::string scene;
  std::string outDir;
  std::string frames;            // "A:B" or "A:B:STEP"; empty: every frame
  std::string size = "480x480";  // "WxH" or "N" (square)
  std::string view = "front";
  std::vector<std::string> overlays;
  double colorScale = 0.0;       // cm; 0: the run's largest |u|
  int sheet = 6;
  bool software = false;
  bool video = false;            // DIR/<scene>.mp4 and .gif of the drawn frames
  bool json = false;
  std::string cacheDir;            // --cache; "" = the default (resources.h)
};

[[noreturn]] void badValue(const std::string& option, const std::string& value, const std::string& why) {
  throw InputError(option + " '" + value + "': " + why);
}

bool parseInt(const std::string& text, int& out) {
  const char* end = text.data() + text.size();
  const auto [p, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && p == end && !text.empty();
}

struct FrameRange {
  int first = 0, last = 0, step = 1;  // frame numbers, last included
};

FrameRange parseFrames(const std::string& text, int frameCount) {
  FrameRange r{0, frameCount - 1, 1};
  if (text.empty()) return r;
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t colon; (colon = text.find(':', start)) != std::string::npos; start = colon + 1)
    parts.push_back(text.substr(start, colon - start));
  parts.push_back(text.substr(start));
  const bool ok = (parts.size() == 2 || parts.size() == 3) && parseInt(parts[0], r.first) &&
                  parseInt(parts[1], r.last) && (parts.size() == 2 || parseInt(parts[2], r.step));
  if (!ok) badValue("--frames", text, "expected A:B or A:B:STEP (frame numbers, e.g. 0:30:5)");
  if (r.step < 1) badValue("--frames", text, "STEP must be at least 1");
  if (r.first < 0 || r.first > r.last) badValue("--frames", text, "expected 0 <= A <= B");
  if (r.last >= frameCount)
    badValue("--frames", text, fmt::format("the scene's frames are 0 to {}", frameCount - 1));
  return r;
}

std::pair<int, int> parseSize(const std::string& text) {
  int w = 0, h = 0;
  const size_t x = text.find('x');
  const bool ok = x == std::string::npos ? parseInt(text, w) && (h = w, true)
                                         : parseInt(text.substr(0, x), w) && parseInt(text.substr(x + 1), h);
  if (!ok) badValue("--size", text, "expected WxH in pixels (e.g. 640x480) or N for NxN");
  if (w < 16 || h < 16 || w > 4096 || h > 4096) badValue("--size", text, "each side must be 16 to 4096 pixels");
  return {w, h};
}

FaceOverlays parseOverlays(const std::vector<std::string>& names) {
  FaceOverlays o;
  for (const std::string& name : names) {
    if (name == "muscles") o.muscles = true;
    else if (name == "roi") o.roi = true;
    else if (name == "displacement") o.displacement = true;
    else if (name == "pins") o.pins = true;
    else badValue("--overlay", name, "unknown overlay (use muscles, roi, displacement, pins)");
  }
  if (o.roi && o.displacement) badValue("--overlay", "roi,displacement", "both colour the skin; choose one");
  return o;
}

// About `count` frames of `frames`, evenly spaced, first and last included.
std::vector<int> sheetFrames(const std::vector<int>& frames, int count) {
  std::vector<int> out;
  const int n = static_cast<int>(frames.size());
  if (count <= 0 || n == 0) return out;
  if (count >= n) return frames;
  for (int i = 0; i < count; ++i) {
    const int k = count == 1 ? 0 : static_cast<int>(std::lround(static_cast<double>(i) * (n - 1) / (count - 1)));
    if (out.empty() || out.back() != frames[static_cast<size_t>(k)]) out.push_back(frames[static_cast<size_t>(k)]);
  }
  return out;
}

double medianOf(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

int runRender(const RenderCommandOptions& opt) {
  // Every option is checked before any work, so a typo fails at once and writes nothing.
  const auto [width, height] = parseSize(opt.size);
  FaceOverlays overlays = parseOverlays(opt.overlays);
  const ViewPreset view = parseView(opt.view);
  checkOutputFolder(opt.outDir, "--out");
  SceneDesc scene = readScene(opt.scene);
  resolveSceneLandmarks(scene, opt.cacheDir);
  if (overlays.roi && scene.modelKind != FaceModelKind::Thesis)
    throw InputError("--overlay roi: the muscles' ROIs are model: thesis only (the scene's model is " +
                     std::string(toString(scene.modelKind)) + ")");
  const int frameCount = ScenePlayer::frameCount(scene.duration, scene.fps);
  const FrameRange range = parseFrames(opt.frames, frameCount);
  const fs::path out(opt.outDir);

  if (opt.video && !ffmpegAvailable())
    throw InputError("--video needs the ffmpeg program, which is not on PATH (scripts/setup installs it)");

  const auto cache = openBasisCache(opt.cacheDir);
  const auto model = buildSceneFace(scene, cache.get());
  std::error_code ec;
  fs::create_directories(out / "png", ec);
  if (ec) throw InputError("cannot create the output folder (" + ec.message() + ")", out.string());

  std::unique_ptr<FacePainter> painter = makePainter(opt.software);

  // Simulate up to the last frame, keeping the state of the frames to draw.
  std::vector<int> frames;
  for (int f = range.first; f <= range.last; f += range.step) frames.push_back(f);
  const std::vector<int> onSheet = sheetFrames(frames, opt.sheet);
  ScenePlayer player(scene, model);
  std::vector<FaceFrameState> states;
  std::vector<double> times;
  double maxDisplacement = 0.0;
  size_t next = 0;
  for (int f = 0; f <= range.last; ++f) {
    player.advanceTo(f);
    const FrameSnapshot& snap = player.snapshot(overlays.muscles);
    maxDisplacement = std::max(maxDisplacement, snap.maxDisplacement);
    if (next >= frames.size() || frames[next] != f) continue;
    ++next;
    states.push_back(faceFrameState(snap, overlays));
    times.push_back(snap.time);
  }
  overlays.displacementScale = opt.colorScale > 0 ? opt.colorScale : maxDisplacement > 0 ? maxDisplacement : 1.0;
  const VecX roi = overlays.roi ? roiWeights(dynamic_cast<const FaceModel&>(*model)) : VecX();

  // Draw and write each frame; keep the contact sheet's pictures.
  std::vector<Image> sheet;
  std::vector<std::string> captions;
  std::vector<double> paintMs;
  std::unique_ptr<VideoWriter> video;
  const fs::path videoPath = out / (scene.name + ".mp4"), gifPath = out / (scene.name + ".gif");
  const double videoFps = scene.fps / range.step;  // the drawn frames keep their timing
  if (opt.video) {
    VideoOptions vo;
    vo.fps = videoFps;
    video = std::make_unique<VideoWriter>(videoPath.string(), width, height, vo);
  }
  // The painter has one drawing context: frames are painted in order, a batch at a time, and each
  // batch's PNGs are encoded side by side (--threads; each file's bytes are the same either way).
  const size_t batch = static_cast<size_t>(2 * parallelThreads());
  for (size_t first = 0; first < frames.size(); first += batch) {
    std::vector<Image> pictures;
    for (size_t i = first; i < std::min(frames.size(), first + batch); ++i) {
      Stopwatch clock;
      pictures.push_back(painter->paint(faceScene(*model, states[i], view, width, height, overlays, &roi)));
      paintMs.push_back(1e3 * clock.seconds());
      if (video) video->addFrame(pictures.back());
      if (std::find(onSheet.begin(), onSheet.end(), frames[i]) != onSheet.end()) {
        sheet.push_back(pictures.back());
        captions.push_back(fmt::format("t = {:.2f} s", times[i]));
      }
    }
    parallelFor(static_cast<std::int64_t>(pictures.size()), [&](std::int64_t k) {
      const size_t i = first + static_cast<size_t>(k);
      writePng((out / "png" / fmt::format("{}_{:04d}.png", scene.name, frames[i])).string(), pictures[static_cast<size_t>(k)]);
    });
  }
  const fs::path sheetPath = out / (scene.name + "_sheet.png");
  if (!sheet.empty()) {
    ContactSheetStyle style;
    style.columns = std::min<int>(3, static_cast<int>(sheet.size()));
    writePng(sheetPath.string(), contactSheet(sheet, captions, style));
  }

  if (video) {
    video->finish();
    makeGif(videoPath.string(), gifPath.string(), std::min(width, 480), std::min(videoFps, 15.0));
  }

  if (opt.json) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["renderer"] = painter->name();
    j["frames"] = frames;
    j["width"] = width;
    j["height"] = height;
    j["png"] = (out / "png").string();
    j["sheet"] = sheet.empty() ? nlohmann::json() : nlohmann::json(sheetPath.string());
    j["sheet_frames"] = onSheet;
    j["render_ms_median"] = medianOf(paintMs);
    if (video) j["video"] = {videoPath.string(), gifPath.string()};
    j["render_ms"] = paintMs;
    if (overlays.displacement) j["color_scale_cm"] = overlays.displacementScale;
    printJsonReport(j);
  } else {
    fmt::print("{}: {} frames drawn by {} at {}x{}, median {:.1f} ms per frame\n", scene.name, frames.size(),
               painter->name(), width, height, medianOf(paintMs));
    fmt::print("wrote {}/png/{}_NNNN.png\n", out.string(), scene.name);
    if (!sheet.empty()) fmt::print("wrote {}\n", sheetPath.string());
    if (video) fmt::print("wrote {} and {}\n", videoPath.string(), gifPath.string());
  }
  return kExitOk;
}

const CommandRegistrar renderRegistrar("render", [](CLI::App& app) {
  auto opt = std::make_shared<RenderCommandOptions>();
  CLI::App* sub = app.add_subcommand("render", "Simulate a scene and draw chosen frames and a contact sheet (PNG)");
  sub->add_option("scene", opt->scene, "Scene file (JSON or YAML)")->required();
  sub->add_option("--out", opt->outDir, "Output folder")->required();
  sub->add_option("--frames", opt->frames, "Frames A:B or A:B:STEP (frame numbers, B included; default all)");
  sub->add_option("--size", opt->size, "Picture size WxH, pixels")->capture_default_str();
  sub->add_option("--view", opt->view, "front, three-quarter, profile or back")->capture_default_str();
  sub->add_option("--overlay", opt->overlays, "Comma-separated: muscles, roi, displacement, pins (default: none)")->delimiter(',');
  sub->add_option("--color-scale", opt->colorScale, "Displacement colour scale [0, CM] (default: the run's largest |u|)")
      ->check(numberAbove(0));
  sub->add_option("--sheet", opt->sheet, "About N evenly spaced frames on the contact sheet (0: none)")
      ->check(wholeAtLeast(0))
      ->capture_default_str();
  sub->add_flag("--video", opt->video, "Also write DIR/<scene>.mp4 and DIR/<scene>.gif of the drawn frames (ffmpeg)");
  sub->add_flag("--software", opt->software, "Use the software renderer even where OpenGL is available");
  addCacheOption(*sub, opt->cacheDir);
  addJsonFlag(*sub, opt->json);
  addThreadsOption(*sub);
  return std::function<int()>([opt] { return runRender(*opt); });
});

}  // namespace
}  // namespace myo::cli
