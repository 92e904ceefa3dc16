// `myoshell head [default|OBJ|DIR] [--landmarks FILE] [--pins FILE] [--units m|mm|cm] [--json]
// [--render PNG]`:
// loads a head, reports its counts, boundary loops, whether its eyes are open (and so whether the
// anatomical model gives it lids), landmarks, face frame and gravity pins, and renders a picture
// with the landmarks (and optionally the pins) marked. The built-in head is shown as the anatomical
// model uses it (eyes open); --closed-eyes shows the thesis model's.
//
// The picture comes from the render layer (orthographic camera preset about the face frame, fitted
// to the head; smooth two-sided shading, z-buffer, 2×2 supersampling; PNG via stb). Views: front,
// threequarter (35° toward the subject's right), side (the subject's right profile), back.
// Markers: Multi-PIE 68 points red, named landmarks blue, gravity pins green (--pins-marked); a
// named landmark that is also a Multi-PIE point shows as a blue dot in a red ring; markers hidden
// behind the surface are not drawn.
#include <fmt/core.h>

#include <sstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/subdivision.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/face_picture.h"
#include "myoshell/render/image.h"
#include "myoshell/render/markers.h"
#include "myoshell/render/png.h"
#include "myoshell/render/render_mesh.h"
#include "option_checks.h"

