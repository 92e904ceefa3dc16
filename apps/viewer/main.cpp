// `myoshell-view`: the interactive viewer. A live face with a slider per muscle (the thesis's Maya
// plug-in, standalone). The only place besides the CLI that prints to the user and exits.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

#include "myoshell/core/parallel.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/live_source.h"
#include "option_checks.h"  // apps/cli: the number checks of the CLI's options
#include "head_landmarks.h"  // apps/cli: the landmarks of a scene's OBJ head without head.landmarks
#include "resources.h"  // apps/cli: where the cache is
#include "viewer_app.h"
#include "viewer_session.h"

namespace {
// As the CLI's (apps/cli/command.h): 2 for bad arguments or input files, 1 for anything else.
constexpr int kExitOk = 0, kExitFailure = 1, kExitBadInput = 2;
}

// A performance file (OpenFace or Live Link CSV, MediaPipe JSON Lines) rather than a scene.
static bool isPerformanceFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".csv" || ext == ".jsonl";
}

// A mesh rather than a scene: YAML would read an OBJ's text as one scalar ("key '(document)': must
// be an object"), which tells a new user nothing.
static bool isMeshFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".glb" || ext == ".gltf" || ext == ".fbx";
}

static std::string meshNotSceneMessage(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string();
  return "'" + path + "' is a mesh, not a scene: myoshell-view opens a scene file (JSON or YAML) or a performance " +
         "(.csv, .jsonl). For an OBJ head, write a scene beside it, e.g. " + stem + ".json: {\"name\": \"" + stem +
         "\", \"head\": {\"obj\": \"" + p.filename().string() + "\", \"landmarks\": \"" + stem +
         "_landmarks.json\"}} (the landmarks: docs/heads.md; `myoshell head " + path +
         " --landmarks FILE` checks the head first; the keys: docs/scene_format.md), then run myoshell-view " + stem +
         ".json";
}

// --live SPEC: vmc, livelink, vmc:PORT or livelink:PORT (the protocol's default port without one).
struct LiveSpec {
  myo::LiveProtocol protocol = myo::LiveProtocol::Vmc;
  int port = 0;
};

