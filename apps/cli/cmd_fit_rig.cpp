// `myoshell fit-rig RIG.glb [--head default|DIR|OBJ --landmarks F] [--units m|mm|cm] [--lambda L]
// [--out MAP.json] [--report DIR] [--cache DIR] [--json]`: every ARKit-named shape of a glTF rig
// fitted to activations of the anatomical face (fit/rig_fit.h), gathered into a retargeting map
// (fit/retarget_map.h) that `myoshell rig` plays on any head. The report is a Markdown table of
// every shape's figures and a picture per shape (the target and the fit side by side, coloured by
// displacement). docs/fitting.md, "Fitting a rig".
#include <fmt/core.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/retarget_map_file.h"
#include "myoshell/io/rig_file.h"
#include "myoshell/io/rig_fitting.h"
#include "myoshell/muscles/muscle_def.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/face_picture.h"
#include "myoshell/render/png.h"
#include "resources.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct FitRigArgs {
  std::string rig;
  HeadOptions head;
  std::string library = defaultMuscleLibrary();
  std::string lambda = "0.02";
  std::string out;
  std::string report;
  std::string cacheDir;
  bool json = false;
};

nlohmann::ordered_json namedValuesJson(const NamedValues& values) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [name, v] : values) j[name] = v;
  return j;
}

std::string activationList(const NamedValues& values) {
  std::string out;
  for (const auto& [name, v] : values) out += fmt::format("{}{} {:.2f}", out.empty() ? "" : ", ", name, v);
  return out.empty() ? "none" : out;
}

// Target and fit side by side, front view on the face, coloured by |u| on the target's scale.
Image shapePicture(const FaceSystem& face, FacePainter& painter, const RigShapeFit& s, int size) {
  const Camera camera = faceCamera(face, ViewPreset::front, size, size, FaceFraming::face);
  FaceOverlays overlays;
  overlays.displacement = true;
  overlays.displacementScale = std::max(1e-3, s.target.rowwise().norm().maxCoeff());
  auto tile = [&](const MatX3& u) {
    FaceFrameState state;
    state.skin = face.head().mesh.V + u;
    state.displacement = u;
    return painter.paint(faceScene(face, state, camera, size, size, overlays));
  };
  ContactSheetStyle style;
  style.columns = 2;
  const std::string fitCaption =
      s.fit ? fmt::format("fit: cos {:.2f}, RMS {:.1f} mm", s.fit->metric.cosine, s.fit->rmsMm) : "not fitted";
  return withCaption(contactSheet({tile(s.target), tile(s.fit->displacement)},
                                  {"target", fitCaption}, style),
                     s.name + (s.correctiveOf.empty() ? "" : " (on " + s.correctiveOf + ")"), 2);
}

// DIR/report.md (the table) and DIR/<shape>.png (the pictures). Returns the files written.
std::vector<std::string> writeReport(const fs::path& dir, const FaceSystem& face, const RigFit& fit, const std::string& rig) {
  std::vector<std::string> written;
  const auto painter = softwarePainter();
  std::string md = fmt::format(
      "# fit-rig report: {}\n\nHead {} ({} vertices), anatomical model, {} muscles. Cosine and magnitude ratio over the "
      "vertices where the target or the fit moves more than 0.5 mm; RMS and maximum error there, in mm "
      "(docs/fitting.md). A left/right pair the rig has both of is fitted together: the right shape's activations are the "
      "left's mirror image, each side's figures its own.\n\n| shape | cosine | magnitude ratio | RMS mm | max mm | activations |\n|---|---|---|---|---|---|\n",
      rig, face.head().name, face.head().mesh.vertexCount(), face.muscleCount());
  for (size_t i = 0; i < fit.shapes.size(); ++i) {
    const RigShapeFit& s = fit.shapes[i];
    const RetargetShape& entry = *fit.map.find(s.name);
    if (!s.reachable) {
      md += fmt::format("| {} | — | — | — | — | not fitted: {} |\n", s.name, s.reason);
      continue;
    }
    const std::string png = s.name + ".png";
    writePng((dir / png).string(), shapePicture(face, *painter, s, 320));
    written.push_back((dir / png).string());
    md += fmt::format("| [{}]({}){} | {:.3f} | {:.3f} | {:.2f} | {:.2f} | {} |\n", s.name, png,
                      s.correctiveOf.empty() ? "" : " (on " + s.correctiveOf + ")", s.fit->metric.cosine,
                      s.fit->metric.magnitudeRatio, s.fit->rmsMm, s.fit->maxMm, activationList(entry.activations));
  }
  md += fmt::format("\nMedian over the reachable shapes: cosine {:.3f}, RMS {:.2f} mm.\n", fit.medianCosine, fit.medianRmsMm);
  if (!fit.skipped.empty()) {
    md += "\nNot ARKit names, not fitted:";
    for (const std::string& n : fit.skipped) md += " " + n;
    md += "\n";
  }
  writeFileAtomically((dir / "report.md").string(), md);
  written.push_back((dir / "report.md").string());
  return written;
}

