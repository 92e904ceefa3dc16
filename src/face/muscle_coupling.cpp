#include "myoshell/face/muscle_coupling.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <unordered_map>

#include "myoshell/core/errors.h"
#include "myoshell/face/tissue_attachment.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

namespace {
double smooth(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

// The skin as a graph for patch distances: per vertex, its neighbours and the edge lengths, and its
// lumped area (tissue_attachment.h).
struct SkinGraph {
  std::vector<std::vector<std::pair<int, double>>> neighbours;
  VecX area;
  double meanEdge = 0.0;
  SkinGraph(const MatX3& V, const MatX3i& F) : neighbours(static_cast<size_t>(V.rows())), area(lumpedVertexAreas(V, F)) {
    long long edges = 0;
    for (Eigen::Index t = 0; t < F.rows(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const int i = F(t, k), j = F(t, (k + 1) % 3);
        const double l = (V.row(i) - V.row(j)).norm();
        neighbours[static_cast<size_t>(i)].emplace_back(j, l);  // each interior edge twice: harmless
        neighbours[static_cast<size_t>(j)].emplace_back(i, l);
        meanEdge += l;
        ++edges;
      }
    }
    if (edges > 0) meanEdge /= static_cast<double>(edges);
  }
};

// The patch of skin within `radius` of the surface point (triangle, barycentric) along the edges
// (Dijkstra from the triangle's corners, started at their straight distances to the point), with
// weights A_j (1 − (d_j/r)²)², normalised. The lips' gap and the lids' slit separate patches.
void patchAround(const SkinGraph& g, const MatX3& V, const Eigen::Vector3i& tri, const Vec3& point, double radius,
                 std::vector<int>& vertices, std::vector<double>& weights) {
  std::vector<std::pair<int, double>> reached;  // (vertex, distance), settled
  std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>> queue;
  std::unordered_map<int, double> best;
  for (int k = 0; k < 3; ++k) {
    const double d = (Vec3(V.row(tri(k))) - point).norm();
    if (!best.count(tri(k)) || d < best[tri(k)]) best[tri(k)] = d, queue.emplace(d, tri(k));
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > best[v] || d > radius) continue;  // a stale entry: v was reached closer already
    reached.emplace_back(v, d);
    for (const auto& [w, l] : g.neighbours[static_cast<size_t>(v)]) {
      const double dw = d + l;
      if (dw <= radius && (!best.count(w) || dw < best[w])) best[w] = dw, queue.emplace(dw, w);
    }
  }
  vertices.clear();
  weights.clear();
  double sum = 0.0;
  for (const auto& [v, d] : reached) {
    const double s = d / radius;
    const double w = g.area(v) * (1.0 - s * s) * (1.0 - s * s);
    if (w <= 0.0) continue;
    vertices.push_back(v);
    weights.push_back(w);
    sum += w;
  }
  for (double& w : weights) w /= sum;
}
}  // namespace

double CouplingProfile::modulus(double t) const {
  if (t <= originEnd) return 0.0;
  if (t < bellyStart) return bellyModulus * smooth((t - originEnd) / (bellyStart - originEnd));
  return bellyModulus + (insertionModulus - bellyModulus) * smooth((t - insertionStart) / (1.0 - insertionStart));
}

void CouplingProfile::validate(const std::string& owner) const {
  auto bad = [&](const std::string& what) { throw InputError(owner + ": " + what); };
  if (!(insertionModulus > 0) || !std::isfinite(insertionModulus)) bad("insertion_modulus must be > 0 dyn/cm²");
  if (!(bellyModulus >= 0) || !std::isfinite(bellyModulus)) bad("belly_modulus must be ≥ 0 dyn/cm²");
  if (!(originEnd >= 0 && originEnd < bellyStart && bellyStart <= insertionStart && insertionStart < 1.0))
    bad("profile positions must satisfy 0 ≤ origin_end < belly_start ≤ insertion_start < 1");
}

