// `myoshell fit TARGET [--head default|DIR|OBJ --landmarks F] [--units m|mm|cm] [--muscles A,B,…]
// [--align none|rigid|similarity] [--lambda L] [--out ACTIVATIONS.json] [--cache DIR] [--json]`:
// the activations in [0, 1] of the anatomical face whose settled shape best matches a target
// (fit/activation_fit.h; docs/fitting.md). TARGET is
// - an OBJ of the head's topology, in the head's units (an expression shape of that head);
// - `RIG.glb#shape`, a morph target of a glTF rig (io/rig_file.h): its delta from the rig's base is
//   the target. Without a head option the head is the rig's base mesh (a glTF file carries no
//   landmarks: found automatically without --landmarks);
// - a marker file (fit/marker_target.h): where a few vertices should be, e.g. tracked landmarks;
//   --align rigid or similarity removes the head's motion first.
// Every argument, the head and the target are read and checked before the model is built.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/fit/activation_fit.h"
#include "myoshell/fit/retarget_map.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/marker_file.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/rig_file.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/muscles/muscle_def.h"
#include "resources.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct FitArgs {
  std::string target;
  HeadOptions head;
  std::string muscles;         // comma-separated; "" = every muscle
  std::string library = defaultMuscleLibrary();
  std::string align = "none";
  std::string lambda = "0.02";
  std::string out;
  std::string cacheDir;
  bool json = false;
};

enum class TargetKind { Obj, Rig, Markers };
const char* kindName(TargetKind k) {
  switch (k) {
    case TargetKind::Rig: return "rig";
    case TargetKind::Markers: return "markers";
    case TargetKind::Obj: break;
  }
  return "obj";
}

FitAlignment parseAlignment(const std::string& text) {
  if (text == "none") return FitAlignment::None;
  if (text == "rigid") return FitAlignment::Rigid;
  if (text == "similarity") return FitAlignment::Similarity;
  throw InputError("--align: '" + text + "' is not one of none, rigid, similarity");
}

std::vector<std::string> splitNames(const std::string& list) {
  std::vector<std::string> names;
  if (list.empty()) return names;
  names.emplace_back();
  for (char c : list) {
    if (c == ',') names.emplace_back();
    else names.back() += c;
  }
  for (const std::string& n : names)
    if (n.empty()) throw InputError("--muscles '" + list + "': an empty name (names are separated by single commas)");
  return names;
}

// A marker file is told from an OBJ by its extension: .json, .yaml or .yml.
bool isMarkerFile(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".json" || ext == ".yaml" || ext == ".yml";
}