int runFitRig(FitRigArgs& a) {
  const Stopwatch total;
  FitSettings settings;
  settings.lambda = parseLambda(a.lambda);
  checkOutputFile(a.out, "--out", "map file (JSON)");
  if (!a.report.empty()) checkOutputFolder(a.report, "--report");

  const RigFile rig = readRig(a.rig);
  resolveRigBaseLandmarks(a.head, rig, a.cacheDir);
  const SceneInputs inputs = rigFitInputs(rig, fitHeadOptions(a.head, a.library));
  const auto cache = openBasisCache(a.cacheDir);
  const FittedRig fitted = fitRigShapes(rig, inputs, a.library, settings, cache.get());
  const RigFit& fit = fitted.fit;
  const AnatomicalFace& face = *fitted.face;
  const Head& head = face.head();
  const double buildSeconds = fitted.buildSeconds;
  for (const std::string& n : fit.skipped)
    fmt::print(stderr, "myoshell fit-rig: warning: {}: shape '{}' is no ARKit name; not fitted\n", a.rig, n);

  if (!a.out.empty()) writeRetargetMapFile(a.out, fit.map);
  std::vector<std::string> reportFiles;
  if (!a.report.empty()) {
    fs::create_directories(a.report);
    reportFiles = writeReport(a.report, face, fit, fs::path(a.rig).filename().string());
  }

  if (a.json) {
    nlohmann::ordered_json shapes = nlohmann::ordered_json::array();
    for (size_t i = 0; i < fit.shapes.size(); ++i) {
      const RigShapeFit& s = fit.shapes[i];
      nlohmann::ordered_json j;
      j["name"] = s.name;
      j["reachable"] = s.reachable;
      j["reason"] = s.reason;
      j["sources"] = s.sources;
      if (!s.correctiveOf.empty()) j["corrective_of"] = s.correctiveOf;
      const bool f = s.fit.has_value();
      j["cosine"] = f ? nlohmann::ordered_json(s.fit->metric.cosine) : nlohmann::ordered_json();
      j["magnitude_ratio"] = f ? nlohmann::ordered_json(s.fit->metric.magnitudeRatio) : nlohmann::ordered_json();
      j["rms_mm"] = f ? nlohmann::ordered_json(s.fit->rmsMm) : nlohmann::ordered_json();
      j["max_mm"] = f ? nlohmann::ordered_json(s.fit->maxMm) : nlohmann::ordered_json();
      j["compared_vertices"] = f ? s.fit->metric.comparedVertices : 0;
      // The map's entry by name: the map holds every ARKit name, the fit only the rig's fitted ones.
      const RetargetShape& entry = *fit.map.find(s.name);
      j["activations"] = namedValuesJson(entry.activations);
      j["jaw"] = namedValuesJson(entry.jaw);
      shapes.push_back(j);
    }
    nlohmann::ordered_json j;
    j["rig"] = a.rig;
    j["head"] = head.name;
    j["shapes"] = shapes;
    j["median_cosine"] = fit.medianCosine;
    j["median_rms_mm"] = fit.medianRmsMm;
    j["skipped"] = fit.skipped;
    j["out"] = a.out.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(a.out);
    j["report"] = a.report.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(a.report);
    j["build_seconds"] = buildSeconds;
    j["fit_seconds"] = fit.seconds;
    j["seconds"] = total.seconds();
    printJsonReport(j);
    return kExitOk;
  }
  for (size_t i = 0; i < fit.shapes.size(); ++i) {
    const RigShapeFit& s = fit.shapes[i];
    if (!s.reachable) {
      fmt::print("  {:<20} not fitted: {}\n", s.name, s.reason);
      continue;
    }
    fmt::print("  {:<20} cosine {:6.3f}  ratio {:5.2f}  RMS {:5.2f} mm  max {:5.2f} mm  {}\n", s.name, s.fit->metric.cosine,
               s.fit->metric.magnitudeRatio, s.fit->rmsMm, s.fit->maxMm, activationList(fit.map.find(s.name)->activations));
  }
  fmt::print("fit-rig of {} on {}: {} shapes, median cosine {:.3f}, median RMS {:.2f} mm ({:.1f} s fitting, {:.1f} s in "
             "all)\n",
             a.rig, head.name, fit.shapes.size(), fit.medianCosine, fit.medianRmsMm, fit.seconds, total.seconds());
  if (!a.out.empty()) fmt::print("wrote {}\n", a.out);
  if (!a.report.empty()) fmt::print("wrote {} ({} files)\n", (fs::path(a.report) / "report.md").string(), reportFiles.size());
  return kExitOk;
}

static CommandRegistrar registerFitRig("fit-rig", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<FitRigArgs>();
  CLI::App* sub = app.add_subcommand(
      "fit-rig", "Fit every ARKit-named shape of a glTF rig to activations and write the retargeting map that "
                 "`myoshell rig` plays on any head (docs/fitting.md)");
  sub->add_option("rig", args->rig, "a glTF 2.0 rig (.glb or .gltf) with named morph targets")->required();
  HeadHelp help;
  help.headDefault = "the rig's base mesh (its landmarks found automatically without --landmarks)";
  help.landmarks = " or of the rig's base";
  addHeadOptions(*sub, args->head, help);
  sub->add_option("--lambda", args->lambda, "sparsity weight ≥ 0 (default 0.02; 0 = plain bounded least squares)");
  sub->add_option("--out", args->out, "write the retargeting map (JSON; its folder must exist)");
  sub->add_option("--report", args->report, "write report.md and a picture per shape into this folder");
  addLibraryOption(*sub, args->library);
  addCacheOption(*sub, args->cacheDir);
  addJsonFlag(*sub, args->json);
  addThreadsOption(*sub);
  return [args] {
    resolveHeadLandmarks(args->head, args->cacheDir);
    return runFitRig(*args);
  };
});

}  // namespace
}  // namespace myo::cli
