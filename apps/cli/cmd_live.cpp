// `myoshell live --input vmc|livelink [--port P] [--listen ADDRESS] [--head …] --out DIR
// [--format glb,pc2,obj] [--glb-tolerance MM] [--duration S] [--fps 60] [--calibrate S] [--timeout S] [--response follow|dynamic] [--lockstep] [--json]`:
// a tracker's stream (docs/live.md) drives the face in real time through the one frame loop
// (ScenePlayer), mapped as `drive` maps a take (io/live_take.h). The frames received are written as
// the face plays them to DIR/live.csv (a Live Link Face CSV) and DIR/replay.json (the scene `run`
// plays to the same frames); the face's frames at --fps to the exports. Ctrl-C keeps the recording
// and the frames made (exit 130).
#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "interrupt.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/animation_exporter.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/live_take.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/scene_face.h"
#include "option_checks.h"
#include "resources.h"
#include "scene_runner.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct LiveArgs {
  std::string input;
  int port = -1;  // < 0: the protocol's default
  std::string listen = "127.0.0.1";
  HeadOptions head;
  std::string library = "face";
  std::string map;
  std::string outDir;
  std::vector<std::string> formats = {"glb"};
  double glbToleranceMm = kDefaultGlbToleranceMm;
  double duration = 10.0;
  double fps = 60.0;
  double calibrate = 0.0;
  double timeout = 0.5;
  std::string filter = "on";
  std::string response = "follow";  // live: the activations' shape at once (docs/live.md, "Lag")
  OneEuroSettings oneEuro;
  bool lockstep = false;
  std::string cacheDir;
  bool json = false;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t k = static_cast<size_t>(std::ceil(p * static_cast<double>(v.size()))) - (p > 0 ? 1 : 0);
  return v[std::min(k, v.size() - 1)];
}