static LiveSpec parseLiveSpec(const std::string& spec) {
  const auto bad = [&] {
    return myo::InputError("--live: expected vmc[:PORT] or livelink[:PORT] (got '" + spec + "')");
  };
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  if (name != "vmc" && name != "livelink") throw bad();
  LiveSpec live;
  live.protocol = myo::liveProtocolFromString(name);
  live.port = myo::defaultLivePort(live.protocol);
  if (colon != std::string::npos) {
    const std::string digits = spec.substr(colon + 1);
    if (digits.empty() || digits.size() > 5 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      throw bad();
    live.port = std::stoi(digits);
    if (live.port > 65535) throw bad();
  }
  return live;
}

int main(int argc, char** argv) {
  // Named here, not after argv[0]: --help reads the same however it is started (docs/cli.md).
  CLI::App app{"myoshell-view: a live face with a slider per muscle", "myoshell-view"};
  std::string scenePath, cacheDir, size = "1280x800";
  myo::viewer::ViewerOptions options;
  app.add_option("scene", scenePath, "scene file (JSON or YAML), or a performance (.csv: OpenFace or Live Link Face; "
                                    ".jsonl: MediaPipe) played on the built-in head; default: the built-in head and "
                                    "the whole face's 40 muscles");
  std::string library;
  app.add_option("--library", library,
                 "muscles of the built-in head or a performance: face (the whole face's 40, the default), builtin "
                 "(the built-in ten) or a library file; a scene names its own");
  app.add_option("--script", options.script, "run this script (commands in docs/viewer.md), then exit");
  app.add_option("--screenshot", options.screenshot, "draw --frames frames, save this PNG and exit");
  app.add_option("--frames", options.frames, "frames before --screenshot (default 30)")->check(myo::cli::wholeIn(0, 100000));
  app.add_option("--msaa", options.samples, "multisamples per pixel (default: 4 on a GPU, 0 on llvmpipe)")
      ->check(myo::cli::wholeIn(0, 16));
  app.add_flag("--stay", options.stay, "keep the window open after --script");
  app.add_option("--size", size, "window size WxH in pixels (default 1280x800)");
  app.add_option("--cache", cacheDir, "folder of cached modal bases (default: $MYOSHELL_CACHE, $XDG_CACHE_HOME/myoshell or ~/.cache/myoshell)");
  int threads = 0;
  app.add_option("--threads", threads,
                 "threads for building the face (0 = every core, the default); the live step runs on one")
      ->check(myo::cli::wholeAtLeast(0, "0 = every core"));
  std::string liveSpec, listen = "127.0.0.1", response;
  bool lockstep = false;
  app.add_option("--live", liveSpec,
                 "drive the face from a tracker's stream (docs/live.md): vmc[:PORT] or livelink[:PORT] (default ports "
                 "39539 and 11111; 0 any free one); the sliders follow it");
  app.add_option("--listen", listen, "with --live: the address to listen on, 127.0.0.1 (default) or 0.0.0.0 for any "
                                     "interface");
  app.add_flag("--lockstep", lockstep, "with --live: acknowledge each frame taken to its sender (myoshell send --lockstep)");
  app.add_option("--response", response,
                 "follow (the activations' quasi-static shape at once; the default with --live) or dynamic (the skin "
                 "trails them; the scene's numerics.response otherwise; docs/live.md, \"Lag\")");
  app.set_version_flag("--version", "myoshell-view 0.1.0");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    fmt::print(stderr, "myoshell-view: error: {} (see myoshell-view --help)\n", e.what());
    return kExitBadInput;
  }
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 64 || h < 64 || w > 8192 || h > 8192) {
    fmt::print(stderr, "myoshell-view: error: --size '{}' is not WxH with sides in [64, 8192]\n", size);
    return kExitBadInput;
  }
  options.width = w;
  options.height = h;
  try {
    if (!scenePath.empty() && isMeshFile(scenePath)) throw myo::InputError(meshNotSceneMessage(scenePath));
    if (!library.empty() && !scenePath.empty() && !isPerformanceFile(scenePath))
      throw myo::InputError("--library chooses the muscles of the built-in head or a performance; the scene names its "
                            "own (key muscles.library)");
    const std::string chosen = myo::sceneMuscleLibrary(library.empty() ? myo::defaultMuscleLibrary() : library);
    if (!response.empty() && response != "follow" && response != "dynamic")
      throw myo::InputError("--response: expected dynamic or follow (got '" + response + "')");
    // Listening before anything is built: a bad spec or a port in use fails at once, and what
    // arrives while the face builds waits (only the newest frame is kept).
    std::unique_ptr<myo::LiveSource> source;
    const myo::LiveClock clock = myo::steadyLiveClock();
    if (!liveSpec.empty()) {
      const LiveSpec live = parseLiveSpec(liveSpec);
      if (isPerformanceFile(scenePath))
        throw myo::InputError("--live drives the face from a stream and '" + scenePath +
                              "' is a recorded performance: give one or the other");
      myo::LiveSourceOptions sourceOptions;
      sourceOptions.protocol = live.protocol;
      sourceOptions.address = listen;
      sourceOptions.port = live.port;
      sourceOptions.clock = clock;
      sourceOptions.acknowledge = lockstep;
      source = std::make_unique<myo::LiveSource>(sourceOptions);
    }
    myo::viewer::checkDisplay();  // no display: say so now, not after building the face
    myo::setParallelThreads(threads);  // the builds (core/parallel.h); a step never spreads
    myo::SceneDesc scene;
    if (isPerformanceFile(scenePath)) {
      // A recorded performance on the built-in head with the whole face (docs/performance_input.md):
      // play and scrub it; the sliders follow the muscles it drives.
      scene.name = std::filesystem::path(scenePath).stem().string();
      scene.muscleLibrary = chosen;
      scene.performance.file = std::filesystem::absolute(scenePath).string();
      myo::loadScenePerformance(scene);
      for (const std::string& w : scene.performanceReport->warnings) fmt::print(stderr, "myoshell-view: warning: {}\n", w);
    } else if (!scenePath.empty()) {
      scene = myo::readScene(scenePath);
      myo::cli::resolveSceneLandmarks(scene, cacheDir, "myoshell-view");
    } else {
      scene.name = "default";
      scene.muscleLibrary = chosen;
    }
    // Live: the activations' shape at once (as `myoshell live`), unless --response says otherwise.
    if (!response.empty() || source)
      scene.anatomical.response = response == "dynamic" ? myo::SkinResponse::Dynamic : myo::SkinResponse::Follow;
    if (source)
      fmt::print("myoshell-view: listening for {} on {}:{}\n", myo::toString(source->protocol()), listen, source->port());
    const auto cache = myo::cli::openBasisCache(cacheDir, "myoshell-view");
    myo::viewer::ViewerSession session(scene, cache.get());
    if (source) {
      session.listen(std::move(source), clock);
      for (const std::string& w : session.takeWarnings()) fmt::print(stderr, "myoshell-view: warning: {}\n", w);
    }
    const myo::viewer::ViewerStats stats = myo::viewer::runViewer(session, options);
    if (!options.screenshot.empty()) fmt::print("wrote {}\n", options.screenshot);
    fmt::print("myoshell-view: {} frames in {:.2f} s ({:.1f} frames/s), simulation {:.0f} steps/s\n", stats.frames,
               stats.seconds, stats.framesPerSecond(), stats.stepsPerSecond);
    if (session.live()) {
      const myo::viewer::LiveStatus st = session.liveStatus();
      const myo::LiveCounters& c = st.counters;
      fmt::print("myoshell-view: live {}: {} packets, {} frames taken ({} malformed, {} dropped, {} superseded); "
                 "latency {}\n",
                 myo::toString(st.protocol), c.packets, c.taken, c.malformed, c.dropped, c.superseded,
                 st.latencySamples > 0 ? fmt::format("median {:.1f} ms over the last second", st.latencyMs)
                                       : std::string("- (no frame in the last second)"));
      if (const auto unknown = session.liveUnknownNames(); !unknown.empty()) {
        std::string names;
        for (const std::string& n : unknown) names += (names.empty() ? "" : ", ") + n;
        fmt::print(stderr, "myoshell-view: warning: VMC blend names that mean nothing here, ignored: {}\n", names);
      }
    }
    return kExitOk;
  } catch (const myo::InputError& e) {
    fmt::print(stderr, "myoshell-view: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {  // no display, a blown-up simulation, …
    fmt::print(stderr, "myoshell-view: error: {}\n", e.what());
    return kExitFailure;
  }
}
