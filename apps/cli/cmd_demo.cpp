// `myoshell demo`: the default head's whole face plays a short scene — brows up, brows down, a
// blink, a smile, a pucker, the jaw opening — and
// out/demo/ receives the OBJ sequence, demo.glb, demo.pc2, demo.mp4, demo.gif, stats.json, PNG frames and a
// contact sheet. The scene is
// scenes/demo.json, embedded at build time so the demo runs from any folder.
#include <fmt/core.h>

#include "command.h"
#include "common_options.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/render/video.h"
#include "scene_runner.h"

namespace myo::cli::detail {
extern const char kDemoSceneJson[];  // scenes/demo.json (cmake/EmbedText.cmake)
}

namespace myo::cli {
namespace {

const CommandRegistrar registrar("demo", [](CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  opt->outDir = "out/demo";
  opt->render = true;
  opt->renderEvery = 3;
  // The skin alone: the whole face's 40 muscles drawn through it hide the expressions they make
  // (`myoshell run scenes/demo.json --render --muscles` shows them).
  opt->showMuscles = false;
  opt->formats = {"glb", "pc2", "obj"};
  CLI::App* sub = app.add_subcommand("demo", "The whole face on the built-in head: brows up and down, a blink, a smile, a pucker, the jaw (scenes/demo.json)");
  sub->add_option("--out", opt->outDir, "Output folder")->capture_default_str();
  addCacheOption(*sub, opt->cacheDir);
  addJsonFlag(*sub, opt->json);
  return std::function<int()>([opt] {
    // demo.mp4 and demo.gif; without ffmpeg the rest still runs. Asked here, when demo runs: at
    // registration every command would pay for starting ffmpeg.
    opt->video = ffmpegAvailable();
    const int code = runScene(parseScene(detail::kDemoSceneJson, "<built-in scenes/demo.json>"), *opt);
    if (!opt->json && code == kExitOk) {
      if (!opt->video) fmt::print(stderr, "myoshell: warning: no ffmpeg on PATH, so no demo.mp4 or demo.gif\n");
      fmt::print("open {}/demo.mp4 or {}/demo_sheet.png; {}/png/ holds the frames\n", opt->outDir, opt->outDir,
                 opt->outDir);
    }
    return code;
  });
});

}  // namespace
}  // namespace myo::cli
