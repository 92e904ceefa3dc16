// Small meshes with flat and curved rest states, random deformations and finite-difference
// checkers for the discrete-shell tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo::test {

struct RestMesh {
  std::string name;
  MatX3 V;
  MatX3i F;
};

inline MatX3 randomMatrix(int rows, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatX3 M(rows, 3);
  for (int i = 0; i < rows; ++i)
    for (int k = 0; k < 3; ++k) M(i, k) = amplitude * u(rng);
  return M;
}

// A 4×3 grid with random in-plane and out-of-plane perturbation (curved, irregular rest).
inline RestMesh perturbedGrid(unsigned seed = 1) {
  TriMesh g = gridMesh(2.0, 1.5, 4, 3);
  MatX3 noise = randomMatrix(g.vertexCount(), 1.0, seed);
  noise.col(0) *= 0.08;
  noise.col(1) *= 0.08;
  noise.col(2) *= 0.15;
  return {"perturbed grid", g.V + noise, g.F};
}

// A 6×2 grid rolled into a quarter cylinder of radius 1 around the y axis (θ̄ ≠ 0 everywhere).
inline RestMesh cylinderPatch() {
  TriMesh g = gridMesh(1.5, 1.0, 6, 2);
  MatX3 V = g.V;
  for (int i = 0; i < V.rows(); ++i) {
    const double s = g.V(i, 0);
    V(i, 0) = std::sin(s);
    V(i, 2) = 1.0 - std::cos(s);
  }
  return {"cylinder patch", V, g.F};
}

// A saddle z = 0.3(x² − y²) over a 4×4 grid (negative Gaussian curvature: θ̄ of both signs).
inline RestMesh saddlePatch() {
  TriMesh g = gridMesh(2.0, 2.0, 4, 4);
  MatX3 V = g.V;
  for (int i = 0; i < V.rows(); ++i) {
    const double x = V(i, 0) - 1.0, y = V(i, 1) - 1.0;
    V(i, 0) = x;
    V(i, 1) = y;
    V(i, 2) = 0.3 * (x * x - y * y);
  }
  return {"saddle", V, g.F};
}

// The cap z > 0.4 of an icosphere (an open, convex patch), re-indexed.
inline RestMesh icospherePatch() {
  const TriMesh s = icosphere(1.0, 2);
  std::vector<int> map(s.vertexCount(), -1);
  std::vector<Eigen::Vector3i> tris;
  std::vector<Vec3> verts;
  for (int t = 0; t < s.triangleCount(); ++t) {
    const Vec3 c = (s.V.row(s.F(t, 0)) + s.V.row(s.F(t, 1)) + s.V.row(s.F(t, 2))).transpose() / 3.0;
    if (c.z() <= 0.4) continue;
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      int& id = map[s.F(t, k)];
      if (id < 0) {
        id = static_cast<int>(verts.size());
        verts.push_back(s.V.row(s.F(t, k)).transpose());
      }
      tri[k] = id;
    }
    tris.push_back(tri);
  }
  RestMesh m{"icosphere patch", MatX3(verts.size(), 3), MatX3i(tris.size(), 3)};
  for (size_t i = 0; i < verts.size(); ++i) m.V.row(i) = verts[i].transpose();
  for (size_t t = 0; t < tris.size(); ++t) m.F.row(t) = tris[t].transpose();
  return m;
}

inline std::vector<RestMesh> testMeshes() {
  return {perturbedGrid(), cylinderPatch(), saddlePatch(), icospherePatch()};
}

inline DiscreteShell makeShell(const RestMesh& m, const ShellMaterial& mat = {}) {
  return DiscreteShell(m.V, m.F, buildEdgeTable(m.F, static_cast<int>(m.V.rows())), mat);
}

// Material with only one of the three terms switched on.
inline ShellMaterial onlyTerm(char term) {
  ShellMaterial m;
  m.kA = term == 'A' ? 3.0 : 0.0;
  m.kL = term == 'L' ? 2.0 : 0.0;
  m.kB = term == 'B' ? 0.7 : 0.0;
  return m;
}

inline const std::vector<double>& fdSteps() {
  static const std::vector<double> steps{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  return steps;
}

// Best (over the step sweep) relative error ‖g_fd − g‖/‖g‖ of the analytic gradient at x.
inline double bestGradientError(const DiscreteShell& shell, const MatX3& x) {
  VecX g;
  shell.energy(x, &g);
  double best = std::numeric_limits<double>::infinity();
  for (double h : fdSteps()) {
    VecX fd(g.size());
    MatX3 xp = x;
    for (Eigen::Index j = 0; j < g.size(); ++j) {
      const double keep = flat(xp)[j];
      flat(xp)[j] = keep + h;
      const double ep = shell.energy(xp).total;
      flat(xp)[j] = keep - h;
      const double em = shell.energy(xp).total;
      flat(xp)[j] = keep;
      fd[j] = (ep - em) / (2.0 * h);
    }
    best = std::min(best, (fd - g).norm() / g.norm());
  }
  return best;
}

// Best relative Frobenius error of the analytic Hessian against central differences of the
// analytic gradient.
inline double bestHessianError(const DiscreteShell& shell, const MatX3& x) {
  VecX g;
  SparseMat H;
  shell.energy(x, &g, &H);
  const MatX Hd = MatX(H);
  double best = std::numeric_limits<double>::infinity();
  for (double h : fdSteps()) {
    MatX fd(g.size(), g.size());
    MatX3 xp = x;
    VecX gp, gm;
    for (Eigen::Index j = 0; j < g.size(); ++j) {
      const double keep = flat(xp)[j];
      flat(xp)[j] = keep + h;
      shell.energy(xp, &gp);
      flat(xp)[j] = keep - h;
      shell.energy(xp, &gm);
      flat(xp)[j] = keep;
      fd.col(j) = (gp - gm) / (2.0 * h);
    }
    best = std::min(best, (fd - Hd).norm() / Hd.norm());
  }
  return best;
}

}  // namespace myo::test
