#include "myoshell/reduce/ritz_basis.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

RitzBasisBuilder::RitzBasisBuilder(const SparseMat& K, const VecX& vertexMass, const MatX3& rest,
                                   const MatX3i& F, const RitzSettings& settings)
    : K_(K), settings_(settings) {
  prepare(vertexMass, rest, F);
  const Eigen::Index n = rest.rows();
  basis_.fullVertexCount = static_cast<int>(n);
  basis_.freeVertices.resize(static_cast<size_t>(n));
  std::iota(basis_.freeVertices.begin(), basis_.freeVertices.end(), 0);
  basis_.freeMass = vertexMass;
  basis_.solver = "ritz";
  if (settings.modes.modeCount > 0) {
    // K's factorisation and step 1 (which factorises K − σM for itself) are independent: on two
    // threads they overlap. Body 0 first, so a K that is not positive definite says so first.
    parallelFor(2, [&](std::int64_t part) {
      if (part == 0)
        factorize();
      else
        lowestModes(K_, mass3_, settings.modes, basis_.lambda, basis_.Phi, nullptr);
    });
    basis_.solver += "+modes";
  } else {
    factorize();
    basis_.Phi.resize(3 * n, 0);
    basis_.lambda.resize(0);
  }
  basis_.Psi = W_ * basis_.Phi;
}

RitzBasisBuilder::RitzBasisBuilder(const SparseMat& K, const VecX& vertexMass, const MatX3& rest,
                                   const MatX3i& F, const RitzSettings& settings, ModalBasis start)
    : K_(K), settings_(settings) {
  const Eigen::Index n = rest.rows();
  const Eigen::Index d = start.lambda.size();
  bool fits = start.fullVertexCount == n && start.freeCount() == n && start.Phi.rows() == 3 * n &&
              start.Phi.cols() == d && start.Psi.rows() == 3 * n && start.Psi.cols() == d;
  for (Eigen::Index i = 0; fits && i < n; ++i) fits = start.freeVertices[static_cast<size_t>(i)] == i;
  if (!fits) throw InputError("Ritz basis: the start basis does not fit this mesh (n = " + std::to_string(n) + ")");
  prepare(vertexMass, rest, F);
  factorize();
  basis_ = std::move(start);
}

void RitzBasisBuilder::prepare(const VecX& vertexMass, const MatX3& rest, const MatX3i& F) {
  const Eigen::Index n = rest.rows();
  if (K_.rows() != 3 * n || K_.cols() != 3 * n || vertexMass.size() != n)
    throw InputError("Ritz basis: K must be 3n×3n and the masses n (n = " + std::to_string(n) + ")");
  if (settings_.modes.modeCount < 0 || settings_.modes.modeCount > 3 * n)
    throw InputError("Ritz basis: mode count must lie in [0, 3n]");
  if (!(vertexMass.minCoeff() > 0.0)) throw InputError("Ritz basis: every vertex mass must be > 0");
  W_ = myo::rotationOperator(rest, F);  // the free function, not the accessor
  mass3_.resize(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) mass3_.segment<3>(3 * i).setConstant(vertexMass(i));
}

void RitzBasisBuilder::factorize() {
  ldlt_.compute(K_);
  if (ldlt_.info() != Eigen::Success || !(ldlt_.vectorD().minCoeff() > 0.0))
    throw NumericalError("Ritz basis: K is not positive definite");
}

MatX3 RitzBasisBuilder::staticResponse(const MatX3& f) const {
  VecX r = ldlt_.solve(flat(f));
  MatX3 out = rows3(r);
  return out;
}

bool RitzBasisBuilder::addLoad(const MatX3& f) {
  if (f.rows() * 3 != K_.rows()) throw InputError("Ritz basis: the load must be n×3");
  return appendResponse(ldlt_.solve(flat(f)));
}

int RitzBasisBuilder::addLoads(const std::vector<MatX3>& loads) {
  for (const MatX3& f : loads)
    if (f.rows() * 3 != K_.rows()) throw InputError("Ritz basis: the load must be n×3");
  // The solves are independent (one kept factorisation, read only); the orthogonalisation is not.
  // In chunks, so that a few dozen responses are held at a time, not one per load.
  const size_t chunk = static_cast<size_t>(4 * parallelThreads());
  int appended = 0;
  for (size_t first = 0; first < loads.size(); first += chunk) {
    std::vector<VecX> responses(std::min(chunk, loads.size() - first));
    parallelFor(static_cast<std::int64_t>(responses.size()), [&](std::int64_t k) {
      responses[static_cast<size_t>(k)] = ldlt_.solve(flat(loads[first + static_cast<size_t>(k)]));
    });
    for (VecX& r : responses) appended += appendResponse(std::move(r)) ? 1 : 0;
  }
  return appended;
}

bool RitzBasisBuilder::appendResponse(VecX r) {
  const double before = std::sqrt(r.dot(mass3_.cwiseProduct(r)));
  if (!(before > 0.0)) {
    ++deflated_;
    return false;
  }
  const MatX& Phi = basis_.Phi;
  for (int pass = 0; pass < 2; ++pass) r -= Phi * (Phi.transpose() * mass3_.cwiseProduct(r));
  const double after = std::sqrt(r.dot(mass3_.cwiseProduct(r)));
  if (!(after > settings_.deflationTolerance * before)) {
    ++deflated_;
    return false;
  }
  r /= after;
  const Eigen::Index d = Phi.cols();
  basis_.Phi.conservativeResize(Eigen::NoChange, d + 1);
  basis_.Phi.col(d) = r;
  basis_.Psi.conservativeResize(Eigen::NoChange, d + 1);
  basis_.Psi.col(d) = W_ * r;
  basis_.lambda.conservativeResize(d + 1);
  basis_.lambda(d) = r.dot(K_ * r);
  diagonal_ = false;
  ++appended_;
  return true;
}

void RitzBasisBuilder::diagonalize() {
  if (diagonal_) return;
  const MatX KPhi = K_ * basis_.Phi;
  MatX Kr = basis_.Phi.transpose() * KPhi;
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<MatX> eig(Kr);
  if (eig.info() != Eigen::Success) throw NumericalError("Ritz basis: the reduced eigenproblem failed");
  const MatX& Z = eig.eigenvectors();  // ascending eigenvalues
  basis_.Phi = (basis_.Phi * Z).eval();
  basis_.Psi = (basis_.Psi * Z).eval();
  basis_.lambda = eig.eigenvalues();
  diagonal_ = true;
}

bool RitzBasisBuilder::addLoadAndDiagonalize(const MatX3& f) {
  const bool added = addLoad(f);
  diagonalize();
  return added;
}

}  // namespace myo
