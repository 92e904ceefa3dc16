// A skin animation as a base plus a few morph targets (scheme and references in io/morph_compression.h).
#include "myoshell/io/morph_compression.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <random>

#include "myoshell/core/check.h"

namespace myo {
namespace {

using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr Eigen::Index kColumnBlock = 3 * 1024;  // columns of D read at a time (1024 vertices)
constexpr Eigen::Index kFrameBlock = 32;         // rows of D read at a time

// The frames' displacements from the rest, read block by block (D is never held whole).
class Displacements {
 public:
  Displacements(const MatX3& rest, const std::vector<MatX3>& frames) : rest_(rest), frames_(frames) {}
  Eigen::Index frames() const { return static_cast<Eigen::Index>(frames_.size()); }
  Eigen::Index columns() const { return rest_.size(); }

  // Columns [c0, c0 + w) of D: F × w.
  void columnBlock(Eigen::Index c0, Eigen::Index w, RowMat& out) const {
    out.resize(frames(), w);
    const double* r = rest_.data() + c0;
    for (Eigen::Index f = 0; f < frames(); ++f) {
      const double* p = frames_[f].data() + c0;
      for (Eigen::Index j = 0; j < w; ++j) out(f, j) = p[j] - r[j];
    }
  }
  // Rows [f0, f0 + b) of D: b × 3n.
  void rowBlock(Eigen::Index f0, Eigen::Index b, RowMat& out) const {
    out.resize(b, columns());
    for (Eigen::Index f = 0; f < b; ++f) out.row(f) = flat(frames_[f0 + f]).transpose() - flat(rest_).transpose();
  }