CoupledMuscle coupleMuscle(const MuscleDef& def, const Head& head, const MuscleCouplingSettings& settings) {
  const CouplingProfile& profile = def.coupling ? *def.coupling : settings.profile;
  profile.validate(def.coupling ? "muscle '" + def.name + "': coupling" : "muscle coupling");
  settings.muscle.validate();
  if (!(settings.shortening > 0.0 && settings.shortening < 1.0))
    throw InputError("muscle '" + def.name + "': shortening must lie in (0, 1)");
  CoupledMuscle cm;
  cm.muscle = buildMuscle(def, head);
  const Muscle& mu = cm.muscle;
  const TriMesh& mm = mu.mesh;
  const int nm = mm.vertexCount();
  const DiscreteShell shell(mm.V, mm.F, buildEdgeTable(mm.F, nm), settings.muscle);

  // The static response of the pinned muscle to its activation load (unit forces along the
  // contraction direction on the central nodes): K_FF⁻¹P (METHOD.md §8's static-shape variant).
  const std::vector<int> freeV = freeVerticesOf(nm, mu.originNodes, mm.F);
  std::vector<int> toFree(static_cast<size_t>(nm), -1);
  for (size_t k = 0; k < freeV.size(); ++k) toFree[static_cast<size_t>(freeV[k])] = static_cast<int>(k);
  const SparseMat Kff = restrictToFree(shell.stiffnessAtRest(), freeV, nm);
  VecX P = VecX::Zero(Kff.rows());
  for (size_t c = 0; c < mu.centralNodes.size(); ++c) {
    const int r = toFree[static_cast<size_t>(mu.centralNodes[c])];
    if (r >= 0) P.segment<3>(3 * r) += mu.contractDirection.row(static_cast<Eigen::Index>(c)).transpose();
  }
  Eigen::SimplicialLDLT<SparseMat> ldlt(Kff);
  if (ldlt.info() != Eigen::Success) throw NumericalError("muscle '" + def.name + "': stiffness is singular");
  const VecX x = ldlt.solve(P);
  // Scale: the insertion ring's mean motion along the muscle is shortening × length.
  const Vec3 axis = (mu.originPoint - mu.insertionPoint).normalized();
  double along = 0.0;
  for (int v : mu.insertionNodes) {
    const int r = toFree[static_cast<size_t>(v)];
    if (r >= 0) along += x.segment<3>(3 * r).dot(axis);
  }
  along /= static_cast<double>(mu.insertionNodes.size());
  if (!(along > 0.0))
    throw NumericalError("muscle '" + def.name + "': its activation load does not move the insertion towards the origin");
  const double scale = settings.shortening * mu.restLength / along;
  cm.fullShape = MatX3::Zero(nm, 3);
  for (int v = 0; v < nm; ++v) {
    const int r = toFree[static_cast<size_t>(v)];
    if (r >= 0) cm.fullShape.row(v) = scale * x.segment<3>(3 * r).transpose();
  }
  {
    const VecX& mass = shell.lumpedMass();
    double mm2 = 0.0;
    for (size_t k = 0; k < freeV.size(); ++k) mm2 += mass(freeV[k]) * x.segment<3>(3 * static_cast<Eigen::Index>(k)).squaredNorm();
    cm.naturalFrequency = std::sqrt(x.dot(Kff * x) / mm2);
  }

  // Springs to patches around the closest skin points.
  const MatX3& S = head.mesh.V;
  const MatX3i& F = head.mesh.F;
  const MatX3 normals = vertexNormals(S, F);
  const double muscleArea = surfaceArea(mm.V, mm.F);
  const double areaPerNode = muscleArea / nm;
  const double L = mu.restLength;
  const SkinGraph graph(S, F);
  const double radius = settings.patchRadius <= 0.0
                            ? 0.0
                            : std::max(settings.patchRadius * muscleArea / (4.0 * L), 1.5 * graph.meanEdge);
  for (int v = 0; v < nm; ++v) {
    const Vec3 p = mm.V.row(v);
    const double t = std::clamp((p - mu.originPoint).dot(-axis) / L, 0.0, 1.0);
    const double G = profile.modulus(t);
    if (G <= 0.0) continue;
    const SurfacePoint sp = closestSurfacePoint(S, F, normals, p);
    if (!(sp.distance > 1e-9 * L))
      throw InputError("muscle '" + def.name + "': node " + std::to_string(v) + " lies on the skin (depth must be > 0)");
    CoupledMuscle::Spring s;
    s.node = v;
    const Eigen::Vector3i tri = F.row(sp.triangle).transpose();
    if (radius > 0.0) patchAround(graph, S, tri, sp.point, radius, s.skin, s.weights);
    if (s.skin.empty()) {  // the closest point alone
      s.skin = {tri(0), tri(1), tri(2)};
      s.weights = {sp.barycentric(0), sp.barycentric(1), sp.barycentric(2)};
    }
    s.t = t;
    s.depth = sp.distance;
    s.stiffness = G * areaPerNode / sp.distance;
    cm.springs.push_back(s);
  }
  return cm;
}

void addCouplingStiffness(const CoupledMuscle& m, std::vector<Triplet>& triplets) {
  for (const auto& s : m.springs)
    for (size_t a = 0; a < s.skin.size(); ++a)
      for (size_t b = 0; b < s.skin.size(); ++b) {
        const double k = s.stiffness * s.weights[a] * s.weights[b];
        for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * s.skin[a] + c, 3 * s.skin[b] + c, k);
      }
}

MatX3 couplingLoad(const CoupledMuscle& m, int skinVertexCount) {
  MatX3 f = MatX3::Zero(skinVertexCount, 3);
  for (const auto& s : m.springs)
    for (size_t a = 0; a < s.skin.size(); ++a) f.row(s.skin[a]) += s.stiffness * s.weights[a] * m.fullShape.row(s.node);
  return f;
}

}  // namespace myo
