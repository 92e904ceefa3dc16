// The discrete-shell energy of thesis eq. 1–4 assembled over a mesh: energy, gradient, Hessian
// (exact or per-element PSD-projected), the rest stiffness K (eq. 7) and the lumped mass.
#include "myoshell/shell/discrete_shell.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/shell/element_derivatives.h"

namespace myo {

namespace {

inline Vec3 point(const MatX3& x, int i) { return x.row(i).transpose(); }

// Adds the element matrix H (3K×3K over the vertices v) into the values of a matrix with the
// layout's pattern. slots[a·Stride + b] is the rank of v[a] among v[b]'s block neighbours, so entry
// (3v[a]+r, 3v[b]+c) sits at outer[3v[b]+c] + 3·rank + r (the three columns of a vertex share a
// row pattern).
template <int K, int Stride = K>
void addBlock(double* values, const int* outer, const std::array<int, K>& v, const int* slots,
              const Eigen::Matrix<double, 3 * K, 3 * K>& H) {
  for (int b = 0; b < K; ++b)
    for (int c = 0; c < 3; ++c) {
      const int base = outer[3 * v[b] + c];
      for (int a = 0; a < K; ++a) {
        double* dst = values + base + 3 * slots[a * Stride + b];
        for (int r = 0; r < 3; ++r) dst[r] += H(3 * a + r, 3 * b + c);
      }
    }
}

// Adds g to the 3K-vector entries of the vertices v.
template <int K>
void scatter(VecX& grad, const std::array<int, K>& v, const Eigen::Matrix<double, 3 * K, 1>& g) {
  for (int a = 0; a < K; ++a) grad.segment<3>(3 * v[a]) += g.template segment<3>(3 * a);
}

// Projects a symmetric element matrix onto the PSD cone: negative eigenvalues clamped to 0
// (METHOD.md §6.1). Fixed-size solver: no heap allocation.
template <int N>
void projectPsd(Eigen::Matrix<double, N, N>& H) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(H);
  const auto& lambda = eig.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return;
  const auto& Q = eig.eigenvectors();
  H = Q * lambda.cwiseMax(0.0).asDiagonal() * Q.transpose();
}

}  // namespace

struct detail::ShellHessianLayout {
  SparseMat pattern;           // 3n×3n, compressed, explicit zeros on every coupled 3×3 block
  std::vector<int> triSlot;    // 9 per triangle, see addBlock
  std::vector<int> hingeSlot;  // 16 per edge over (x0, x1, x2, x3); boundary edges: a, b < 2 only
};

namespace {

std::shared_ptr<const detail::ShellHessianLayout> buildLayout(int n, const MatX3i& F, const EdgeTable& table) {
  // Block neighbours of each vertex (itself included): vertices sharing a triangle or a hinge. The
  // pattern does not depend on the material, so it holds for every k and is shared by copies.
  std::vector<std::vector<int>> nbr(n);
  for (int i = 0; i < n; ++i) nbr[i].push_back(i);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (a != b) nbr[F(t, b)].push_back(F(t, a));
  for (const Edge& e : table.edges) {
    const int k = e.isBoundary() ? 2 : 4;
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b)
        if (a != b) nbr[e.v[b]].push_back(e.v[a]);
  }
  std::vector<int> outer(3 * static_cast<size_t>(n) + 1);
  size_t nnz = 0;
  for (int j = 0; j < n; ++j) {
    auto& list = nbr[j];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (int c = 0; c < 3; ++c) {
      outer[3 * j + c] = static_cast<int>(nnz);
      nnz += 3 * list.size();
    }
  }
  outer[3 * n] = static_cast<int>(nnz);
  MYO_CHECK(nnz < static_cast<size_t>(std::numeric_limits<int>::max()), "Hessian too large: " << nnz);
  std::vector<int> inner(nnz);
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) {
      int p = outer[3 * j + c];
      for (int i : nbr[j])
        for (int r = 0; r < 3; ++r) inner[p++] = 3 * i + r;
    }
  const std::vector<double> zeros(nnz, 0.0);

  auto layout = std::make_shared<detail::ShellHessianLayout>();
  layout->pattern = Eigen::Map<const SparseMat>(3 * n, 3 * n, static_cast<Eigen::Index>(nnz), outer.data(),
                                                inner.data(), zeros.data());
  auto rank = [&](int i, int j) {
    const auto& list = nbr[j];
    return static_cast<int>(std::lower_bound(list.begin(), list.end(), i) - list.begin());
  };
  layout->triSlot.resize(9 * static_cast<size_t>(F.rows()));
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) layout->triSlot[9 * t + 3 * a + b] = rank(F(t, a), F(t, b));
  layout->hingeSlot.assign(16 * table.edges.size(), -1);
  for (size_t i = 0; i < table.edges.size(); ++i) {
    const Edge& e = table.edges[i];
    const int k = e.isBoundary() ? 2 : 4;
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b) layout->hingeSlot[16 * i + 4 * a + b] = rank(e.v[a], e.v[b]);
  }
  return layout;
}

}  // namespace

