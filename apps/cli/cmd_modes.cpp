// `myoshell modes MESH.obj [--pin PINS.json] [--count N] [--ka --kl --kb --density --thickness]
// [--solver auto|dense|shift-invert] [--json]`: the constrained modal analysis of a shell (thesis
// eq. 8; METHOD.md §2) — the lowest eigenvalues of K Φ = M Φ Λ with the pinned vertices removed.
#include <fmt/core.h>

#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/vertex_set_file.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo::cli {

namespace {

struct ModesArgs {
  std::string mesh, pins;
  int count = 20;
  std::string solver = "auto";
  ShellMaterial material;
  bool json = false;
};

int runModes(const ModesArgs& args) {
  args.material.validate();
  if (args.count < 1) throw InputError("--count must be at least 1");
  static const std::map<std::string, EigenSolverKind> kinds = {
      {"auto", EigenSolverKind::Auto}, {"dense", EigenSolverKind::Dense}, {"shift-invert", EigenSolverKind::ShiftInvert}};
  const auto kind = kinds.find(args.solver);
  if (kind == kinds.end()) throw InputError("--solver must be auto, dense or shift-invert, not '" + args.solver + "'");

  const TriMesh mesh = readObj(args.mesh);
  const std::vector<int> pins = args.pins.empty() ? std::vector<int>{} : readVertexSet(args.pins, mesh.vertexCount());
  const DiscreteShell shell(mesh.V, mesh.F, buildEdgeTable(mesh.F, mesh.vertexCount()), args.material);
  ModalSettings settings;
  settings.modeCount = args.count;
  settings.solver = kind->second;
  const ModalBasis basis = computeModalBasis(shell, pins, settings);

  if (args.json) {
    nlohmann::ordered_json j;
    j["eigenvalues"] = std::vector<double>(basis.lambda.data(), basis.lambda.data() + basis.modeCount());
    nlohmann::ordered_json freqs = nlohmann::ordered_json::array();
    for (int k = 0; k < basis.modeCount(); ++k)
      freqs.push_back(std::sqrt(std::max(basis.lambda[k], 0.0)) / (2.0 * std::numbers::pi));
    j["frequencies_hz"] = freqs;
    j["solve_seconds"] = basis.solveSeconds;
    j["solver"] = basis.solver;
    j["vertices"] = mesh.vertexCount();
    j["free_vertices"] = basis.freeCount();
    j["pinned_vertices"] = mesh.vertexCount() - basis.freeCount();
    j["modes"] = basis.modeCount();
    printJsonReport(j);
  } else {
    fmt::print("{}: {} vertices, {} free, {} modes ({} solver, {:.3f} s)\n", args.mesh, mesh.vertexCount(),
               basis.freeCount(), basis.modeCount(), basis.solver, basis.solveSeconds);
    fmt::print("  {:>4}  {:>16}  {:>14}  {:>12}\n", "mode", "lambda (1/s²)", "omega (rad/s)", "f (Hz)");
    for (int k = 0; k < basis.modeCount(); ++k) {
      const double w = std::sqrt(std::max(basis.lambda[k], 0.0));
      fmt::print("  {:>4}  {:>16.8g}  {:>14.6g}  {:>12.6g}\n", k, basis.lambda[k], w, w / (2.0 * std::numbers::pi));
    }
  }
  return kExitOk;
}

}  // namespace

static CommandRegistrar registerModes("modes", [](CLI::App& app) {
  auto* sub = app.add_subcommand("modes", "Constrained modal analysis: the lowest eigenvalues of K phi = lambda M phi");
  auto args = std::make_shared<ModesArgs>();
  sub->add_option("mesh", args->mesh, "Shell mesh (OBJ)")->required();
  sub->add_option("--pin", args->pins, "Pinned vertices (JSON list, or {\"vertices\": [...]})");
  sub->add_option("--count", args->count, "Number of lowest modes")->capture_default_str();
  sub->add_option("--solver", args->solver, "Eigen-solver: auto, dense or shift-invert")->capture_default_str();
  sub->add_option("--ka", args->material.kA, "Area stiffness k_A, dyn/cm")->capture_default_str();
  sub->add_option("--kl", args->material.kL, "Edge-length stiffness k_L, dyn")->capture_default_str();
  sub->add_option("--kb", args->material.kB, "Bending stiffness k_B, erg")->capture_default_str();
  sub->add_option("--density", args->material.density, "Density rho, g/cm^3")->capture_default_str();
  sub->add_option("--thickness", args->material.thickness, "Thickness, cm")->capture_default_str();
  addJsonFlag(*sub, args->json);
  return std::function<int()>([args] { return runModes(*args); });
});

}  // namespace myo::cli
