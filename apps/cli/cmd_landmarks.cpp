// `myoshell landmarks HEAD.obj [--units auto|m|cm|mm] [--out FILE] [--picture PNG] [--json]
// [--compare FILE]`: finds the head's landmarks (head/auto_landmarks.h) and writes them as a
// landmark file in the layout of docs/heads.md (usable as --landmarks, with a confidence per
// point), a picture of the points on the head from the front and the side, and with --compare the
// distance of each found point from a given landmark file's.
#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "command.h"
#include "common_options.h"
#include "job_report.h"
#include "resources.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/auto_landmarks.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/auto_landmark_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/contact_sheet.h"
#include "myoshell/render/image.h"
#include "myoshell/render/markers.h"
#include "myoshell/render/png.h"
#include "myoshell/render/render_mesh.h"

namespace myo::cli {
namespace {

struct LandmarksArgs {
  std::string head;
  std::string units = "auto";
  std::string out;
  std::string picture;
  std::string compare;
  std::string cacheDir;
  bool json = false;
};

nlohmann::ordered_json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Front and side views with the 68 points red (yellow when their confidence is under 0.5) and the
// named points blue, side by side.
void drawPicture(const TriMesh& mesh, const AutoLandmarks& a, const std::string& path) {
  const int ss = 2, W = 600 * ss;
  std::vector<Image> tiles;
  for (const ViewPreset view : {ViewPreset::front, ViewPreset::profile}) {
    Camera camera = presetCamera(ViewFrame{a.frame.origin, a.frame.axes, a.frame.scale}, view);
    fitToBounds(camera, mesh.V, W, W, 0.04);
    Image image(W, W, Rgb(0.16, 0.17, 0.20));
    DepthBuffer depth(W, W);
    RenderStyle style;
    style.color = Rgb(0.93, 0.78, 0.68);
    style.backColor = Rgb(0.55, 0.60, 0.75);
    renderMesh(image, depth, camera, mesh.V, mesh.F, style);
    std::vector<Marker> markers;
    auto at = [&](int v) { return Vec3(mesh.V.row(v).transpose()); };
    for (int k = 0; k < 68; ++k)
      markers.push_back({at(a.landmarks.multipie68[k]),
                         a.confidence68[k] < 0.5 ? Rgb(1.0, 0.85, 0.1) : Rgb(230, 30, 30) / 255.0, 3.5 * ss});
    for (const auto& [name, v] : a.landmarks.named) markers.push_back({at(v), Rgb(40, 110, 255) / 255.0, 1.8 * ss});
    MarkerStyle ms;
    ms.depthTolerance = 0.02 * camera.orthoHeight;
    ms.outlineWidth = 0.8 * ss;
    drawMarkers(image, &depth, camera, markers, ms);
    tiles.push_back(downsample(image, ss));
  }
  ContactSheetStyle cs;
  cs.columns = 2;
  cs.background = Rgb(0.16, 0.17, 0.20);
  writePng(path, contactSheet(tiles, {}, cs));
}

int runLandmarks(const LandmarksArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  AutoLandmarkOptions options;
  if (a.units != "auto") {
    try {
      options.unit = parseLengthUnit(a.units);
    } catch (const InputError& e) {
      throw InputError("--units: " + e.message() + " or auto");
    }
  }
  const std::string out =
      a.out.empty() ? std::filesystem::path(a.head).stem().string() + ".landmarks.json" : a.out;
  checkOutputFile(out, "--out", "landmark file");
  checkOutputFile(a.picture, "--picture", "PNG file");
  const TriMesh mesh = readObj(a.head);
  AutoLandmarks found = findLandmarks(mesh, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeFileAtomically(out, autoLandmarkFileText(found, a.head), "cannot write landmark file");
  // Kept in the cache too: later commands on this OBJ reuse it, and check a file given as --landmarks against it.
  try {
    storeAutoLandmarks(a.head, found, cacheDir(a.cacheDir).dir);
  } catch (const InputError& e) {
    found.warnings.push_back(std::string("not kept in the cache: ") + e.what());
  }
  if (!a.picture.empty()) drawPicture(mesh, found, a.picture);

  const double cm = centimetresPer(found.unit);
  nlohmann::ordered_json j;
  j["head"] = a.head;
  j["landmark_file"] = out;
  if (!a.picture.empty()) j["picture"] = a.picture;
  j["units"] = lengthUnitName(found.unit);
  j["units_inferred"] = found.unitInferred;
  j["landmarks"] = nlohmann::ordered_json::object();
  for (const auto& [name, v] : found.landmarks.resolved()) j["landmarks"][name] = v;
  j["multipie68"] = found.landmarks.multipie68;
  j["confidence"]["multipie68"] = found.confidence68;
  j["confidence"]["named"] = found.namedConfidence;
  const FaceFrame& f = found.frame;
  j["frame"] = {{"origin", vec(f.origin)}, {"x", vec(f.axes.col(0))}, {"y", vec(f.axes.col(1))},
                {"z", vec(f.axes.col(2))}, {"scale", f.scale}};
  j["eyes"] = found.eyesOpen ? "open" : "closed";
  j["mouth"] = found.mouthOpen ? "open" : "closed";
  j["skin_vertices"] = found.skinVertices;
  j["other_pieces"] = found.otherPieces;
  j["placement_rms_mm"] = found.placementRmsMm;
  j["fit_mean_distance_mm"] = 10.0 * found.fitMeanDistanceCm;
  j["seconds"] = seconds;
  j["warnings"] = found.warnings;

  // --compare: distances (mm) from a given landmark file's points.
  struct Row {
    std::string name;
    double mm;
  };
  std::vector<Row> rows;
  if (!a.compare.empty()) {
    const Landmarks given = readLandmarks(a.compare, mesh.vertexCount());
    // 1-based ids and swapped sides are errors (exit 2); points far from the automatic ones warnings.
    for (const std::string& w : checkGivenLandmarks(mesh, given, found)) found.warnings.push_back(w);
    j["warnings"] = found.warnings;
    auto dist = [&](int u, int v) { return 10.0 * cm * (mesh.V.row(u) - mesh.V.row(v)).norm(); };
    if (given.multipie68.size() == 68)
      for (int k = 0; k < 68; ++k)
        rows.push_back({fmt::format("multipie{}", k), dist(given.multipie68[k], found.landmarks.multipie68[k])});
    for (const auto& [name, v] : given.named)
      if (found.landmarks.has(name)) rows.push_back({name, dist(v, found.landmarks.vertex(name))});
    auto summary = [&](int from, int to) {
      double mean = 0.0, mx = 0.0;
      for (int k = from; k < to; ++k) {
        mean += rows[static_cast<size_t>(k)].mm / (to - from);
        mx = std::max(mx, rows[static_cast<size_t>(k)].mm);
      }
      return nlohmann::ordered_json{{"points", to - from}, {"mean_mm", mean}, {"max_mm", mx}};
    };
    nlohmann::ordered_json c;
    c["file"] = a.compare;
    const int n68 = given.multipie68.size() == 68 ? 68 : 0;
    if (n68) {
      c["multipie68"] = summary(0, 68);
      c["jaw_0_16"] = summary(0, 17);
      c["off_jaw_17_67"] = summary(17, 68);
    }
    if (static_cast<int>(rows.size()) > n68) c["named"] = summary(n68, static_cast<int>(rows.size()));
    c["all"] = summary(0, static_cast<int>(rows.size()));
    for (const Row& r : rows) c["points_mm"][r.name] = r.mm;
    j["compare"] = c;
  }

  if (a.json) {
    printJsonReport(j);
    return kExitOk;
  }
  fmt::print("landmarks of {}: {} Multi-PIE points and {} named found in {:.1f} s (units {}{})\n", a.head,
             found.landmarks.multipie68.size(), found.landmarks.named.size(), seconds, lengthUnitName(found.unit),
             found.unitInferred ? ", inferred from the size" : "");
  fmt::print("eyes {}, mouth {}; skin {} vertices, {} other piece(s) left out\n", found.eyesOpen ? "open" : "closed",
             found.mouthOpen ? "open" : "closed", found.skinVertices, found.otherPieces);
  for (const std::string& w : found.warnings) fmt::print("warning: {}\n", w);
  if (j.contains("compare")) {
    const auto& c = j["compare"];
    for (const char* key : {"multipie68", "jaw_0_16", "off_jaw_17_67", "named", "all"})
      if (c.contains(key))
        fmt::print("against {}: {:<14} {:>3} points, mean {:.2f} mm, max {:.2f} mm\n", a.compare, key,
                   c[key]["points"].get<int>(), c[key]["mean_mm"].get<double>(), c[key]["max_mm"].get<double>());
  }
  fmt::print("wrote {}\n", out);
  if (!a.picture.empty()) fmt::print("wrote {}\n", a.picture);
  return kExitOk;
}

static CommandRegistrar registerLandmarks("landmarks", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<LandmarksArgs>();
  CLI::App* sub = app.add_subcommand(
      "landmarks", "Find a head's 68 Multi-PIE and named landmarks automatically (any pose and unit) and "
                   "write them as a landmark file for --landmarks");
  sub->add_option("head", args->head, "the head as an OBJ file")->required();
  sub->add_option("--units", args->units, "the mesh's unit: auto (from its size), m, cm or mm")->capture_default_str();
  sub->add_option("--out", args->out, "landmark file to write (default: HEAD's stem + .landmarks.json, here)");
  sub->add_option("--picture", args->picture, "write a PNG of the points on the head, front and side");
  sub->add_option("--compare", args->compare, "a landmark file of the same mesh: report each point's distance (mm); ids that look 1-based or sides swapped exit 2, points over 1.5 cm off warn");
  addCacheOption(*sub, args->cacheDir);  // it keeps the landmarks too (later commands reuse them and check a given file)
  addJsonFlag(*sub, args->json);
  return [args] { return runLandmarks(*args); };
});

}  // namespace
}  // namespace myo::cli
