// `myoshell demo`: the engine on the built-in default head, end to end, in well under a minute.
// Until the face model lands it shows the modal-warping engine under gravity (the thesis's
// Fig. 22 set-up): the default head pinned at its rim and nose bridge sags under 981 cm/s²,
// and, when ../shared is present (or --ict-dir is given), the ICT head does the same with its
// rigid vertices pinned. Writes an OBJ sequence and stats.json under --out.
#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "myoshell/core/timer.h"
#include "myoshell/face/head.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  std::string outDir = "out/demo";
  std::string cacheDir = ".cache/bases";
  std::string ictDir;  // empty: ../shared/data/ict beside the working directory, if present
  int modes = 30;
  double seconds = 1.0;
  double dt = 1.0 / 240.0;
  int frameEvery = 8;  // write one OBJ every this many steps (30 fps at dt = 1/240)
};

// Skin material of the demo (cm–g–s): soft enough that gravity visibly sags the unsupported cheeks
// (the thesis's Fig. 22 shows the same effect as stiffness decreases).
ShellMaterial demoSkin() {
  ShellMaterial m;
  m.kA = 3.0e3;       // dyn/cm
  m.kL = 3.0e2;       // dyn
  m.kB = 2.0e2;       // erg
  m.density = 1.1;    // g/cm³
  m.thickness = 0.3;  // cm
  return m;
}

nlohmann::json sagHead(const Head& head, const DemoOptions& opt, FileBasisCache& cache,
                       const fs::path& outDir) {
  const TriMesh& mesh = head.mesh;
  const EdgeTable edges = buildEdgeTable(mesh.F, mesh.vertexCount());
  const DiscreteShell shell(mesh.V, mesh.F, edges, demoSkin());

  ModalSettings modal;
  modal.modeCount = opt.modes;
  Stopwatch precompute;
  auto basis = std::make_shared<const ModalBasis>(computeModalBasis(shell, head.gravityPins, modal, &cache));
  const double precomputeSeconds = precompute.seconds();

  // Gravity on the free vertices: f_i = m_i·g, g = 981 cm/s² down (−y).
  MatX3 gravity(basis->freeCount(), 3);
  for (int i = 0; i < basis->freeCount(); ++i) gravity.row(i) << 0.0, -981.0 * basis->freeMass(i), 0.0;
  const LoadParticipation participation = loadParticipation(*basis, shell, gravity);

  ModalWarpingSettings settings;
  settings.dt = opt.dt;
  settings.rayleighMass = 8.0;           // ξ, 1/s: settles within about a second
  settings.rayleighStiffness = 2.0e-4;   // ζ, s
  settings.channel = head.name + "/gravity";
  ModalWarpingIntegrator integrator(basis, settings);

  fs::create_directories(outDir);
  writeObj((outDir / (head.name + "_rest.obj")).string(), mesh);
  const int steps = static_cast<int>(std::lround(opt.seconds / opt.dt));
  MatX3 positions = mesh.V;
  double stepSeconds = 0.0;
  int framesWritten = 0;
  for (int s = 1; s <= steps; ++s) {
    Stopwatch sw;
    integrator.step(gravity);
    stepSeconds += sw.seconds();
    if (s % opt.frameEvery == 0 || s == steps) {
      positions = mesh.V;
      integrator.addDisplacementTo(positions);
      writeObj((outDir / fmt::format("{}_gravity_{:04d}.obj", head.name, framesWritten++)).string(),
               mesh, &positions);
    }
  }
  const MatX3& u = integrator.freeDisplacement();
  Eigen::Index worst = 0;
  const double maxSag = u.rowwise().norm().maxCoeff(&worst);

  // The linear (unwarped) static response for comparison: the warped result should stay close
  // for this small-rotation load.
  const StaticSolveResult linear = solveStaticLinear(*basis, gravity);
  const double linearMax = linear.u.rowwise().norm().maxCoeff();

  nlohmann::json j;
  j["head"] = head.name;
  j["vertices"] = mesh.vertexCount();
  j["triangles"] = mesh.triangleCount();
  j["pinned"] = static_cast<int>(head.gravityPins.size());
  j["free_vertices"] = basis->freeCount();
  j["modes"] = basis->modeCount();
  j["basis_from_cache"] = basis->fromCache;
  j["precompute_seconds"] = precomputeSeconds;
  j["load_participation"] = participation.ratio;
  j["steps"] = steps;
  j["dt"] = opt.dt;
  j["step_ms_mean"] = 1e3 * stepSeconds / steps;
  j["steps_per_second"] = steps / stepSeconds;
  j["max_sag_cm"] = maxSag;
  j["max_sag_vertex"] = basis->freeVertices[static_cast<size_t>(worst)];
  j["linear_static_max_cm"] = linearMax;
  j["frames_written"] = framesWritten;
  fmt::print("  {:8s} {:6d} vertices, {:5d} free, d = {}, basis {} in {:.2f} s, load participation {:.3f}\n",
             head.name, mesh.vertexCount(), basis->freeCount(), basis->modeCount(),
             basis->fromCache ? "loaded" : "solved", precomputeSeconds, participation.ratio);
  fmt::print("           {} steps of {:.4f} s: {:.3f} ms/step ({:.0f} steps/s); max sag {:.3f} cm "
             "(linear static {:.3f} cm)\n",
             steps, opt.dt, 1e3 * stepSeconds / steps, steps / stepSeconds, maxSag, linearMax);
  return j;
}

