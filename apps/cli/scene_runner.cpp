#include "scene_runner.h"

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "job_report.h"
#include "command.h"
#include "interrupt.h"
#include "myoshell/gl/gl_face_painter.h"
#include "resources.h"
#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anim/head_motion.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"
#include "myoshell/core/timer.h"
#include "myoshell/head/face_frame.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/animation_exporter.h"
#include "myoshell/io/output_manifest.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/png.h"
#include "myoshell/render/video.h"
#include "myoshell/thesis/simulator.h"

namespace myo::cli {

namespace fs = std::filesystem;

std::unique_ptr<FacePainter> makePainter(bool software) {
  std::string warning;
  std::unique_ptr<FacePainter> painter = makeFacePainter(software, &warning);
  if (!warning.empty()) fmt::print(stderr, "myoshell: warning: {}\n", warning);
  return painter;
}

void warnIfGlbInexact(const GlbReport& report) {
  if (!report.withinTolerance)
    fmt::print(stderr,
               "myoshell: warning: the GLB's {} morph targets (the cap) leave a frame {:.3f} mm from the simulation, "
               "more than the GLB's tolerance ({:g} mm); the PC2 and OBJ frames are exact\n",
               report.targets, 10.0 * report.maxErrorCm, report.toleranceMm);
}

int runScene(const SceneDesc& sceneIn, const RunOptions& opt) {
  SceneDesc scene = sceneIn;
  scene.model.measureLoadParticipation = opt.diagnostics;
  const fs::path out(opt.outDir);
  checkOutputFolder(opt.outDir, "--out");
  const ExportFormats formats = parseExportFormats(opt.formats);  // before any work: a typo fails at once
  const ViewPreset view = parseView(opt.view);
  const FaceFraming framing = parseFraming(opt.framing);
  const auto cache = openBasisCache(opt.cacheDir);

  const bool tty = !opt.json && isatty(STDOUT_FILENO);
  if (scene.performanceReport)
    for (const std::string& w : scene.performanceReport->warnings) fmt::print(stderr, "myoshell: warning: {}\n", w);
  Stopwatch buildClock;
  const auto model = buildSceneFace(scene, cache.get());
  const double buildSeconds = buildClock.seconds();
  // The gaze turns the eyes through the lids (docs/eyelids.md): a head without eye openings has
  // none, so the track would move nothing without a word.
  if (scene.hasGaze() && !hasOpenEyes(model->head().mesh, model->head().landmarks))
    fmt::print(stderr,
               "myoshell: warning: the scene turns the eyes (its gaze), but this head has no eye openings between "
               "its eye corners: no lids, so nothing follows the gaze\n");
  // Folders only once the scene has built: a bad scene leaves nothing behind.
  AnimationExporter exporter(out, formats, scene.name, model->head().mesh, scene.fps,
                             ScenePlayer::frameCount(scene.duration, scene.fps), scene.head.units,
                             glbOptionsForTolerance(opt.glbToleranceMm));
  // What the last run here wrote: whatever of it this run does not rewrite goes at the end.
  const std::vector<std::string> previous = readOutputManifest(out);
  std::vector<std::string> written;  // relative to out
  ScenePlayer player(scene, model);
  const std::atomic<bool>& interrupted = installInterruptHandlers();
  player.watch(&interrupted);
  const double dt = model->dt();
  const int frames = player.frameCount();
  const std::vector<std::string> channels = model->channelNames();

  FaceOverlays overlays;
  overlays.muscles = opt.showMuscles;
  overlays.displacement = opt.colorScale > 0.0;
  overlays.displacementScale = opt.colorScale > 0.0 ? opt.colorScale : 1.0;
  const bool draw = opt.render || opt.video;
  std::unique_ptr<FacePainter> painter = draw ? makePainter(opt.software) : nullptr;
  std::unique_ptr<VideoWriter> video;
  const fs::path videoPath = out / (scene.name + ".mp4"), gifPath = out / (scene.name + ".gif");
  const bool panel = opt.video && !opt.videoPanel.curves.empty();
  if (opt.video) {
    VideoOptions vo;
    vo.fps = scene.fps;
    video = std::make_unique<VideoWriter>(videoPath.string(), panel ? 2 * opt.size : opt.size, opt.size, vo);
  }
  // --head-motion: the rigid turn of every exported frame, about the neck pivot.
  const bool turnHead = opt.headMotion && !scene.headPose.empty();
  MatX3 turned;
  std::vector<Image> sheet;
  std::vector<std::string> sheetCaptions;
  const int sheetEvery = std::max(1, (frames - 1) / 5);  // about six frames on the sheet
  if (opt.render) fs::create_directories(out / "png");
  nlohmann::json frameStats = nlohmann::json::array();
  std::vector<double> channelMax(channels.size(), 0.0);
  double stepSeconds = 0.0;
  long long steps = 0;
  Stopwatch wall;
  int framesDone = 0;
  for (int f = 0; f < frames; ++f) {
    if (interrupted.load() || !player.advanceTo(f)) break;  // Ctrl-C: stop at the next step
    const FrameSnapshot& snap = player.snapshot(overlays.muscles);
    stepSeconds += snap.stepSeconds;
    steps += snap.steps;
    const MatX3* shown = &snap.positions;
    if (turnHead) {
      turnWithHead(snap.positions, model->head().frame(), scene.headPose, snap.time, turned);
      shown = &turned;
    }
    if (const std::string rel = exporter.addFrame(f, *shown); !rel.empty()) written.push_back(rel);
    const bool png = opt.render && f % opt.renderEvery == 0;
    const bool onSheet = opt.render && f % sheetEvery == 0 && sheet.size() < 6;
    if (video || png || onSheet) {
      const Image image = painter->paint(
          faceScene(*model, faceFrameState(snap, overlays), view, opt.size, opt.size, overlays, nullptr, framing));
      if (video) video->addFrame(panel ? besideEachOther(image, drawCurvePanel(opt.videoPanel, snap.time, opt.size, opt.size)) : image);
      if (png) {
        const std::string rel = fmt::format("png/{}_{:04d}.png", scene.name, f);
        writePng((out / rel).string(), image);
        written.push_back(rel);
      }
      if (onSheet) {
        sheet.push_back(image);
        sheetCaptions.push_back(fmt::format("t = {:.2f} s", snap.time));
      }
    }
    nlohmann::json fs_ = {{"frame", f}, {"time", snap.time}, {"steps", snap.steps},
                          {"step_ms", snap.steps ? 1e3 * snap.stepSeconds / snap.steps : 0.0},
                          {"max_displacement_cm", snap.maxDisplacement}};
    nlohmann::json perChannel = nlohmann::json::object();
    for (size_t c = 0; c < channels.size(); ++c) {
      channelMax[c] = std::max(channelMax[c], snap.channelMax[c]);
      perChannel[channels[c]] = snap.channelMax[c];
    }
    fs_["channel_max_cm"] = perChannel;
    frameStats.push_back(fs_);
    framesDone = f + 1;
    if (tty) {
      const double rate = steps / std::max(stepSeconds, 1e-12);
      const double eta = wall.seconds() / (f + 1) * (frames - f - 1);
      fmt::print("\r  frame {:4d}/{}  {:8.0f} steps/s  ETA {:5.1f} s", f + 1, frames, rate, eta);
      std::fflush(stdout);
    }
  }
  if (tty) fmt::print("\n");
  if (framesDone < frames) {
    // Interrupted: no video (ffmpeg killed and reaped, its temporary file gone), no GLB, PC2 or
    // stats; the frames written stay and the manifest names them (and the previous run's files) so
    // the next run here cleans up.
    if (video) video->abort();
    std::vector<std::string> listed = previous;
    listed.insert(listed.end(), written.begin(), written.end());
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
    writeOutputManifest(out, listed);
    fmt::print(stderr,
               "myoshell: interrupted ({}) at frame {} of {}: kept the {} frame file(s) written in {}; no stats.json, "
               "GLB, PC2 or video\n",
               interruptName(), framesDone, frames, written.size(), out.string());
    return 128 + interruptSignal();
  }
  if (video) {
    video->finish();
    makeGif(videoPath.string(), gifPath.string(), std::min(opt.size, 480), std::min(scene.fps, 15.0));
    written.push_back(scene.name + ".mp4");
    written.push_back(scene.name + ".gif");
  }
  for (const std::string& rel : exporter.finish()) written.push_back(rel);
  if (const GlbReport* glb = exporter.glbReport()) warnIfGlbInexact(*glb);

  nlohmann::json stats;
  stats["scene"] = scene.name;
  stats["model"] = toString(model->kind());
  stats["frames"] = frames;
  stats["steps"] = steps;
  stats["dt"] = dt;
  stats["precompute_seconds"] = buildSeconds;
  stats["cache_hits"] = model->cacheHits();
  if (painter) stats["renderer"] = painter->name();
  stats["steps_per_second"] = steps / std::max(stepSeconds, 1e-12);
  // Where the wall time went: the simulation's steps, and everything else (snapshots, exports,
  // pictures) up to the last export written.
  const double wallSeconds = wall.seconds();
  stats["simulate_seconds"] = stepSeconds;
  stats["output_seconds"] = std::max(0.0, wallSeconds - stepSeconds);
  stats["realtime_factor"] = (frames > 1 ? (frames - 1) / scene.fps : 0.0) / std::max(wallSeconds, 1e-12);
  if (scene.performanceReport) {
    const PerformanceReport& p = *scene.performanceReport;
    stats["performance"] = p.file;
    stats["input"] = toString(p.input);
    stats["au_scale"] = p.auScale;
    stats["fps"] = p.fps;
    stats["duration"] = p.duration;
    stats["dropped_frames"] = p.droppedFrames;
    stats["warnings"] = p.warnings;
    stats["unmapped"] = p.unmapped;
  }
  stats["step_ms_mean"] = steps ? 1e3 * stepSeconds / steps : 0.0;
  stats["units"] = lengthUnitName(scene.head.units);  // the OBJ frames' and the PC2's
  if (const GlbReport* glb = exporter.glbReport()) stats["glb"] = glbJson(*glb);
  nlohmann::json ch = nlohmann::json::array();
  nlohmann::json mus = nlohmann::json::array();
  if (const auto* thesis = dynamic_cast<const FaceModel*>(model.get())) {
    const auto& chs = thesis->channels();
    for (size_t c = 0; c < chs.size(); ++c)
      ch.push_back({{"name", chs[c].name},
                    {"free_vertices", chs[c].basis->freeCount()},
                    {"modes", chs[c].basis->modeCount()},
                    {"load_participation", chs[c].loadParticipation >= 0 ? nlohmann::json(chs[c].loadParticipation)
                                                                           : nlohmann::json()},
                    {"max_displacement_cm", channelMax[c]}});
    for (const MuscleUnit& u : thesis->muscles())
      mus.push_back({{"name", u.muscle.def.name},
                     {"stretch_mode_index", u.stretchModeIndex},
                     {"stretch_participation", u.stretchParticipation},
                     {"max_force_dyn", u.maxForce},
                     {"roi_vertices", static_cast<int>(u.roi.size())}});
  } else if (const auto* anatomical = dynamic_cast<const AnatomicalFace*>(model.get())) {
    const AnatomicalSkin& skin = anatomical->skin();
    ch.push_back({{"name", "skin"},
                  {"free_vertices", skin.basis()->freeCount()},
                  {"modes", skin.basis()->modeCount()},
                  {"max_displacement_cm", channelMax[0]}});
    for (const CoupledMuscle& m : skin.muscles())
      mus.push_back({{"name", m.muscle.def.name},
                     {"couplings", static_cast<int>(m.springs.size())},
                     {"natural_frequency", m.naturalFrequency}});
  }
  stats["channels"] = ch;
  stats["muscles"] = mus;
  stats["per_frame"] = frameStats;
  writeFileAtomically((out / "stats.json").string(), stats.dump(2) + "\n");
  written.push_back("stats.json");
  if (!sheet.empty()) {
    ContactSheetStyle style;
    style.columns = std::min<int>(3, static_cast<int>(sheet.size()));
    writePng((out / (scene.name + "_sheet.png")).string(), contactSheet(sheet, sheetCaptions, style));
    written.push_back(scene.name + "_sheet.png");
  }
  // A shorter rerun leaves no stale frames or exports: what the last run wrote and this one did
  // not goes (and nothing else: the user's own files are in no manifest).
  const std::vector<std::string> stale = removeStaleOutputs(out, previous, written);
  writeOutputManifest(out, written);

  if (opt.json) {
    nlohmann::json summary = stats;
    summary.erase("per_frame");
    summary["out"] = out.string();
    summary["removed_stale"] = stale;
    printJsonReport(summary);
  } else {
    fmt::print("{}: {} frames, {} steps at {:.0f} steps/s (precompute {:.2f} s, {} cached bases)\n", scene.name,
               frames, steps, steps / std::max(stepSeconds, 1e-12), buildSeconds, model->cacheHits());
    if (formats.obj) fmt::print("wrote {}/obj/{}_NNNN.obj\n", out.string(), scene.name);
    if (const GlbReport* glb = exporter.glbReport())
      fmt::print("wrote {}/{}.glb ({} frames at {:g} fps as {} morph targets, every frame within {:.3f} mm)\n",
                 out.string(), scene.name, glb->frames, glb->fps, glb->targets, 10.0 * glb->maxErrorCm);
    if (formats.pc2) fmt::print("wrote {}/{}.pc2\n", out.string(), scene.name);
    if (video) fmt::print("wrote {} and {}\n", videoPath.string(), gifPath.string());
    fmt::print("wrote {}/stats.json\n", out.string());
    if (!stale.empty()) fmt::print("removed {} stale file(s) of the previous run in {}\n", stale.size(), out.string());
  }
  return kExitOk;
}

}  // namespace myo::cli
