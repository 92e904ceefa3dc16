// `myoshell rig [--head default|DIR|OBJ --landmarks F] [--units m|mm|cm] --map MAP.json --out RIG.glb
// [--cache DIR] [--json]`: a blendshape rig made by physics for any head. Each shape of a
// retargeting map (face/retarget_map.h; `fit-rig` writes them, assets/retarget/arkit_ict.json is
// fitted on ICT) is settled on the head's anatomical face, and the 52 ARKit shapes are written as
// glTF morph targets (io/rig_export.h) in ARKit's order: zero deltas where the map has none or the
// shape is unreachable. A corrective (mouthClose on jawOpen) is written as what it adds to its base.
// docs/fitting.md, "Making a rig".
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/core/timer.h"
#include "myoshell/face/anatomical_skin.h"
#include "myoshell/face/arkit_names.h"
#include "myoshell/face/muscle_def.h"
#include "myoshell/io/retarget_map_file.h"
#include "myoshell/io/rig_export.h"
#include "resources.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct RigArgs {
  FitHeadOptions head;
  std::string map;
  std::string out;
  std::string cacheDir;
  bool json = false;
  const CLI::Option* unitsOption = nullptr;
};

bool endsWithGlb(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".glb";
}

int runRig(RigArgs& a) {
  const Stopwatch total;
  checkOutputFile(a.out, "--out", "rig file (.glb)");
  if (!endsWithGlb(a.out)) throw InputError("--out: a rig is written as a glTF binary; give a file name ending in .glb", a.out);
  a.head.headGiven = true;
  a.head.unitsGiven = a.unitsOption->count() > 0;
  const SceneInputs inputs = fitHeadInputs(a.head, nullptr, "rig");
  std::vector<std::string> muscles;
  for (const MuscleDef& d : inputs.muscles) muscles.push_back(d.name);
  RetargetMap map;
  try {
    map = readRetargetMapFile(a.map, muscles);
  } catch (const InputError&) {
    // A map fitted with the whole face's muscles needs that library: say so rather than "unknown
    // muscle" (the map is read again, without the muscle list, on this error path only).
    if (a.head.library != "face")
      for (const std::string& name : readRetargetMapFile(a.map).muscleNames())
        if (std::find(muscles.begin(), muscles.end(), name) == muscles.end() &&
            std::any_of(faceMuscleDefs().begin(), faceMuscleDefs().end(), [&](const MuscleDef& d) { return d.name == name; }))
          throw InputError("the map uses the whole face's muscles (" + name + ", …): give --library face", a.map);
    throw;
  }
  for (const RetargetShape& s : map.shapes)
    if (!s.jaw.empty())
      throw InputError("shape " + s.name + " sets jaw values, and the anatomical model has no jaw yet", a.map);

  const Stopwatch buildClock;
  const auto cache = openBasisCache(a.cacheDir);
  const AnatomicalSkin skin(inputs.head, inputs.muscles, inputs.anatomical, {}, cache.get());
  const double buildSeconds = buildClock.seconds();
  const Stopwatch settleClock;
  const bool warped = skin.settings().warping;
  SkinLoads loads;
  loads.gravity = skin.restGravity();  // no gravity load: the rig's shapes are the muscles' alone
  loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
  auto settle = [&](const NamedValues& activations) -> MatX3 {
    loads.activations = VecX::Zero(static_cast<Eigen::Index>(skin.muscles().size()));
    for (const auto& [name, value] : activations) loads.activations(skin.muscleIndex(name)) = value;
    const SettledSkin s = skin.settle(loads, warped);
    if (!s.converged || !s.u.allFinite())
      throw NumericalError(fmt::format("rig: the warped static solve did not converge (residual {:.3g})", s.residual));
    return s.u;
  };
  const MatX3 rest = settle({});  // zero with warping off; the warped solve's own rest otherwise

  const Head& head = skin.head();
  const Eigen::Index n = head.mesh.vertexCount();
  RigExport rig;
  rig.name = head.name;
  rig.rest = head.mesh.V;
  rig.triangles = head.mesh.F;
  rig.uv = head.mesh.UV;
  rig.cornerUV = head.mesh.cornerUV;  // an OBJ head's UV seams become appended duplicate vertices
  nlohmann::ordered_json shapes = nlohmann::ordered_json::array();
  int made = 0;
  for (const std::string& name : arkitNames()) {
    const RetargetShape* s = map.find(name);
    MatX3 delta = MatX3::Zero(n, 3);
    if (s && s->reachable) {
      delta = settle(map.totalActivations(*s)) - rest;
      if (!s->correctiveOf.empty()) delta -= settle(map.totalActivations(*map.find(s->correctiveOf))) - rest;
      ++made;
    }
    rig.names.push_back(name);
    rig.deltas.push_back(delta);
    Eigen::Index peakVertex = 0;
    const double peak = delta.rowwise().norm().maxCoeff(&peakVertex);
    shapes.push_back({{"name", name},
                      {"mapped", s != nullptr && s->reachable},
                      {"max_displacement_cm", peak},
                      {"max_displacement_vertex", static_cast<int>(peakVertex)}});
  }
  const double settleSeconds = settleClock.seconds();
  writeRigGlb(a.out, rig);

  if (a.json) {
    nlohmann::ordered_json j;
    j["head"] = head.name;
    j["vertices"] = n;
    j["map"] = a.map;
    j["out"] = a.out;
    j["shapes_made"] = made;
    j["shapes"] = shapes;
    j["build_seconds"] = buildSeconds;
    j["settle_seconds"] = settleSeconds;
    j["seconds"] = total.seconds();
    printJsonReport(j);
    return kExitOk;
  }
  fmt::print("rig of {} ({} vertices) from {}: {} of the 52 ARKit shapes made by physics, the others zero ({:.1f} s)\nwrote {}\n",
             head.name, n, a.map, made, total.seconds(), a.out);
  return kExitOk;
}

static CommandRegistrar reg("rig", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<RigArgs>();
  CLI::App* sub = app.add_subcommand(
      "rig", "Make an ARKit-named glTF blendshape rig for a head by settling each shape of a retargeting map on its "
             "anatomical face (docs/fitting.md)");
  sub->add_option("--head", args->head.head, "'default', an OBJ file (with --landmarks), or a folder like "
                                              "../shared/data/ict (default: default)");
  sub->add_option("--landmarks", args->head.landmarks, "landmark file of an OBJ head (docs/heads.md)");
  args->unitsOption = sub->add_option("--units", args->head.units, "the OBJ head's length unit, m, mm or cm (default cm)");
  sub->add_option("--map", args->map, "a retargeting map (fit-rig --out; e.g. assets/retarget/arkit_ict.json)")->required();
  sub->add_option("--out", args->out, "the rig to write (.glb; its folder must exist)")->required();
  sub->add_option("--library", args->head.library, "muscles: builtin (the thesis's eight, default), face (the whole face, docs/muscles.md) or a library file");
  sub->add_option("--cache", args->cacheDir, "Basis cache folder (default: $MYOSHELL_CACHE, $XDG_CACHE_HOME/myoshell or "
                                             "~/.cache/myoshell)");
  sub->add_flag("--json", args->json, "print each shape's largest displacement and the timings as JSON");
  return [args] { return runRig(*args); };
});

}  // namespace
}  // namespace myo::cli