int runDemo(const DemoOptions& opt) {
  const fs::path out(opt.outDir);
  fs::create_directories(out);
  FileBasisCache cache(opt.cacheDir);
  fmt::print("myoshell demo: gravity on the skin, modal warping (the thesis's Fig. 22 set-up)\n");
  nlohmann::json report;
  report["heads"] = nlohmann::json::array();
  report["heads"].push_back(sagHead(loadDefaultHead(), opt, cache, out));

  fs::path ict = opt.ictDir.empty() ? fs::path("../shared/data/ict") : fs::path(opt.ictDir);
  if (fs::exists(ict / "head_skin.obj")) {
    const Head head = loadHead((ict / "head_skin.obj").string(),
                               (ict / "landmarks_multipie68.json").string(),
                               (ict / "rigid_vertices.json").string());
    report["heads"].push_back(sagHead(head, opt, cache, out));
  } else {
    fmt::print("  (ICT head not found at {}: skipped)\n", ict.string());
  }
  report["cache"] = {{"hits", cache.stats().hits}, {"stores", cache.stats().stores}};

  const fs::path stats = out / "stats.json";
  const fs::path tmp = out / "stats.json.tmp";
  {
    std::ofstream f(tmp);
    f << report.dump(2) << "\n";
    if (!f) throw InputError("cannot write " + tmp.string());
  }
  fs::rename(tmp, stats);
  fmt::print("wrote {} (OBJ frames and stats.json)\n", out.string());
  return kExitOk;
}

const CommandRegistrar registrar("demo", [](CLI::App& app) {
  auto opt = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand("demo", "Run the demo on the built-in default head (and ICT's when present)");
  sub->add_option("--out", opt->outDir, "Output folder")->capture_default_str();
  sub->add_option("--cache", opt->cacheDir, "Basis cache folder")->capture_default_str();
  sub->add_option("--ict-dir", opt->ictDir, "Folder of the ICT-FaceKit head (default ../shared/data/ict)");
  sub->add_option("--modes", opt->modes, "Modes per channel")->capture_default_str()->check(CLI::Range(1, 500));
  sub->add_option("--seconds", opt->seconds, "Simulated time, s")->capture_default_str()->check(CLI::PositiveNumber);
  return std::function<int()>([opt] { return runDemo(*opt); });
});

}  // namespace
}  // namespace myo::cli
