// `myoshell run SCENE --out DIR`: simulates a scene and writes its animation (--format: an OBJ
// sequence, GLB, PC2), stats.json and, with --render, pictures. `myoshell check SCENE`: validates a scene and prints it with every
// default filled in (--json: that scene under "scene", beside "ok" and "file").
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/scene_face.h"
#include "option_checks.h"
#include "scene_runner.h"

namespace myo::cli {
namespace {

const CommandRegistrar runRegistrar("run", [](CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "Simulate a scene file and write an OBJ sequence and stats.json");
  sub->add_option("scene", opt->scene, "Scene file (JSON or YAML)")->required();
  sub->add_option("--out", opt->outDir, "Output folder")->required();
  addCacheOption(*sub, opt->cacheDir);
  addJsonFlag(*sub, opt->json);
  addThreadsOption(*sub);
  sub->add_option("--format", opt->formats, "Animation exports, comma-separated: glb, pc2, obj")
      ->delimiter(',')
      ->capture_default_str();
  addGlbToleranceOption(*sub, opt->glbToleranceMm);
  sub->add_flag("--render", opt->render, "Write PNG frames (DIR/png/) and a contact sheet");
  sub->add_option("--render-every", opt->renderEvery, "Render every N-th frame")->check(wholeAtLeast(1))->capture_default_str();
  sub->add_option("--size", opt->size, "Picture size, pixels")->check(wholeIn(64, 4096))->capture_default_str();
  sub->add_option("--view", opt->view, "front, three-quarter, profile or back")->capture_default_str();
  sub->add_flag("--muscles", opt->showMuscles, "Show the muscles through the skin");
  sub->add_flag("--video", opt->video, "Write DIR/<name>.mp4 and DIR/<name>.gif of every frame (ffmpeg)");
  sub->add_flag("--software", opt->software, "Draw with the software renderer even where OpenGL is available");
  sub->add_flag("--diagnostics", opt->diagnostics,
                "Also measure each thesis channel's load participation for stats.json (a sparse factorisation per "
                "channel: slower start)");
  sub->add_option("--color-scale", opt->colorScale, "Colour the skin by displacement on [0, CM] (default 0: not coloured)")->check(numberAtLeast(0));
  return std::function<int()>([opt] {
    checkOutputFolder(opt->outDir, "--out");  // before the scene is read
    SceneDesc scene = readScene(opt->scene);
    resolveSceneLandmarks(scene, opt->cacheDir);
    return runScene(scene, *opt);
  });
});

struct CheckArgs {
  std::string scene;
  bool json = false;
};

const CommandRegistrar checkRegistrar("check", [](CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* sub = app.add_subcommand("check", "Validate a scene file and print it with every default filled in");
  sub->add_option("scene", args->scene, "Scene file (JSON or YAML)")->required();
  addJsonFlag(*sub, args->json);
  return std::function<int()>([args] {
    SceneDesc scene = readScene(args->scene);
    resolveSceneLandmarks(scene, "");
    readSceneInputs(scene);  // every file it names and every name checked, as `run` does; nothing built
    if (!args->json) {
      fmt::print("{}", sceneToJson(scene));
      return kExitOk;
    }
    // A fault exits 2 with the message on stderr before this: printed, the scene is valid.
    nlohmann::ordered_json j;
    j["ok"] = true;
    j["file"] = args->scene;
    j["scene"] = nlohmann::ordered_json::parse(sceneToJson(scene));
    fmt::print("{}\n", j.dump(2));
    return kExitOk;
  });
});

}  // namespace
}  // namespace myo::cli
