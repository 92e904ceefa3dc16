// `myoshell rig [--head default|DIR|OBJ --landmarks F] [--units m|mm|cm] [--map MAP.json] --out RIG.glb
// [--library face|builtin|FILE] [--cache DIR] [--json]`: a blendshape rig made by physics for any
// head. Each shape of a retargeting map (fit/retarget_map.h; `fit-rig` writes them; without --map the
// library's shipped map, assets/retarget/arkit_ict_face.json for the whole face) is settled on the head's anatomical face, and the 52 ARKit shapes are written as
// glTF morph targets (io/rig_export.h) in ARKit's order: zero deltas where the map has none or the
// shape is unreachable. A corrective (mouthClose on jawOpen) is written as what it adds to its base.
// docs/fitting.md, "Making a rig".
#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/rig_making.h"
#include "myoshell/muscles/muscle_def.h"
#include "resources.h"

namespace myo::cli {
namespace {

struct RigArgs {
  HeadOptions head;
  std::string library = defaultMuscleLibrary();
  std::string map;
  std::string out;
  std::string cacheDir;
  bool json = false;
};

// What the report names for the shipped map a run without --map used.
std::string shippedMapLabel(const std::string& library) {
  return library == "builtin" ? "assets/retarget/arkit_ict.json" : "assets/retarget/arkit_ict_face.json";
}

int runRig(RigArgs& a) {
  const Stopwatch total;
  checkRigOutputPath(a.out);
  FitHeadOptions headOptions = fitHeadOptions(a.head, a.library);
  headOptions.headGiven = true;  // no rig to take a base from: the head is --head's, 'default' when not given
  const SceneInputs inputs = fitHeadInputs(headOptions, nullptr, "rig");
  const RetargetMap map = readRigMap(a.map, inputs.muscles, a.library);
  const auto cache = openBasisCache(a.cacheDir);
  const MadeRig made = makeArkitRig(inputs, map, cache.get());
  for (const std::string& w : made.settled.warnings) fmt::print(stderr, "myoshell: warning: {}\n", w);
  writeRigGlb(a.out, made.glb);

  const std::string& head = made.glb.name;
  const Eigen::Index n = made.glb.rest.rows();
  if (a.json) {
    nlohmann::ordered_json shapes = nlohmann::ordered_json::array();
    for (const ArkitRigShape& s : made.settled.shapes)
      shapes.push_back({{"name", s.name},
                        {"mapped", s.mapped},
                        {"max_displacement_cm", s.maxDisplacementCm},
                        {"max_displacement_vertex", s.maxDisplacementVertex}});
    nlohmann::ordered_json j;
    j["head"] = head;
    j["vertices"] = n;
    j["map"] = a.map.empty() ? shippedMapLabel(a.library) : a.map;
    j["out"] = a.out;
    j["shapes_made"] = made.settled.made;
    j["shapes"] = shapes;
    j["build_seconds"] = made.buildSeconds;
    j["settle_seconds"] = made.settleSeconds;
    j["seconds"] = total.seconds();
    printJsonReport(j);
    return kExitOk;
  }
  fmt::print("rig of {} ({} vertices) from {}: {} of the 52 ARKit shapes made by physics, the others zero ({:.1f} s)\nwrote {}\n",
             head, n, a.map.empty() ? shippedMapLabel(a.library) : a.map, made.settled.made, total.seconds(), a.out);
  return kExitOk;
}

static CommandRegistrar registerRig("rig", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<RigArgs>();
  CLI::App* sub = app.add_subcommand(
      "rig", "Make an ARKit-named glTF blendshape rig for a head by settling each shape of a retargeting map on its "
             "anatomical face (docs/fitting.md)");
  addHeadOptions(*sub, args->head);
  sub->add_option("--map", args->map,
                  "a retargeting map (fit-rig --out); default: the library's shipped map "
                  "(assets/retarget/arkit_ict_face.json for face, arkit_ict.json for builtin)");
  sub->add_option("--out", args->out, "the rig to write (.glb; its folder must exist)")->required();
  addLibraryOption(*sub, args->library);
  addCacheOption(*sub, args->cacheDir);
  addJsonFlag(*sub, args->json);
  addThreadsOption(*sub);
  return [args] {
    resolveHeadLandmarks(args->head, args->cacheDir);
    return runRig(*args);
  };
});

}  // namespace
}  // namespace myo::cli
