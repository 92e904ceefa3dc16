// `myoshell info MESH.obj [--json]`: the mesh's Table 1 and every fault found, read leniently.
#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "common_options.h"
#include "myoshell/mesh/mesh_stats.h"
#include "myoshell/mesh/obj_reader.h"

namespace myo::cli {

namespace {

struct FaultSummary {
  int count = 0;
  std::string firstMessage;
  int firstLine = 0;
};

// Faults grouped by kind, in the order each kind first appears.
std::vector<std::pair<std::string, FaultSummary>> summarise(const MeshReport& report) {
  std::vector<std::pair<std::string, FaultSummary>> out;
  for (const MeshFault& f : report.faults) {
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == f.kind; });
    if (it == out.end()) {
      out.push_back({f.kind, {0, f.message, f.line}});
      it = out.end() - 1;
    }
    ++it->second.count;
  }
  return out;
}

int runInfo(const std::string& path, bool json) {
  MeshReport report;
  const TriMesh mesh = readObjLenient(path, report);
  const MeshStats s = meshStats(mesh);
  const auto faults = summarise(report);
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = path;
    j["vertices"] = s.vertices;
    j["triangles"] = s.triangles;
    j["polygons"] = mesh.polygons.size();
    j["edges"] = s.edges;
    j["interior_edges"] = s.interiorEdges;
    j["boundary_edges"] = s.boundaryEdges;
    j["boundary_loops"] = s.boundaryLoops;
    j["components"] = s.components;
    j["euler_characteristic"] = s.vertices - s.edges + s.triangles;
    j["non_manifold_edges"] = s.nonManifoldEdges;
    j["degenerate_triangles"] = s.degenerateTriangles;
    j["inconsistent_edges"] = s.inconsistentEdges;
    j["bbox_min"] = {s.bboxMin.x(), s.bboxMin.y(), s.bboxMin.z()};
    j["bbox_max"] = {s.bboxMax.x(), s.bboxMax.y(), s.bboxMax.z()};
    j["area"] = s.area;
    j["has_uv"] = mesh.UV.rows() > 0;
    j["groups"] = nlohmann::ordered_json::object();
    for (const auto& [name, set] : mesh.groups) j["groups"][name] = set.size();
    j["faults"] = nlohmann::ordered_json::array();
    for (const auto& [kind, f] : faults)
      j["faults"].push_back({{"kind", kind}, {"count", f.count}, {"first_message", f.firstMessage},
                             {"first_line", f.firstLine}});
    fmt::print("{}\n", j.dump(2));
  } else {
    auto row = [](const char* label, const std::string& value) { fmt::print("  {:<22}{}\n", label, value); };
    fmt::print("{}\n", path);
    row("vertices", std::to_string(s.vertices));
    row("triangles", fmt::format("{} (from {} polygons)", s.triangles, mesh.polygons.size()));
    row("edges", std::to_string(s.edges));
    row("  interior", std::to_string(s.interiorEdges));
    row("  boundary", std::to_string(s.boundaryEdges));
    row("boundary loops", std::to_string(s.boundaryLoops));
    row("components", std::to_string(s.components));
    row("Euler characteristic", std::to_string(s.vertices - s.edges + s.triangles));
    row("non-manifold edges", std::to_string(s.nonManifoldEdges));
    row("degenerate triangles", std::to_string(s.degenerateTriangles));
    row("inconsistent edges", std::to_string(s.inconsistentEdges));
    // An OBJ carries no unit: the numbers are the file's (a head may be in m, mm or cm).
    row("bbox min", fmt::format("{:.4g} {:.4g} {:.4g} (the file's units)", s.bboxMin.x(), s.bboxMin.y(), s.bboxMin.z()));
    row("bbox max", fmt::format("{:.4g} {:.4g} {:.4g}", s.bboxMax.x(), s.bboxMax.y(), s.bboxMax.z()));
    row("area", fmt::format("{:.6g} (the file's units, squared)", s.area));
    row("UVs", mesh.UV.rows() > 0 ? "yes" : "no");
    for (const auto& [name, set] : mesh.groups) row("group", fmt::format("{} ({} vertices)", name, set.size()));
    if (faults.empty()) {
      row("faults", "none");
    } else {
      fmt::print("faults:\n");
      for (const auto& [kind, f] : faults) fmt::print("  {} × {}: first{}: {}\n", f.count, kind, f.firstLine > 0 ? fmt::format(" (line {})", f.firstLine) : "", f.firstMessage);
    }
  }
  return faults.empty() ? kExitOk : kExitMeshFaults;
}

}  // namespace

static CommandRegistrar registerInfo("info", [](CLI::App& app) {
  auto* sub = app.add_subcommand("info", "Print a mesh's statistics (Table 1) and every fault found");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  sub->add_option("mesh", *path, "OBJ mesh to inspect")->required();
  addJsonFlag(*sub, *json);
  return std::function<int()>([path, json] { return runInfo(*path, *json); });
});

}  // namespace myo::cli
