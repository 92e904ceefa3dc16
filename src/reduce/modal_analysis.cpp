#include "myoshell/reduce/modal_analysis.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

namespace {

// (K − σM)⁻¹ for Spectra's generalized shift-invert mode, over a sparse LDLᵀ factorization.
// K − σM is SPD for σ < 0 because K is PSD, so no pivoting is needed.
class ShiftInvertLdlt {
 public:
  using Scalar = double;
  ShiftInvertLdlt(const SparseMat& K, const VecX& massDiag) : K_(K), m_(massDiag) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(const double& sigma) {
    SparseMat A = K_;
    for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) -= sigma * m_[i];
    ldlt_.compute(A);
    if (ldlt_.info() != Eigen::Success) {
      std::ostringstream os;
      os << "modal analysis: factorization of K - sigma*M failed (sigma = " << sigma << ")";
      throw NumericalError(os.str());
    }
  }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<VecX>(y, rows()) = ldlt_.solve(Eigen::Map<const VecX>(x, rows()));
  }

 private:
  const SparseMat& K_;
  const VecX& m_;
  Eigen::SimplicialLDLT<SparseMat> ldlt_;
};

// y = M x with a diagonal M.
class DiagonalProduct {
 public:
  using Scalar = double;
  explicit DiagonalProduct(const VecX& m) : m_(m) {}
  Eigen::Index rows() const { return m_.size(); }
  Eigen::Index cols() const { return m_.size(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<VecX>(y, rows()) = m_.cwiseProduct(Eigen::Map<const VecX>(x, rows()));
  }

 private:
  const VecX& m_;
};

EigenSolverKind resolveSolver(const ModalSettings& s, Eigen::Index dofs) {
  if (s.solver != EigenSolverKind::Auto) return s.solver;
  if (dofs <= s.denseMaxDofs) return EigenSolverKind::Dense;
  // Spectra needs nev < ncv ≤ n; tiny systems go dense.
  if (dofs <= s.modeCount + 2) return EigenSolverKind::Dense;
  return EigenSolverKind::ShiftInvert;
}

// Rayleigh–Ritz on span(Φ): makes ΦᵀMΦ = I and ΦᵀKΦ = Λ hold to round-off and sorts ascending.
void rayleighRitz(const SparseMat& K, const VecX& m, VecX& lambda, MatX& Phi) {
  const MatX KPhi = K * Phi;
  MatX Kr = Phi.transpose() * KPhi;
  MatX Mr = Phi.transpose() * m.asDiagonal() * Phi;
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Mr = 0.5 * (Mr + Mr.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<MatX> ges(Kr, Mr);
  if (ges.info() != Eigen::Success)
    throw NumericalError("modal analysis: the Rayleigh-Ritz refinement failed (modes not independent)");
  Phi = (Phi * ges.eigenvectors()).eval();
  lambda = ges.eigenvalues();
  // Re-normalize in the M-norm and fix the sign (largest-magnitude entry positive) so results are
  // reproducible across solvers.
  for (Eigen::Index j = 0; j < Phi.cols(); ++j) {
    const double nrm = std::sqrt(Phi.col(j).dot(m.cwiseProduct(Phi.col(j))));
    Phi.col(j) /= nrm;
    Eigen::Index imax;
    Phi.col(j).cwiseAbs().maxCoeff(&imax);
    if (Phi(imax, j) < 0) Phi.col(j) *= -1.0;
  }
}

}  // namespace

std::vector<int> freeVerticesOf(int vertexCount, const std::vector<int>& pinned, const MatX3i& F) {
  std::vector<char> fixed(vertexCount, 1);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      MYO_CHECK(F(t, k) >= 0 && F(t, k) < vertexCount, "triangle index out of range");
      fixed[F(t, k)] = 0;
    }
  for (int p : pinned) {
    if (p < 0 || p >= vertexCount) {
      std::ostringstream os;
      os << "pinned vertex " << p << " is out of range [0, " << vertexCount << ")";
      throw InputError(os.str());
    }
    fixed[p] = 1;
  }
  std::vector<int> free;
  for (int i = 0; i < vertexCount; ++i)
    if (!fixed[i]) free.push_back(i);
  return free;
}

SparseMat restrictToFree(const SparseMat& A, const std::vector<int>& freeVertices, int vertexCount) {
  MYO_CHECK_EQ(A.rows(), static_cast<Eigen::Index>(3 * vertexCount));
  std::vector<int> dofMap(3 * vertexCount, -1);
  for (size_t i = 0; i < freeVertices.size(); ++i)
    for (int c = 0; c < 3; ++c) dofMap[3 * freeVertices[i] + c] = static_cast<int>(3 * i + c);
  std::vector<Triplet> trip;
  trip.reserve(A.nonZeros());
  for (Eigen::Index col = 0; col < A.outerSize(); ++col) {
    const int fc = dofMap[col];
    if (fc < 0) continue;
    for (SparseMat::InnerIterator it(A, col); it; ++it) {
      const int fr = dofMap[it.row()];
      if (fr >= 0) trip.emplace_back(fr, fc, it.value());
    }
  }
  const Eigen::Index nf = 3 * static_cast<Eigen::Index>(freeVertices.size());
  SparseMat out(nf, nf);
  out.setFromTriplets(trip.begin(), trip.end());
  return out;
}