int runFit(FitArgs& a) {
  const Stopwatch total;
  const FitAlignment alignment = parseAlignment(a.align);
  FitSettings settings;
  settings.alignment = alignment;
  settings.lambda = parseLambda(a.lambda);
  settings.muscles = splitNames(a.muscles);
  checkOutputFile(a.out, "--out", "JSON file");

  const TargetKind kind = isRigShapeArgument(a.target) ? TargetKind::Rig
                          : isMarkerFile(a.target)      ? TargetKind::Markers
                                                        : TargetKind::Obj;
  if (kind != TargetKind::Rig && !fs::is_regular_file(a.target))
    throw InputError("no such target file: give an OBJ of the head, RIG.glb#shape or a marker file", a.target);

  // The head, its muscles and settings; then the target, checked against the head.
  RigFile rig;
  std::string rigShapeName;
  if (kind == TargetKind::Rig) {
    const RigShapeRef ref = splitRigShape(a.target);
    rig = readRig(ref.path);
    rigShapeName = ref.shape;
    rig.shape(rigShapeName);  // InputError listing the rig's shapes when it has no such one
    resolveRigBaseLandmarks(a.head, rig, a.cacheDir);
  }
  const FitHeadOptions headOptions = fitHeadOptions(a.head, a.library);
  const RigFile* rigOrNull = kind == TargetKind::Rig ? &rig : nullptr;
  const SceneInputs inputs = fitHeadInputs(headOptions, rigOrNull, "fit " + a.target);
  const Head& head = inputs.head;
  const int n = head.mesh.vertexCount();

  for (const std::string& name : settings.muscles)
    if (std::none_of(inputs.muscles.begin(), inputs.muscles.end(), [&](const MuscleDef& d) { return d.name == name; })) {
      std::string names;
      for (const MuscleDef& d : inputs.muscles) names += (names.empty() ? "" : ", ") + d.name;
      throw InputError("--muscles: unknown muscle '" + name + "' (the anatomical model's muscles: " + names + ")");
    }

  FitTarget target;
  switch (kind) {
    case TargetKind::Rig:
      if (rig.vertexCount() != n)
        throw InputError(fmt::format("the rig's base has {} vertices and the head {}: give the head the rig was made "
                                     "for (or no head option and --landmarks)",
                                     rig.vertexCount(), n),
                         rig.path);
      target.displacement = rig.delta(rigShapeName);
      break;
    case TargetKind::Markers: {
      const MarkerTarget markers = readMarkerFile(a.target, n);
      const size_t needed = alignment == FitAlignment::Similarity ? 4 : alignment == FitAlignment::Rigid ? 3 : 1;
      if (markers.vertices.size() < needed)
        throw InputError(fmt::format("--align {} needs at least {} markers; the file has {}", a.align, needed,
                                     markers.vertices.size()),
                         a.target);
      target.markerVertices = markers.vertices;
      target.markerPositions = markers.positions;
      break;
    }
    case TargetKind::Obj: {
      // The target is in the head's own units (the unit its OBJ was read in).
      const LengthUnit unit = fitHeadUnit(headOptions, rigOrNull);
      TriMesh rest = head.mesh;
      rest.V /= centimetresPer(unit);
      const TriMesh shape = readObjLike(a.target, rest);
      target.displacement = shape.V * centimetresPer(unit) - head.mesh.V;
      break;
    }
  }

  const Stopwatch buildClock;
  const auto cache = openBasisCache(a.cacheDir);
  const AnatomicalSkin skin(head, inputs.muscles, inputs.anatomical, {}, cache.get());
  const double buildSeconds = buildClock.seconds();
  const ActivationFit fit = fitActivations(skin, target, settings);

  nlohmann::ordered_json acts = nlohmann::ordered_json::object();
  for (size_t m = 0; m < skin.muscles().size(); ++m)
    acts[skin.muscles()[m].muscle.def.name] = fit.activations(static_cast<Eigen::Index>(m));
  nlohmann::ordered_json j;
  // The keys of one `fit-rig` shape (name, reachable, reason, …), then the fit's own. A rig shape is
  // named by its name in the rig; other targets by their file's stem.
  const std::string shapeName = kind == TargetKind::Rig ? rigShapeName : fs::path(a.target).stem().string();
  const std::optional<std::string> unreachable = unreachableReason(shapeName);
  j["name"] = shapeName;
  j["reachable"] = !unreachable.has_value();
  j["reason"] = unreachable.value_or("");
  j["target"] = a.target;
  j["kind"] = kindName(kind);
  j["head"] = head.name;
  j["vertices"] = n;
  if (kind == TargetKind::Markers) j["markers"] = target.markerVertices.size();
  j["compared_vertices"] = fit.metric.comparedVertices;  // the metric's: target or result moves > 0.5 mm
  j["cosine"] = fit.metric.cosine;
  j["magnitude_ratio"] = fit.metric.magnitudeRatio;
  j["rms_mm"] = fit.rmsMm;
  j["max_mm"] = fit.maxMm;
  j["activations"] = acts;
  j["jaw"] = nlohmann::ordered_json::object();  // no jaw in the model yet
  j["align"] = toString(alignment);
  j["lambda"] = settings.lambda;
  j["condition_number"] = fit.conditionNumber;
  j["iterations"] = fit.iterations;
  j["build_seconds"] = buildSeconds;
  j["fit_seconds"] = fit.seconds;
  j["seconds"] = total.seconds();
  if (!a.out.empty()) writeFileAtomically(a.out, j.dump(2) + "\n");
  if (a.json) {
    printJsonReport(j);
    return kExitOk;
  }
  std::string used;
  for (Eigen::Index m = 0; m < fit.activations.size(); ++m)
    if (fit.activations(m) > 0.0)
      used += fmt::format("{}{}={:.3f}", used.empty() ? "" : ", ", skin.muscles()[static_cast<size_t>(m)].muscle.def.name,
                          fit.activations(m));
  fmt::print("fit of {} on {}: cosine {:.3f}, magnitude ratio {:.3f}, RMS {:.2f} mm, max {:.2f} mm over {} vertices "
             "({:.2f} s fit, {:.1f} s in all)\n  {}\n",
             a.target, head.name, fit.metric.cosine, fit.metric.magnitudeRatio, fit.rmsMm, fit.maxMm,
             fit.metric.comparedVertices, fit.seconds, total.seconds(), used.empty() ? "no muscle active" : used);
  if (!a.out.empty()) fmt::print("wrote {}\n", a.out);
  return kExitOk;
}

static CommandRegistrar registerFit("fit", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<FitArgs>();
  CLI::App* sub = app.add_subcommand(
      "fit", "Find the activations in [0, 1] whose settled anatomical face best matches a target shape, a rig's "
             "shape or markers (docs/fitting.md)");
  sub->add_option("target", args->target, "an OBJ of the head, RIG.glb#shape, or a marker file (.json/.yaml)")->required();
  HeadHelp help;
  help.headDefault = "default, or a RIG.glb#shape target's base mesh (its landmarks found automatically without --landmarks)";
  help.landmarks = " or of a rig's base";
  help.units = "; an OBJ target is in the head's unit";
  addHeadOptions(*sub, args->head, help);
  sub->add_option("--muscles", args->muscles, "A,B,…: fit only these muscles (default: all)");
  sub->add_option("--align", args->align, "none, rigid or similarity: remove the target's motion first (default none)");
  sub->add_option("--lambda", args->lambda, "sparsity weight ≥ 0 (default 0.02; 0 = plain bounded least squares)");
  sub->add_option("--out", args->out, "write the activations and figures as JSON (its folder must exist)");
  addLibraryOption(*sub, args->library);
  addCacheOption(*sub, args->cacheDir);
  addJsonFlag(*sub, args->json);
  addThreadsOption(*sub);
  return [args] {
    resolveHeadLandmarks(args->head, args->cacheDir);
    return runFit(*args);
  };
});

}  // namespace
}  // namespace myo::cli