namespace myo::cli {
namespace {

// ---------------------------------------------------------------------------------------------
// Picture: the render layer's software renderer, drawn at 2× and downsampled.

struct RenderOptions {
  int size = 800;                       // output width and height, pixels
  ViewPreset view = ViewPreset::front;  // camera preset about the head's face frame
  bool wire = false;                    // draw the triangle edges
  bool markLandmarks = true;
  bool markPins = false;
};

void renderHead(const Head& head, const RenderOptions& opt, const std::string& path) {
  const int ss = 2, W = opt.size * ss;
  const TriMesh& m = head.mesh;
  const FaceFrame f = head.frame();
  Camera camera = presetCamera(ViewFrame{f.origin, f.axes, f.scale}, opt.view);
  fitToBounds(camera, m.V, W, W, 0.04);

  Image image(W, W, Rgb(0.16, 0.17, 0.20));
  DepthBuffer depth(W, W);
  RenderStyle style;
  style.color = Rgb(0.93, 0.78, 0.68);
  style.backColor = Rgb(0.55, 0.60, 0.75);  // the inside of the open head
  style.wireframe = opt.wire;
  style.wireColor = Rgb(0.42, 0.33, 0.30);
  style.wireWidth = 1.8 * ss;
  renderMesh(image, depth, camera, m.V, m.F, style);

  // Landmarks red, named landmarks blue on top (a red ring: also a Multi-PIE point), pins green.
  std::vector<Marker> markers;
  auto at = [&](int v) { return Vec3(m.V.row(v).transpose()); };
  if (opt.markPins)
    for (int v : head.gravityPins) markers.push_back({at(v), Rgb(40, 200, 60) / 255.0, 2.2 * ss});
  if (opt.markLandmarks) {
    for (int v : head.landmarks.multipie68) markers.push_back({at(v), Rgb(230, 30, 30) / 255.0, 3.5 * ss});
    for (const auto& [name, v] : head.landmarks.named)
      markers.push_back({at(v), Rgb(40, 110, 255) / 255.0, 1.8 * ss});
  }
  MarkerStyle ms;
  ms.depthTolerance = 0.02 * camera.orthoHeight;  // cm: hidden when this far behind the surface
  ms.outlineWidth = 0.8 * ss;
  drawMarkers(image, &depth, camera, markers, ms);
  writePng(path, downsample(image, ss));
}

// ---------------------------------------------------------------------------------------------

struct HeadArgs {
  HeadOptions head;  // the positional head, --landmarks and --units
  std::string pins;
  bool json = false;
  std::string render;
  std::string view = "front";
  int size = 800;
  bool wire = false;
  bool markPins = false;
  bool noLandmarks = false;
  int levels = 2;
  bool closedMouth = false;
  bool closedEyes = false;
  std::string writeObj;
  std::string writeLandmarks;
  std::string cacheDir;  // where the landmarks of an OBJ without --landmarks are kept
};

Head loadFromArgs(const HeadArgs& a) {
  const HeadFiles files = resolveHeadArgument(a.head.head, a.head.landmarks, a.pins, a.head.units);
  if (!files.builtIn()) return loadHead(files.obj, files.landmarks, files.pins, files.unit);
  DefaultHeadOptions o = defaultHeadOptions(a.closedEyes ? FaceModelKind::Thesis : FaceModelKind::Anatomical);
  o.subdivisionLevels = a.levels;
  o.openMouth = !a.closedMouth;
  return loadDefaultHead(o);
}

nlohmann::ordered_json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

int runHead(const HeadArgs& a) {
  const ViewPreset view = parseView(a.view);  // before any work: a typo fails at once
  checkOutputFile(a.render, "--render", "PNG file");
  checkOutputFile(a.writeObj, "--write-obj", "OBJ file");
  checkOutputFile(a.writeLandmarks, "--write-landmarks", "landmark file");
  const Head head = loadFromArgs(a);
  const TriMesh& m = head.mesh;
  const EdgeTable edges = buildEdgeTable(m.F, m.vertexCount());
  const auto loops = boundaryLoops(m.F, m.vertexCount());
  const FaceFrame f = head.frame();
  const Vec3 lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const bool eyesOpen = hasOpenEyes(m, head.landmarks);  // the anatomical model gives it lids
  // The built-in head is each model's own: which one this is.
  const std::string usedBy = head.name != "default" ? "" : a.closedEyes ? "thesis" : "anatomical";

  nlohmann::ordered_json j;
  j["name"] = head.name;
  j["source"] = m.sourcePath;
  if (head.name == "default") j["source_sha256"] = defaultHeadSourceSha256();
  j["vertices"] = m.vertexCount();
  j["triangles"] = m.triangleCount();
  j["edges"] = edges.edges.size();
  j["boundary_loops"] = nlohmann::ordered_json::array();
  for (const auto& l : loops) j["boundary_loops"].push_back(l.size());
  j["eyes"] = eyesOpen ? "open" : "closed";
  if (!usedBy.empty()) j["model"] = usedBy;
  j["bbox_cm"] = {{"min", vec(lo)}, {"max", vec(hi)}};
  j["landmarks"]["file"] = head.landmarks.sourcePath;
  j["landmarks"]["multipie68"] = head.landmarks.multipie68.size();
  j["landmarks"]["named"] = head.landmarks.named.size();
  j["landmarks"]["required"] = nlohmann::ordered_json::object();
  for (const RequiredLandmark& r : kRequiredLandmarks)
    j["landmarks"]["required"][r.name] = head.landmarks.vertex(r.name);
  j["frame"] = {{"origin", vec(f.origin)}, {"x", vec(f.axes.col(0))}, {"y", vec(f.axes.col(1))},
                {"z", vec(f.axes.col(2))}, {"scale", f.scale}};
  j["gravity_pins"] = {{"count", head.gravityPins.size()}, {"source", head.pinsSource}};

  if (!a.writeObj.empty()) {
    // The head's triangles as OBJ; the resolved landmarks go into "# landmark NAME ID" comments.
    std::ostringstream out;
    out << "# " << head.name << " head written by myoshell head\n";
    for (const auto& [name, v] : head.landmarks.resolved()) out << "# landmark " << name << " " << v << "\n";
    for (int i = 0; i < m.vertexCount(); ++i)
      out << fmt::format("v {:.9g} {:.9g} {:.9g}\n", m.V(i, 0), m.V(i, 1), m.V(i, 2));
    for (int t = 0; t < m.triangleCount(); ++t)
      out << "f " << m.F(t, 0) + 1 << ' ' << m.F(t, 1) + 1 << ' ' << m.F(t, 2) + 1 << "\n";
    writeFileAtomically(a.writeObj, out.str(), "cannot write OBJ");
    j["obj"] = a.writeObj;
  }
  if (!a.writeLandmarks.empty()) {
    writeFileAtomically(a.writeLandmarks, landmarksToJson(head.landmarks), "cannot write landmark file");
    j["landmark_file"] = a.writeLandmarks;
  }
  if (!a.render.empty()) {
    RenderOptions ro;
    ro.size = a.size;
    ro.view = view;
    ro.wire = a.wire;
    ro.markPins = a.markPins;
    ro.markLandmarks = !a.noLandmarks;
    renderHead(head, ro, a.render);
    j["render"] = a.render;
  }

  if (a.json) {
    printJsonReport(j);
    return kExitOk;
  }
  fmt::print("head {}: {} vertices, {} triangles, {} boundary loop(s)", head.name, m.vertexCount(),
             m.triangleCount(), loops.size());
  if (!loops.empty()) {
    fmt::print(" (edges:");
    for (const auto& l : loops) fmt::print(" {}", l.size());
    fmt::print(")");
  }
  fmt::print("\neyes: {}", eyesOpen ? "open (the anatomical model gives it lids)" : "closed (no lids)");
  if (!usedBy.empty()) fmt::print("; the {} model's built-in head", usedBy);
  fmt::print("\nlandmarks: {} Multi-PIE points, {} named, all {} required names resolved ({})\n",
             head.landmarks.multipie68.size(), head.landmarks.named.size(), kRequiredLandmarks.size(),
             head.landmarks.sourcePath);
  fmt::print("frame: origin ({:.3f}, {:.3f}, {:.3f}) cm, scale {:.3f} cm, z ({:.3f}, {:.3f}, {:.3f})\n",
             f.origin.x(), f.origin.y(), f.origin.z(), f.scale, f.axes(0, 2), f.axes(1, 2),
             f.axes(2, 2));
  fmt::print("gravity pins: {} ({})\n", head.gravityPins.size(), head.pinsSource);
  if (!a.render.empty()) fmt::print("wrote {}\n", a.render);
  return kExitOk;
}

static CommandRegistrar registerHead("head", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<HeadArgs>();
  CLI::App* sub = app.add_subcommand(
      "head", "Load a head (the built-in default, an OBJ with or without a landmark file, or a folder like "
              "../shared/data/ict) and report counts, landmarks, face frame and gravity pins");
  sub->add_option("head", args->head.head, "'default', an OBJ file, or a folder with head_skin.obj, "
                                           "landmarks_multipie68.json and rigid_vertices.json");
  addHeadFileOptions(*sub, args->head);
  addCacheOption(*sub, args->cacheDir);  // it keeps the landmarks found for an OBJ without --landmarks
  sub->add_option("--pins", args->pins, "vertex-set file of gravity pins (default: the rim rule)");
  addJsonFlag(*sub, args->json);
  sub->add_option("--render", args->render, "write a PNG picture with the landmarks marked");
  sub->add_option("--view", args->view, "front, three-quarter, profile or back")->capture_default_str();
  sub->add_option("--size", args->size, "picture size in pixels")->check(wholeIn(64, 4096))->capture_default_str();
  sub->add_flag("--wire", args->wire, "draw the triangle edges");
  sub->add_flag("--pins-marked", args->markPins, "mark the gravity pins (green)");
  sub->add_flag("--no-landmarks", args->noLandmarks, "do not mark the landmarks");
  sub->add_option("--levels", args->levels, "default head: subdivision levels (default 2)")
      ->check(wholeIn(0, 4));
  sub->add_flag("--closed-mouth", args->closedMouth, "default head: keep the mouth closed");
  sub->add_flag("--closed-eyes", args->closedEyes,
                "default head: keep the eyes closed (the thesis model's head; the anatomical model's has them open)");
  sub->add_option("--write-obj", args->writeObj, "write the head as OBJ (landmarks in comments)");
  sub->add_option("--write-landmarks", args->writeLandmarks, "write the head's landmark file");
  return [args] {
    resolveHeadLandmarks(args->head, args->cacheDir);
    return runHead(*args);
  };
});

}  // namespace
}  // namespace myo::cli
