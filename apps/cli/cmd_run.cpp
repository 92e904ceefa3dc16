// `myoshell run SCENE --out DIR`: simulates a scene and writes its animation (--format: an OBJ
// sequence, GLB, PC2), stats.json and, with --render, pictures. `myoshell check SCENE`: validates a scene and prints it with every
// default filled in.
#include <fmt/core.h>

#include "command.h"
#include "myoshell/io/scene_face.h"
#include "scene_runner.h"

namespace myo::cli {
namespace {

const CommandRegistrar runRegistrar("run", [](CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "Simulate a scene file and write an OBJ sequence and stats.json");
  sub->add_option("scene", opt->scene, "Scene file (JSON or YAML)")->required();
  sub->add_option("--out", opt->outDir, "Output folder")->required();
  sub->add_option("--cache", opt->cacheDir, "Basis cache folder (default: $MYOSHELL_CACHE, $XDG_CACHE_HOME/myoshell or ~/.cache/myoshell)");
  sub->add_flag("--json", opt->json, "Print a JSON summary");
  sub->add_option("--format", opt->formats, "Animation exports, comma-separated: glb, pc2, obj")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_flag("--render", opt->render, "Write PNG frames (DIR/png/) and a contact sheet");
  sub->add_option("--render-every", opt->renderEvery, "Render every N-th frame")->check(CLI::PositiveNumber);
  sub->add_option("--size", opt->size, "Picture size, pixels")->check(CLI::Range(64, 4096));
  sub->add_option("--view", opt->view, "front, three-quarter, profile or back")->capture_default_str();
  sub->add_flag("--muscles", opt->showMuscles, "Show the muscles through the skin");
  sub->add_flag("--video", opt->video, "Write DIR/<name>.mp4 and DIR/<name>.gif of every frame (ffmpeg)");
  sub->add_flag("--software", opt->software, "Draw with the software renderer even where OpenGL is available");
  sub->add_flag("--diagnostics", opt->diagnostics,
                "Also measure each thesis channel's load participation for stats.json (a sparse factorisation per "
                "channel: slower start)");
  sub->add_option("--color-scale", opt->colorScale, "Colour the skin by displacement on [0, CM]")->check(CLI::NonNegativeNumber);
  return std::function<int()>([opt] { return runScene(readScene(opt->scene), *opt); });
});

const CommandRegistrar checkRegistrar("check", [](CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("check", "Validate a scene file and print it with every default filled in");
  sub->add_option("scene", *path, "Scene file (JSON or YAML)")->required();
  return std::function<int()>([path] {
    const SceneDesc scene = readScene(*path);
    readSceneInputs(scene);  // every file it names and every name checked, as `run` does; nothing built
    fmt::print("{}", sceneToJson(scene));
    return kExitOk;
  });
});

}  // namespace
}  // namespace myo::cli