 private:
  const MatX3& rest_;
  const std::vector<MatX3>& frames_;
};

// Calls fn(c0, w, D_c) for every column block of D.
template <typename Fn>
void forColumnBlocks(const Displacements& D, Fn fn) {
  RowMat block;
  for (Eigen::Index c0 = 0; c0 < D.columns(); c0 += kColumnBlock) {
    const Eigen::Index w = std::min(kColumnBlock, D.columns() - c0);
    D.columnBlock(c0, w, block);
    fn(c0, w, block);
  }
}

MatX orthonormalColumns(const MatX& A) {
  Eigen::HouseholderQR<MatX> qr(A);
  return qr.householderQ() * MatX::Identity(A.rows(), A.cols());
}

// Q (F × r): orthonormal columns spanning (nearly) D's column space; Q = I (r = F) when exact.
MatX rangeOf(const Displacements& D, int sketch, bool exact) {
  const Eigen::Index F = D.frames();
  if (exact) return MatX::Identity(F, F);
  // Halko et al. 2011, Algorithm 4.4: Y = D Ω, then two power iterations Y = D Dᵀ Q, each
  // orthonormalised (the spectrum's tail then barely leaks into the leading directions).
  std::mt19937_64 rng(20261128);
  std::normal_distribution<double> gauss;
  MatX Y = MatX::Zero(F, sketch);
  forColumnBlocks(D, [&](Eigen::Index, Eigen::Index w, const RowMat& Dc) {
    MatX omega(w, sketch);
    for (Eigen::Index i = 0; i < omega.size(); ++i) omega.data()[i] = gauss(rng);
    Y.noalias() += Dc * omega;
  });
  MatX Q = orthonormalColumns(Y);
  for (int iteration = 0; iteration < 2; ++iteration) {
    Y.setZero();
    forColumnBlocks(D, [&](Eigen::Index, Eigen::Index, const RowMat& Dc) {
      const MatX Z = Dc.transpose() * Q;
      Y.noalias() += Dc * Z;
    });
    Q = orthonormalColumns(Y);
  }
  return Q;
}

// Largest vertex distance over all frames between D and W(:, :k) V(:, :k)ᵀ.
double maxVertexError(const Displacements& D, const MatX& W, const MatX& V, Eigen::Index k) {
  double worst = 0.0;
  RowMat block;
  for (Eigen::Index f0 = 0; f0 < D.frames(); f0 += kFrameBlock) {
    const Eigen::Index b = std::min(kFrameBlock, D.frames() - f0);
    D.rowBlock(f0, b, block);
    if (k > 0) block.noalias() -= W.block(f0, 0, b, k) * V.leftCols(k).transpose();
    for (Eigen::Index f = 0; f < b; ++f)
      for (Eigen::Index v = 0; v + 2 < block.cols(); v += 3)
        worst = std::max(worst, block.row(f).segment<3>(v).squaredNorm());
  }
  return std::sqrt(worst);
}

float asStored(double x) { return static_cast<float>(x); }

}  // namespace

MorphAnimation compressToMorphTargets(const MatX3& rest, const std::vector<MatX3>& frames, double tolerance,
                                      int maxTargets, double toFile) {
  MYO_CHECK(!frames.empty(), "morph compression needs at least one frame");
  MYO_CHECK_GT(tolerance, 0.0);
  MYO_CHECK_GE(maxTargets, 1);
  for (const MatX3& P : frames) MYO_CHECK(P.rows() == rest.rows() && P.allFinite(), "every frame must be n×3 and finite");
  const Displacements D(rest, frames);
  const Eigen::Index F = D.frames(), N = D.columns();

  // The SVD's leading directions: H = B Bᵀ, B = Qᵀ D (read by column blocks).
  const bool exact = F <= kExactRangeFrames || F <= maxTargets + 16;
  const MatX Q = rangeOf(D, maxTargets + 16, exact);
  const Eigen::Index r = Q.cols();
  MatX H = MatX::Zero(r, r);
  forColumnBlocks(D, [&](Eigen::Index, Eigen::Index, const RowMat& Dc) {
    if (exact) {
      H.selfadjointView<Eigen::Lower>().rankUpdate(Dc);
    } else {
      const MatX Bc = Q.transpose() * Dc;
      H.selfadjointView<Eigen::Lower>().rankUpdate(Bc);
    }
  });
  H = H.selfadjointView<Eigen::Lower>();
  const Eigen::SelfAdjointEigenSolver<MatX> eig(H);
  MYO_CHECK(eig.info() == Eigen::Success, "morph compression: the eigendecomposition failed");
  // Descending; directions with σ below 1e-9 σ₁ are round-off, not motion.
  const VecX lambda = eig.eigenvalues().reverse();
  const double floor = 1e-18 * std::max(lambda(0), 0.0);
  Eigen::Index K = 0;
  while (K < std::min<Eigen::Index>(r, maxTargets) && lambda(K) > floor && lambda(K) > 0.0) ++K;

  // W (F × K): the weights, D V. With Q = I, W = D Dᵀ U Σ⁻¹ = U Σ straight from the eigenvectors,
  // and V = Dᵀ U Σ⁻¹ is orthonormal to round-off, so only the columns the bisection may use are
  // formed. With a randomized Q, V = Dᵀ Q U Σ⁻¹ is re-orthonormalised (nested spans kept) and
  // W = D V. Every k is checked on every frame, so neither shortcut can hide an error.
  const MatX U = eig.eigenvectors().rowwise().reverse().leftCols(K);
  const VecX sigma = lambda.head(K).cwiseSqrt();
  MatX V(N, 0), W(F, K);
  // V's first m columns (the exact path forms them on demand).
  auto formV = [&](Eigen::Index m) {
    if (V.cols() >= m) return;
    const MatX QU = Q * (U.leftCols(m) * sigma.head(m).cwiseInverse().asDiagonal());  // F × m
    V.resize(N, m);
    forColumnBlocks(D, [&](Eigen::Index c0, Eigen::Index w, const RowMat& Dc) {
      V.middleRows(c0, w).noalias() = Dc.transpose() * QU;
    });
  };
  if (K == 0) {  // nothing moves: one target that every frame weighs 0
    K = 1;
    V = MatX::Zero(N, 1);
    V(0, 0) = 1.0;
    W = MatX::Zero(F, 1);
  } else if (exact) {
    W = U * sigma.asDiagonal();
  } else {
    formV(K);
    V = orthonormalColumns(V);
    W.setZero();
    forColumnBlocks(D, [&](Eigen::Index c0, Eigen::Index w, const RowMat& Dc) {
      W.noalias() += Dc * V.middleRows(c0, w);
    });
  }

  // The smallest k whose error over every frame is within the tolerance, by bisection between two
  // bounds from each frame's residual norm ‖r_f(k)‖ (‖r_f‖² = ‖d_f‖² − Σ_{j≤k} w_fj²): no vertex is
  // off by more than ‖r_f‖ (k with max_f ‖r_f‖ ≤ tolerance is feasible), and the worst vertex is
  // off by at least the RMS ‖r_f‖ / √n (k with max_f ‖r_f‖ / √n > tolerance is not).
  VecX residual2(F);
  for (Eigen::Index f = 0; f < F; ++f) residual2(f) = (frames[f] - rest).squaredNorm();
  const double n = static_cast<double>(rest.rows());
  Eigen::Index lo = 0, hi = K;
  for (Eigen::Index k = 1; k <= K; ++k) {
    residual2 -= W.col(k - 1).cwiseAbs2();
    const double worst = std::sqrt(std::max(residual2.maxCoeff(), 0.0));
    if (worst / std::sqrt(n) > tolerance) lo = k;
    if (worst <= tolerance) {
      hi = k;
      break;
    }
  }
  MorphAnimation out;
  formV(hi);
  if (maxVertexError(D, W, V, hi) > tolerance) {  // the bound not reached within the cap (or round-off)
    formV(K);
    if (hi < K && maxVertexError(D, W, V, K) <= tolerance) {
      lo = hi;
      hi = K;
    } else {
      lo = hi = K;
      out.withinTolerance = false;  // the cap binds: all K
    }
  }
  while (hi - lo > 1) {
    const Eigen::Index mid = (lo + hi) / 2;
    (maxVertexError(D, W, V, mid) <= tolerance ? hi : lo) = mid;
  }
  const Eigen::Index k = hi;

  // Weights into [0, 1]: w = lo + (hi − lo) s; the constant part lo joins the base.
  const VecX wLo = W.leftCols(k).colwise().minCoeff().transpose();
  const VecX wSpan = W.leftCols(k).colwise().maxCoeff().transpose() - wLo;
  MatX3 base = rest;
  flat(base) += V.leftCols(k) * wLo;
  out.base = base * toFile;
  out.weights = MatX::Zero(F, k);
  for (Eigen::Index j = 0; j < k; ++j) {
    MatX3 target = MatX3::Zero(rest.rows(), 3);
    if (wSpan(j) > 0.0) {
      flat(target) = V.col(j) * (wSpan(j) * toFile);
      out.weights.col(j) = (W.col(j).array() - wLo(j)) / wSpan(j);
    }
    out.targets.push_back(target);
  }

  // The error as a player meets it: base, targets and weights rounded to float32 as stored.
  RowMat T(k, N);
  for (Eigen::Index j = 0; j < k; ++j)
    for (Eigen::Index i = 0; i < N; ++i) T(j, i) = asStored(out.targets[j].data()[i]);
  VecX baseStored(N);
  for (Eigen::Index i = 0; i < N; ++i) baseStored(i) = asStored(out.base.data()[i]);
  const MatX S = out.weights.unaryExpr([](double x) { return static_cast<double>(asStored(x)); });
  double worst = 0.0;
  RowMat played;
  for (Eigen::Index f0 = 0; f0 < F; f0 += kFrameBlock) {
    const Eigen::Index b = std::min(kFrameBlock, F - f0);
    played.noalias() = S.middleRows(f0, b) * T;
    for (Eigen::Index f = 0; f < b; ++f) {
      const Eigen::Map<const VecX> P = flat(frames[f0 + f]);
      for (Eigen::Index v = 0; v + 2 < N; v += 3) {
        const Vec3 e = played.row(f).segment<3>(v).transpose() + baseStored.segment<3>(v) - toFile * P.segment<3>(v);
        worst = std::max(worst, e.squaredNorm());
      }
    }
  }
  out.maxError = std::sqrt(worst) / toFile;
  return out;
}

}  // namespace myo
