// `myoshell energy REST.obj DEFORMED.obj [--ka X] [--kl X] [--kb X] [--json]`: the discrete-shell
// energy of thesis eq. 1–4 of a deformed pose against its rest mesh, term by term.
#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "common_options.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo::cli {

namespace {

struct EnergyArgs {
  std::string rest, deformed;
  ShellMaterial material;  // only k_A, k_L, k_B are set from the command line
  bool json = false;
};

int runEnergy(const EnergyArgs& args) {
  args.material.validate();  // before reading: a bad flag is reported first
  const TriMesh rest = readObj(args.rest);
  const TriMesh deformed = readObjLike(args.deformed, rest);  // same topology, or a clear error
  const DiscreteShell shell(rest.V, rest.F, buildEdgeTable(rest.F, rest.vertexCount()), args.material);
  const ShellEnergy E = shell.energy(deformed.V);
  const ShellMaterial& k = shell.material();
  if (args.json) {
    nlohmann::ordered_json j;
    j["E_A"] = E.EA;
    j["E_L"] = E.EL;
    j["E_B"] = E.EB;
    j["E"] = E.total;
    j["k_A"] = k.kA;
    j["k_L"] = k.kL;
    j["k_B"] = k.kB;
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("{} → {} ({} vertices, {} triangles)\n", args.rest, args.deformed, rest.vertexCount(),
               rest.triangleCount());
    fmt::print("  E_A  {:<14.8g} cm²   × k_A {:<10.6g} dyn/cm = {:.8g} erg\n", E.EA, k.kA, k.kA * E.EA);
    fmt::print("  E_L  {:<14.8g} cm    × k_L {:<10.6g} dyn    = {:.8g} erg\n", E.EL, k.kL, k.kL * E.EL);
    fmt::print("  E_B  {:<14.8g}       × k_B {:<10.6g} erg    = {:.8g} erg\n", E.EB, k.kB, k.kB * E.EB);
    fmt::print("  E    {:.8g} erg\n", E.total);
  }
  return kExitOk;
}

}  // namespace

static CommandRegistrar registerEnergy("energy", [](CLI::App& app) {
  auto* sub = app.add_subcommand("energy", "Print the discrete-shell energy (thesis eq. 1-4) of a deformed pose");
  auto args = std::make_shared<EnergyArgs>();
  sub->add_option("rest", args->rest, "Rest mesh (OBJ)")->required();
  sub->add_option("deformed", args->deformed, "Deformed mesh with the rest mesh's topology (OBJ)")->required();
  sub->add_option("--ka", args->material.kA, "Area stiffness k_A, dyn/cm")->capture_default_str();
  sub->add_option("--kl", args->material.kL, "Edge-length stiffness k_L, dyn")->capture_default_str();
  sub->add_option("--kb", args->material.kB, "Bending stiffness k_B, erg")->capture_default_str();
  addJsonFlag(*sub, args->json);
  return std::function<int()>([args] { return runEnergy(*args); });
});

}  // namespace myo::cli