int runLive(const LiveArgs& a) {
  const LiveProtocol protocol = liveProtocolFromString(a.input);
  if (a.filter != "on" && a.filter != "off") throw InputError("--filter: expected on or off (got '" + a.filter + "')");
  if (a.response != "dynamic" && a.response != "follow")
    throw InputError("--response: expected dynamic or follow (got '" + a.response + "')");
  checkOutputFolder(a.outDir, "--out");
  const ExportFormats formats = parseExportFormats(a.formats);
  OneEuroSettings filter = a.oneEuro;
  filter.enabled = a.filter == "on";

  SceneDesc scene;
  scene.name = "live";
  const HeadFiles files = resolveHeadArgument(a.head.head, a.head.landmarks, "", a.head.units);
  // Absolute: replay.json, in the output folder, names them too.
  scene.head.obj = files.obj.empty() ? "" : fs::absolute(files.obj).string();
  scene.head.landmarks = files.landmarks.empty() ? "" : fs::absolute(files.landmarks).string();
  scene.head.units = files.unit;
  scene.muscleLibrary = sceneMuscleLibrary(a.library);
  scene.performance.map = a.map.empty() ? "" : fs::absolute(a.map).string();
  scene.duration = a.duration;
  scene.fps = a.fps;
  scene.anatomical.response = a.response == "follow" ? SkinResponse::Follow : SkinResponse::Dynamic;
  LiveFaceMapper mapper(scene, filter);

  // Listening before the face builds: a port in use fails at once, and what arrives meanwhile waits.
  const LiveClock clock = steadyLiveClock();
  LiveSourceOptions sourceOptions;
  sourceOptions.protocol = protocol;
  sourceOptions.address = a.listen;
  sourceOptions.port = a.port < 0 ? defaultLivePort(protocol) : a.port;
  sourceOptions.clock = clock;
  sourceOptions.acknowledge = a.lockstep;
  LiveSource source(sourceOptions);
  LiveFaceSettings faceSettings;
  faceSettings.timeout = a.timeout;
  faceSettings.calibrateSeconds = a.calibrate;
  LiveFaceInput input(faceSettings);

  const auto cache = openBasisCache(a.cacheDir);
  const auto model = buildSceneFace(scene, cache.get());
  const fs::path out(a.outDir);
  const int frames = ScenePlayer::frameCount(scene.duration, scene.fps);
  AnimationExporter exporter(out, formats, scene.name, model->head().mesh, scene.fps, frames, scene.head.units,
                             glbOptionsForTolerance(a.glbToleranceMm));
  LiveTakeRecorder recorder((out / "live.csv").string(), protocol == LiveProtocol::LiveLink, scene.fps);
  const SceneDesc replay = liveReplayScene(scene, "live.csv", scene.fps, filter);
  writeFileAtomically((out / "replay.json").string(), sceneToJson(replay), "cannot write the replay scene");
  ScenePlayer player(scene, model);
  FaceStepper& face = player.simulator();
  const std::vector<int> muscleIndex = mapper.muscleIndex(*model);
  const std::atomic<bool>& interrupted = installInterruptHandlers();
  player.watch(&interrupted);
  // Said once the face is built, when the take starts (to stderr under --json: a script waits for it).
  fmt::print(a.json ? stderr : stdout, "listening for {} on {}:{} for {} s\n", toString(protocol), a.listen,
             source.port(), a.duration);
  std::fflush(a.json ? stderr : stdout);

  std::vector<std::string> warnings;
  std::vector<double> latencyMs;
  MatX3 positions;
  int framesDone = 0;
  LiveFrame played;  // the last frame the face played, as the recording holds it
  const double dt = model->dt();
  const double start = clock();
  // Frame 0 is the rest shape. Frame f ≥ 1 (the steps from (f−1)/fps to f/fps) plays the newest
  // frame taken: stepped as soon as one arrives once frame f−1's time has come, or at frame f's own
  // time when none does (a silent stream eases to neutral), so a packet waits for no fixed tick.
  // What it played is recorded at (f−1)/fps − dt/2, between the steps of frames f−1 and f (the
  // first at 0): replayed with each frame held (replay.json), the steps see exactly these values.
  face.skinPositions(positions);
  exporter.addFrame(0, positions);
  framesDone = 1;
  for (int f = 1; f < frames; ++f) {
    const double earliest = start + (f - 1) / scene.fps, deadline = start + f / scene.fps;
    while (!interrupted.load() && clock() < earliest)
      std::this_thread::sleep_for(std::chrono::duration<double>(std::min(earliest - clock(), 0.002)));
    while (!interrupted.load() && clock() < deadline && !source.waitForFrame(std::min(deadline - clock(), 0.01))) {
    }
    if (interrupted.load()) break;
    std::optional<double> arrival;
    if (const std::optional<LiveSample> sample = source.takeNewest()) {
      input.receive(*sample);
      arrival = sample->arrival;
    }
    const double t = f == 1 ? 0.0 : (f - 1) / scene.fps - 0.5 * dt;
    played = recorder.write(t, input.at(clock()));
    const MappedPerformance mapped = mapper.map(t, played);
    if (f == 1) warnings = mapped.warnings;
    LiveFaceMapper::apply(mapped, muscleIndex, face);
    if (!player.advanceTo(f)) break;
    face.skinPositions(positions);
    // Arrival → positions ready for this frame (the wait for the frame's turn included).
    if (arrival) latencyMs.push_back(1e3 * (clock() - *arrival));
    exporter.addFrame(f, positions);
    framesDone = f + 1;
  }
  // The closing row: the take's length is the frames made, the last held to the end.
  if (framesDone >= 2) recorder.write((framesDone - 1) / scene.fps, played);
  const double seconds = clock() - start;
  const bool cut = framesDone < frames;
  // Cut short (Ctrl-C), the exports hold the frames made.
  const std::vector<std::string> written = exporter.finish();
  if (const GlbReport* glb = exporter.glbReport()) warnIfGlbInexact(*glb);
  source.stop();
  const LiveCounters c = source.counters();
  if (!source.unknownNames().empty())
    warnings.push_back("VMC blend names that mean nothing here, ignored: " + fmt::format("{}", fmt::join(source.unknownNames(), ", ")));
  for (const std::string& w : warnings) fmt::print(stderr, "myoshell: warning: {}\n", w);
  if (a.json) {
    nlohmann::ordered_json j;
    j["input"] = toString(protocol);
    j["port"] = source.port();
    j["packets"] = c.packets;
    j["dropped"] = c.dropped;
    j["malformed"] = c.malformed;
    j["superseded"] = c.superseded;
    j["ignored"] = c.ignored;
    j["received_frames"] = c.frames;
    j["frames"] = framesDone;
    j["duration"] = framesDone > 0 ? (framesDone - 1) / scene.fps : 0.0;
    j["seconds"] = seconds;
    j["latency_ms"] = {{"median", percentile(latencyMs, 0.5)}, {"p99", percentile(latencyMs, 0.99)},
                       {"samples", latencyMs.size()}};
    j["recording"] = recorder.path();
    j["replay"] = (out / "replay.json").string();
    j["recorded_frames"] = recorder.rows();
    j["outputs"] = written;
    if (const GlbReport* glb = exporter.glbReport()) j["glb"] = glbJson<nlohmann::ordered_json>(*glb);
    j["last_malformed"] = source.lastMalformed();
    j["warnings"] = warnings;
    j["interrupted"] = cut;
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("{} packets ({} malformed, {} lost, {} superseded), {} frames in {:.1f} s; latency median {:.1f} ms, "
               "p99 {:.1f} ms; recorded {} frames to {}\n",
               c.packets, c.malformed, c.dropped, c.superseded, framesDone, seconds, percentile(latencyMs, 0.5),
               percentile(latencyMs, 0.99), recorder.rows(), recorder.path());
  }
  if (cut) {
    fmt::print(stderr, "myoshell: interrupted ({}) at frame {} of {}: kept the recording {} ({} rows) and the {} frames made\n",
               interruptName(), framesDone, frames, recorder.path(), recorder.rows(), framesDone);
    return 128 + interruptSignal();
  }
  return kExitOk;
}