DiscreteShell::DiscreteShell(const MatX3& rest, const MatX3i& F, const EdgeTable& edges,
                             const ShellMaterial& material)
    : rest_(rest), F_(F), edges_(edges), material_(material) {
  material_.validate();
  const int n = vertexCount();
  for (Eigen::Index t = 0; t < F_.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      MYO_CHECK(F_(t, k) >= 0 && F_(t, k) < n,
                "triangle " << t << " has vertex " << F_(t, k) << " outside [0, " << n << ")");
  MYO_CHECK(F_.rows() == 0 || !edges_.edges.empty(), "edge table is empty for a non-empty mesh");

  restArea_.resize(F_.rows());
  for (Eigen::Index t = 0; t < F_.rows(); ++t) {
    double A = 0.0;
    triangleAreaDerivatives(point(rest_, F_(t, 0)), point(rest_, F_(t, 1)), point(rest_, F_(t, 2)), A);
    if (!(A > 0.0)) {
      std::ostringstream os;
      os << "triangle " << t << " (" << F_(t, 0) << ", " << F_(t, 1) << ", " << F_(t, 2)
         << ") has zero rest area; the shell energy divides by it";
      throw InputError(os.str());
    }
    restArea_[t] = A;
  }

  const size_t m = edges_.edges.size();
  restLength_.assign(m, 0.0);
  restTheta_.assign(m, 0.0);
  bendWeight_.assign(m, 0.0);
  for (size_t i = 0; i < m; ++i) {
    const Edge& e = edges_.edges[i];
    for (int k = 0; k < 4; ++k)
      MYO_CHECK(e.v[k] < n && (e.v[k] >= 0 || (k == 3 && e.isBoundary())),
                "edge " << i << " has vertex index " << e.v[k] << " (n = " << n << ")");
    MYO_CHECK(e.face[0] >= 0 && e.face[0] < F_.rows() && e.face[1] < F_.rows(),
              "edge " << i << " has an invalid face index");
    const double l = (rest_.row(e.v[1]) - rest_.row(e.v[0])).norm();
    if (!(l > 0.0)) {
      std::ostringstream os;
      os << "edge " << i << " (" << e.v[0] << ", " << e.v[1] << ") has zero rest length";
      throw InputError(os.str());
    }
    restLength_[i] = l;
    if (e.isBoundary()) continue;
    // θ̄ with the same vertex order as θ (METHOD.md §6.3); weight |ē|/h̄_e = 3|ē|²/(Ā1+Ā2) (§1.2).
    dihedralAngleDerivatives(point(rest_, e.v[0]), point(rest_, e.v[1]), point(rest_, e.v[2]),
                             point(rest_, e.v[3]), restTheta_[i]);
    bendWeight_[i] = 3.0 * l * l / (restArea_[e.face[0]] + restArea_[e.face[1]]);
  }
  computeMass();
  layout_ = buildLayout(n, F_, edges_);
}

void DiscreteShell::computeMass() {
  // m_i = ρ·t·Σ_{t∋i} Ā_t/3 (METHOD.md §1.6).
  mass_ = VecX::Zero(vertexCount());
  const double arealDensity = material_.density * material_.thickness;
  for (Eigen::Index t = 0; t < F_.rows(); ++t)
    for (int k = 0; k < 3; ++k) mass_[F_(t, k)] += arealDensity * restArea_[t] / 3.0;
}

DiscreteShell DiscreteShell::withMaterial(const ShellMaterial& material) const {
  material.validate();
  DiscreteShell copy = *this;
  copy.material_ = material;
  copy.computeMass();
  return copy;
}

ShellEnergy DiscreteShell::energy(const MatX3& x, VecX* grad, SparseMat* hess, HessianMode mode) const {
  MYO_CHECK_EQ(x.rows(), rest_.rows());
  const int n = vertexCount();
  const bool project = mode == HessianMode::Projected;
  const double kA = material_.kA, kL = material_.kL, kB = material_.kB;
  if (grad) grad->setZero(3 * n);
  double* values = nullptr;
  const int* outer = nullptr;
  if (hess) {
    *hess = layout_->pattern;  // fixed pattern, zero values: elements add into it in place
    values = hess->valuePtr();
    outer = hess->outerIndexPtr();
  }
  const detail::ShellHessianLayout& layout = *layout_;
  ShellEnergy E;

  // E_A (thesis eq. 1): per triangle (A − Ā)²/Ā; derivative of k c (g − ḡ)² is 2kc(g − ḡ)∇g and
  // its Hessian 2kc(∇g∇gᵀ + (g − ḡ)∇²g) (METHOD.md §1.4).
  {
    const bool derive = kA != 0.0 && (grad || hess);
    Vec9 g;
    Mat9 H;
    for (Eigen::Index t = 0; t < F_.rows(); ++t) {
      const std::array<int, 3> v{F_(t, 0), F_(t, 1), F_(t, 2)};
      double A = 0.0;
      const bool ok = triangleAreaDerivatives(point(x, v[0]), point(x, v[1]), point(x, v[2]), A,
                                              derive ? &g : nullptr, derive && hess ? &H : nullptr);
      const double d = A - restArea_[t], c = 1.0 / restArea_[t];
      E.EA += c * d * d;
      if (!derive || !ok) continue;
      if (grad) scatter<3>(*grad, v, (2.0 * kA * c * d) * g);
      if (hess) {
        H = (2.0 * kA * c) * (g * g.transpose() + d * H);
        if (project) projectPsd(H);
        addBlock<3>(values, outer, v, &layout.triSlot[9 * t], H);
      }
    }
  }

  // E_L (thesis eq. 2): per edge, boundary edges included, (l − l̄)²/l̄.
  {
    const bool derive = kL != 0.0 && (grad || hess);
    Vec6 g;
    Mat6 H;
    for (size_t i = 0; i < edges_.edges.size(); ++i) {
      const Edge& e = edges_.edges[i];
      const std::array<int, 2> v{e.v[0], e.v[1]};
      double l = 0.0;
      const bool ok = edgeLengthDerivatives(point(x, v[0]), point(x, v[1]), l, derive ? &g : nullptr,
                                            derive && hess ? &H : nullptr);
      const double d = l - restLength_[i], c = 1.0 / restLength_[i];
      E.EL += c * d * d;
      if (!derive || !ok) continue;
      if (grad) scatter<2>(*grad, v, (2.0 * kL * c * d) * g);
      if (hess) {
        // Projection in closed form: the block is S ⊗ [[1,−1],[−1,1]] with S's eigenvalues
        // 2kc (along ê) and 2kc·d/l (across, negative when compressed), so clamping d at 0 is exactly
        // the eigen-projection of the 6×6.
        const double across = project ? std::max(d, 0.0) : d;
        const Vec3 eh = g.tail<3>();
        const Mat3 S = (2.0 * kL * c) * (eh * eh.transpose() +
                                         (across / l) * (Mat3::Identity() - eh * eh.transpose()));
        H << S, -S, -S, S;
        addBlock<2, 4>(values, outer, v, &layout.hingeSlot[16 * i], H);
      }
    }
  }

  // E_B (thesis eq. 3): per interior edge 3(θ − θ̄)²|ē|/h̄_e = c_e (θ − θ̄)², c_e = 3|ē|²/(Ā1 + Ā2).
  {
    const bool derive = kB != 0.0 && (grad || hess);
    Vec12 g;
    Mat12 H;
    for (size_t i = 0; i < edges_.edges.size(); ++i) {
      const Edge& e = edges_.edges[i];
      if (e.isBoundary()) continue;
      double theta = 0.0;
      const bool ok = dihedralAngleDerivatives(point(x, e.v[0]), point(x, e.v[1]), point(x, e.v[2]),
                                               point(x, e.v[3]), theta, derive ? &g : nullptr,
                                               derive && hess ? &H : nullptr);
      const double d = wrapAngle(theta - restTheta_[i]), c = bendWeight_[i];
      E.EB += c * d * d;
      if (!derive || !ok) continue;  // collapsed hinge: energy kept, no force (METHOD.md §6.2)
      if (grad) scatter<4>(*grad, e.v, (2.0 * kB * c * d) * g);
      if (hess) {
        H = (2.0 * kB * c) * (g * g.transpose() + d * H);
        if (project) projectPsd(H);
        addBlock<4>(values, outer, e.v, &layout.hingeSlot[16 * i], H);
      }
    }
  }

  E.total = kA * E.EA + kL * E.EL + kB * E.EB;
  return E;
}

SparseMat DiscreteShell::stiffnessAtRest() const {
  // K = Σ 2kc ∇g∇gᵀ at X̄ (METHOD.md §1.5): the (g − ḡ)∇²g parts vanish at rest.
  const double kA = material_.kA, kL = material_.kL, kB = material_.kB;
  const detail::ShellHessianLayout& layout = *layout_;
  SparseMat K = layout.pattern;
  double* values = K.valuePtr();
  const int* outer = K.outerIndexPtr();

  if (kA != 0.0) {
    Vec9 g;
    for (Eigen::Index t = 0; t < F_.rows(); ++t) {
      const std::array<int, 3> v{F_(t, 0), F_(t, 1), F_(t, 2)};
      double A = 0.0;
      triangleAreaDerivatives(point(rest_, v[0]), point(rest_, v[1]), point(rest_, v[2]), A, &g);
      const Mat9 H = (2.0 * kA / restArea_[t]) * g * g.transpose();
      addBlock<3>(values, outer, v, &layout.triSlot[9 * t], H);
    }
  }
  if (kL != 0.0) {
    Mat6 H;
    for (size_t i = 0; i < edges_.edges.size(); ++i) {
      const Edge& e = edges_.edges[i];
      const Vec3 eh = (point(rest_, e.v[1]) - point(rest_, e.v[0])) / restLength_[i];
      const Mat3 S = (2.0 * kL / restLength_[i]) * eh * eh.transpose();
      H << S, -S, -S, S;
      addBlock<2, 4>(values, outer, std::array<int, 2>{e.v[0], e.v[1]}, &layout.hingeSlot[16 * i], H);
    }
  }
  if (kB != 0.0) {
    Vec12 g;
    for (size_t i = 0; i < edges_.edges.size(); ++i) {
      const Edge& e = edges_.edges[i];
      if (e.isBoundary()) continue;
      double theta = 0.0;
      dihedralAngleDerivatives(point(rest_, e.v[0]), point(rest_, e.v[1]), point(rest_, e.v[2]),
                               point(rest_, e.v[3]), theta, &g);
      const Mat12 H = (2.0 * kB * bendWeight_[i]) * g * g.transpose();
      addBlock<4>(values, outer, e.v, &layout.hingeSlot[16 * i], H);
    }
  }
  return K;
}

}  // namespace myo