void lowestModes(const SparseMat& Kff, const VecX& massDiag, const ModalSettings& settings,
                 VecX& lambda, MatX& Phi, std::string* solverUsed) {
  const Eigen::Index N = Kff.rows();
  const int d = settings.modeCount;
  if (d < 1) throw InputError("modal analysis: the mode count must be at least 1");
  if (d > N) {
    std::ostringstream os;
    os << "modal analysis: " << d << " modes requested but the system has only " << N
       << " free degrees of freedom";
    throw InputError(os.str());
  }
  MYO_CHECK_EQ(massDiag.size(), N);
  MYO_CHECK(massDiag.minCoeff() > 0.0, "every free DOF needs a positive mass");

  const EigenSolverKind kind = resolveSolver(settings, N);
  if (kind == EigenSolverKind::Dense) {
    if (solverUsed) *solverUsed = "dense";
    const VecX s = massDiag.cwiseSqrt().cwiseInverse();
    MatX S = s.asDiagonal() * MatX(Kff) * s.asDiagonal();
    S = 0.5 * (S + S.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<MatX> es(S);
    if (es.info() != Eigen::Success) throw NumericalError("modal analysis: dense eigen-solve failed");
    lambda = es.eigenvalues().head(d);
    Phi = s.asDiagonal() * es.eigenvectors().leftCols(d);
  } else {
    if (solverUsed) *solverUsed = "shift-invert";
    if (N <= d + 2) throw InputError("modal analysis: too few DOFs for shift-invert; use the dense solver");
    double sigma = settings.shift;
    if (sigma == 0.0) {
      // A tiny negative shift relative to the mean eigenvalue τ = tr K / tr M: K − σM is then SPD
      // even when K is singular (free rigid modes, collinear pins), and the convergence of the
      // lowest modes (ratios (λ_j − σ)/(λ_{d+1} − σ)) is as good as with σ = 0.
      double trK = 0.0;
      for (Eigen::Index i = 0; i < N; ++i) trK += Kff.coeff(i, i);
      const double tau = trK / massDiag.sum();
      sigma = -1e-6 * (tau > 0 ? tau : 1.0);
    }
    if (!(sigma < 0.0))
      throw InputError("modal analysis: the shift-invert shift must be negative (K - sigma*M must be SPD)");
    ShiftInvertLdlt op(Kff, massDiag);
    DiagonalProduct bop(massDiag);
    const Eigen::Index ncv = std::min<Eigen::Index>(N, std::max(2 * d + 1, settings.ncvMin));
    Spectra::SymGEigsShiftSolver<ShiftInvertLdlt, DiagonalProduct, Spectra::GEigsMode::ShiftInvert>
        geigs(op, bop, d, ncv, sigma);
    geigs.init();
    const Eigen::Index nconv =
        geigs.compute(Spectra::SortRule::LargestMagn, settings.maxIterations, settings.tolerance,
                      Spectra::SortRule::SmallestAlge);
    if (geigs.info() != Spectra::CompInfo::Successful || nconv < d) {
      std::ostringstream os;
      os << "modal analysis: shift-invert Lanczos did not converge (" << nconv << " of " << d
         << " modes after " << geigs.num_iterations() << " restarts, sigma = " << sigma << ")";
      throw NumericalError(os.str());
    }
    lambda = geigs.eigenvalues();
    Phi = geigs.eigenvectors();
  }

  rayleighRitz(Kff, massDiag, lambda, Phi);
  // Check ΦᵀMΦ = I (the Rayleigh–Ritz step guarantees it up to round-off).
  const MatX G = Phi.transpose() * massDiag.asDiagonal() * Phi;
  const double err = (G - MatX::Identity(d, d)).cwiseAbs().maxCoeff();
  if (!(err < 1e-8)) {
    std::ostringstream os;
    os << "modal analysis: modes are not mass-orthonormal (max |PhiT M Phi - I| = " << err << ")";
    throw NumericalError(os.str());
  }
}

BasisKey modalBasisKey(const DiscreteShell& shell, const std::vector<int>& pinned,
                       const ModalSettings& settings) {
  std::vector<int> pins = pinned;
  std::sort(pins.begin(), pins.end());
  pins.erase(std::unique(pins.begin(), pins.end()), pins.end());
  const MatX3& X = shell.rest();
  const MatX3i& F = shell.triangles();
  const ShellMaterial& m = shell.material();
  const std::vector<int> free = freeVerticesOf(shell.vertexCount(), pins, F);
  const int kind = static_cast<int>(resolveSolver(settings, 3 * static_cast<Eigen::Index>(free.size())));
  KeyHasher h;
  h.str("myoshell.modal_basis").pod(kModalBasisFormatVersion);
  const int64_t n = X.rows(), nt = F.rows(), np = static_cast<int64_t>(pins.size());
  h.pod(n).bytes(X.data(), sizeof(double) * X.size());
  h.pod(nt).bytes(F.data(), sizeof(int) * F.size());
  h.pod(np).bytes(pins.data(), sizeof(int) * pins.size());
  h.pod(m.kA).pod(m.kL).pod(m.kB).pod(m.density).pod(m.thickness);
  h.pod(settings.modeCount).pod(kind).pod(settings.shift).pod(settings.tolerance);
  h.pod(settings.maxIterations).pod(settings.ncvMin);
  return h.key();
}

ModalBasis computeModalBasis(const SparseMat& K, const VecX& vertexMass, const MatX3& rest,
                             const MatX3i& F, const std::vector<int>& pinned,
                             const ModalSettings& settings) {
  const int n = static_cast<int>(rest.rows());
  MYO_CHECK_EQ(K.rows(), static_cast<Eigen::Index>(3 * n));
  MYO_CHECK_EQ(vertexMass.size(), static_cast<Eigen::Index>(n));
  ModalBasis b;
  b.fullVertexCount = n;
  b.freeVertices = freeVerticesOf(n, pinned, F);
  if (b.freeVertices.empty()) throw InputError("modal analysis: every vertex is pinned");
  const int f = b.freeCount();
  b.freeMass.resize(f);
  for (int i = 0; i < f; ++i) {
    b.freeMass[i] = vertexMass[b.freeVertices[i]];
    if (!(b.freeMass[i] > 0.0)) {
      std::ostringstream os;
      os << "modal analysis: free vertex " << b.freeVertices[i] << " has no mass";
      throw InputError(os.str());
    }
  }
  VecX massDiag(3 * f);
  for (int i = 0; i < f; ++i) massDiag.segment<3>(3 * i).setConstant(b.freeMass[i]);

  Stopwatch sw;
  const SparseMat Kff = restrictToFree(K, b.freeVertices, n);
  lowestModes(Kff, massDiag, settings, b.lambda, b.Phi, &b.solver);
  b.solveSeconds = sw.seconds();
  b.Psi = modalRotationMatrix(rest, F, b.freeVertices, b.Phi);
  return b;
}

ModalBasis computeModalBasis(const DiscreteShell& shell, const std::vector<int>& pinned,
                             const ModalSettings& settings, BasisCache* cache) {
  BasisKey key;
  if (cache) {
    key = modalBasisKey(shell, pinned, settings);
    if (std::optional<ModalBasis> hit = cache->load(key)) {
      if (hit->fullVertexCount == shell.vertexCount() && hit->modeCount() == settings.modeCount &&
          hit->Phi.rows() == 3 * hit->freeCount() && hit->Psi.rows() == hit->Phi.rows() &&
          hit->Phi.cols() == settings.modeCount && hit->Psi.cols() == settings.modeCount) {
        hit->fromCache = true;
        hit->solveSeconds = 0.0;
        return std::move(*hit);
      }
    }
  }
  ModalBasis b = computeModalBasis(shell.stiffnessAtRest(), shell.lumpedMass(), shell.rest(),
                                   shell.triangles(), pinned, settings);
  if (cache) cache->store(key, b);
  return b;
}

LoadParticipation loadParticipation(const ModalBasis& basis, const SparseMat& Kff,
                                    const MatX3& freeForce) {
  MYO_CHECK_EQ(freeForce.rows(), static_cast<Eigen::Index>(basis.freeCount()));
  MYO_CHECK_EQ(Kff.rows(), basis.Phi.rows());
  LoadParticipation lp;
  const int d = basis.modeCount();
  const double lmax = basis.lambda.cwiseAbs().maxCoeff();
  if (basis.lambda[0] <= 1e-9 * lmax)
    throw NumericalError(
        "load participation needs a constrained system: the basis has a rigid (zero) mode; pin "
        "at least two non-collinear rows of vertices");
  const auto Fv = flat(freeForce);
  const VecX p = basis.Phi.transpose() * Fv;
  lp.perMode.resize(d);
  for (int j = 0; j < d; ++j) lp.perMode[j] = basis.lambda[j] > 0 ? p[j] * p[j] / basis.lambda[j] : 0.0;
  lp.modal = lp.perMode.sum();
  if (Fv.squaredNorm() == 0.0) return lp;
  Eigen::SimplicialLDLT<SparseMat> ldlt(Kff);
  if (ldlt.info() != Eigen::Success ||
      !(ldlt.vectorD().minCoeff() > 1e-12 * ldlt.vectorD().cwiseAbs().maxCoeff()))
    throw NumericalError("load participation: K_FF is singular (the system is not fully constrained)");
  const VecX x = ldlt.solve(VecX(Fv));
  lp.total = Fv.dot(x);
  lp.ratio = lp.total > 0 ? lp.modal / lp.total : 0.0;
  return lp;
}

LoadParticipation loadParticipation(const ModalBasis& basis, const DiscreteShell& shell,
                                    const MatX3& freeForce) {
  return loadParticipation(
      basis, restrictToFree(shell.stiffnessAtRest(), basis.freeVertices, shell.vertexCount()), freeForce);
}

}  // namespace myo