static CommandRegistrar registerLive("live", [](CLI::App& app) -> std::function<int()> {
  auto a = std::make_shared<LiveArgs>();
  CLI::App* sub = app.add_subcommand(
      "live", "Drive the face from a tracker's live stream (VMC or Live Link Face over UDP), record what arrives and "
              "write the animation (docs/live.md)");
  sub->add_option("--input", a->input, "the protocol: vmc or livelink")->required();
  sub->add_option("--port", a->port, "UDP port to listen on (default 39539 for vmc, 11111 for livelink; 0 any free one)")
      ->check(wholeIn(0, 65535));
  sub->add_option("--listen", a->listen, "the address to listen on: 127.0.0.1 (default) or 0.0.0.0 for any interface");
  sub->add_option("--out", a->outDir, "Output folder")->required();
  addHeadOptions(*sub, a->head);
  addLibraryOption(*sub, a->library);
  sub->add_option("--map", a->map, "ARKit input: a retargeting map (fit-rig --out); default the shipped ICT map");
  sub->add_option("--format", a->formats, "Animation exports, comma-separated: glb, pc2, obj")
      ->delimiter(',')
      ->capture_default_str();
  addGlbToleranceOption(*sub, a->glbToleranceMm);
  sub->add_option("--duration", a->duration, "seconds to run")->check(numberAbove(0))->capture_default_str();
  sub->add_option("--fps", a->fps, "output frames per second")->check(numberAbove(0))->capture_default_str();
  sub->add_option("--calibrate", a->calibrate, "seconds of the performer's resting face to subtract (default 0: none)")
      ->check(numberAtLeast(0));
  sub->add_option("--timeout", a->timeout, "seconds of silence before the face eases to neutral")
      ->check(numberAtLeast(0))
      ->capture_default_str();
  sub->add_option("--filter", a->filter, "the One-Euro filter on the input curves: on (default) or off");
  sub->add_option("--min-cutoff", a->oneEuro.minCutoff, "One-Euro filter: cutoff at rest, Hz")->capture_default_str();
  sub->add_option("--beta", a->oneEuro.beta, "One-Euro filter: speed coefficient")->capture_default_str();
  sub->add_option("--response", a->response,
                  "follow (the activations' quasi-static shape at once, only gravity, drags and contact lag; "
                  "the default live) or dynamic (the skin trails the activations by its dynamics; docs/live.md)")
      ->capture_default_str();
  sub->add_flag("--lockstep", a->lockstep, "Acknowledge each frame taken to its sender (myoshell send --lockstep)");
  addCacheOption(*sub, a->cacheDir);
  addJsonFlag(*sub, a->json);
  return [a] {
    resolveHeadLandmarks(a->head, a->cacheDir);
    return runLive(*a);
  };
});

}  // namespace
}  // namespace myo::cli
