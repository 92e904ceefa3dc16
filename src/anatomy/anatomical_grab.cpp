// A drag's grip moved at run time (AnatomicalStepper::grab; docs/anatomical_model.md, "A grip moved
// at run time"). The skin and its basis are shared and immutable: the stepper keeps its own basis,
// the skin's extended by the moved grips' static responses and the current state.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include "myoshell/anatomy/anatomical_stepper.h"
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/parallel.h"
#include "myoshell/core/timer.h"

namespace myo {

double AnatomicalStepper::grab(int drag, int vertex, double radius) {
  Stopwatch clock;
  MYO_CHECK(drag >= 0 && drag < static_cast<int>(grips_.size()), "drag index " << drag);
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw InputError("drag: radius " + std::to_string(radius) + " cm must be ≥ 0");
  const AnatomicalSkin& skin = *skin_;
  std::vector<int> vertices = skin.dragVertices(vertex, radius);  // InputError outside the mesh
  grabTimes_ = {};
  Grip& grip = grips_[static_cast<size_t>(drag)];
  if (vertices == grip.vertices) return grabTimes_.total = clock.seconds();  // the grip it has

  const ModalBasis& B0 = *skin.basis_;  // the skin's: diagonal for K (Λ₀)
  const ModalBasis& Bc = integrator_.basis();
  const Eigen::Index n3 = B0.Phi.rows();
  const Eigen::Index d0 = B0.modeCount();

  // The grip's static responses K⁻¹f_a (f_a = ê_a spread over the vertices), unless the skin's own
  // drag is there (its responses are in the skin's basis).
  MatX responses;
  const bool home = vertices == skin.drags_[static_cast<size_t>(drag)].vertices;
  bool anyMoved = !home;
  for (size_t k = 0; k < grips_.size(); ++k)
    if (static_cast<int>(k) != drag && grips_[k].responses.size() > 0) anyMoved = true;
  const RitzBasisBuilder* builder = anyMoved ? &skin.builder() : nullptr;  // K̂ = LDLᵀ, kept by the skin
  grabTimes_.factorisation = clock.seconds();
  if (!home) {
    responses.resize(n3, 3);
    parallelFor(3, [&](std::int64_t a) {  // independent solves with the one kept factorisation
      responses.col(a) = flat(builder->staticResponse(skin.dragPattern(vertices, static_cast<int>(a))));
    });
    grabTimes_.solves = clock.seconds() - grabTimes_.factorisation;
    // The release (Woodbury, as linearFullResponse): K⁻¹f = y + K̂⁻¹C̃ S (I − S C̃ᵀK̂⁻¹C̃ S)⁻¹ S C̃ᵀy,
    // y = K̂⁻¹f, S = Ρ^½, with K̂⁻¹C̃ = Φ_h Λ_h⁻¹ Φ_hᵀC̃ from the held basis (it spans K̂⁻¹C̃), so the
    // release costs no solve.
    // What no grip changes (C̃ᵀΦ_h, the R × R factorisation) is the skin's, made at the first grab.
    const SparseMat& C = skin.releaseColumns_;
    if (C.cols() > 0) {
      const AnatomicalSkin::ReleaseSolve& release = skin.releaseSolve();
      const MatX SCy = release.S.asDiagonal() * (C.transpose() * responses);  // R × 3
      const MatX z = release.S.asDiagonal() * MatX(release.D.solve(SCy));
      responses.noalias() += builder->basis().Phi * (release.PL.transpose() * z);
    }
  }
  grabTimes_.responses = clock.seconds() - grabTimes_.factorisation;
  grip.vertices = std::move(vertices);
  grip.responses = std::move(responses);

  // The candidates for the new vectors, each with its Ψ (= W times it) when warping: every moved
  // grip's responses, then the state's fields u = Φ_c q and v = Φ_c q̇ (Ψ_c q, Ψ_c q̇), so that the
  // state lies in the new span whatever grips it came from. With linear modes the integrator never
  // reads Ψ: the extended basis carries none (half the cost of turning the basis).
  const bool warped = skin.settings_.warping;
  std::vector<VecX> phi, psi;
  std::vector<double> tolerance;
  for (const Grip& g : grips_)
    for (Eigen::Index a = 0; a < g.responses.cols(); ++a) {
      phi.push_back(g.responses.col(a));
      psi.push_back(warped ? VecX(builder->rotationOperator() * phi.back()) : VecX());
      tolerance.push_back(skin.ritz_.deflationTolerance);
    }
  const VecX& q = integrator_.q();
  const VecX& qdot = integrator_.qdot();
  for (const VecX* s : {&q, &qdot})
    if (s->size() > 0 && s->squaredNorm() > 0.0) {
      phi.push_back(Bc.Phi * *s);
      psi.push_back(warped ? VecX(Bc.Psi * *s) : VecX());
      tolerance.push_back(1e-12);  // the state must stay exact: keep all but round-off
    }
  if (phi.empty()) {  // nothing moved and the stepper at rest: the skin's basis as it is
    ModalWarpingSettings settings = integrator_.settings();
    integrator_ = ModalWarpingIntegrator(skin.basis_, settings);
    penalty_ = skin.penalty_;
    fitToBasis();
    grabTimes_.total = clock.seconds();
    grabTimes_.basis = grabTimes_.total - grabTimes_.factorisation - grabTimes_.responses;
    return grabTimes_.total;
  }

  // M-orthonormalise against the skin's basis and each other (twice), with the Ritz deflation.
  VecX mass3(n3);
  for (Eigen::Index i = 0; i < n3 / 3; ++i) mass3.segment<3>(3 * i).setConstant(skin.mass_(i));
  MatX X(n3, static_cast<Eigen::Index>(phi.size())), PsiX(warped ? n3 : 0, X.cols());
  Eigen::Index k = 0;
  for (size_t c = 0; c < phi.size(); ++c) {
    VecX& x = phi[c];
    VecX& w = psi[c];
    const double before = std::sqrt(x.dot(mass3.cwiseProduct(x)));
    if (!(before > 0.0)) continue;
    for (int pass = 0; pass < 2; ++pass) {
      const VecX Mx = mass3.cwiseProduct(x);
      const VecX a = B0.Phi.transpose() * Mx;
      const VecX b = X.leftCols(k).transpose() * Mx;
      x.noalias() -= B0.Phi * a;
      x.noalias() -= X.leftCols(k) * b;
      if (!warped) continue;
      w.noalias() -= B0.Psi * a;
      w.noalias() -= PsiX.leftCols(k) * b;
    }
    const double after = std::sqrt(x.dot(mass3.cwiseProduct(x)));
    if (!(after > tolerance[c] * before)) continue;
    X.col(k) = x / after;
    if (warped) PsiX.col(k) = w / after;
    ++k;
  }
  X.conservativeResize(Eigen::NoChange, k);
  PsiX.conservativeResize(Eigen::NoChange, k);

  // The reduced stiffness in [Φ₀ X] with K = K̂ − C̃ΡC̃ᵀ: Λ₀ on the skin's block, Φ₀ᵀKX and XᵀKX
  // from K applied to the new vectors; then re-diagonalised, K_r = Z Λ Zᵀ.
  MatX KX = skin.Khat_ * X;
  if (skin.releaseColumns_.cols() > 0)
    KX.noalias() -= skin.releaseColumns_ * (skin.releaseRho_.asDiagonal() * (skin.releaseColumns_.transpose() * X));
  MatX Kr = MatX::Zero(d0 + k, d0 + k);
  Kr.topLeftCorner(d0, d0).diagonal() = B0.lambda;
  Kr.topRightCorner(d0, k) = B0.Phi.transpose() * KX;
  Kr.bottomLeftCorner(k, d0) = Kr.topRightCorner(d0, k).transpose();
  const MatX XKX = X.transpose() * KX;
  Kr.bottomRightCorner(k, k) = 0.5 * (XKX + XKX.transpose());
  const Eigen::SelfAdjointEigenSolver<MatX> eig(Kr);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues().minCoeff() > 0))
    throw NumericalError("anatomical model: the basis extended for a drag's grip is not positive definite");
  const MatX& Z = eig.eigenvectors();

  // The state's coordinates in [Φ₀ X] (M-projection: exact, the state lies in the span), turned.
  auto coordinates = [&](const VecX& s) -> VecX {
    if (s.size() == 0 || s.squaredNorm() == 0.0) return VecX::Zero(d0 + k);
    const VecX Mu = mass3.cwiseProduct(VecX(Bc.Phi * s));
    VecX c(d0 + k);
    c.head(d0) = B0.Phi.transpose() * Mu;
    c.tail(k) = X.transpose() * Mu;
    return Z.transpose() * c;
  };
  const VecX qNew = coordinates(q), qdotNew = coordinates(qdot);

  ModalBasis b;  // every field of the skin's basis but Φ, Ψ, λ
  b.fullVertexCount = B0.fullVertexCount;
  b.freeVertices = B0.freeVertices;
  b.freeMass = B0.freeMass;
  b.solveSeconds = B0.solveSeconds;
  b.solver = B0.solver;
  b.fromCache = B0.fromCache;
  b.Phi.noalias() = B0.Phi * Z.topRows(d0);
  b.Phi.noalias() += X * Z.bottomRows(k);
  if (warped) {
    b.Psi.noalias() = B0.Psi * Z.topRows(d0);
    b.Psi.noalias() += PsiX * Z.bottomRows(k);
  }
  b.lambda = eig.eigenvalues();
  auto basis = std::make_shared<const ModalBasis>(std::move(b));
  grabTimes_.basis = clock.seconds() - grabTimes_.factorisation - grabTimes_.responses;

  ModalWarpingSettings settings = integrator_.settings();
  integrator_ = ModalWarpingIntegrator(basis, settings);
  integrator_.setState(qNew, qdotNew);
  if (skin.penalty_)
    penalty_ = std::make_shared<const ContactPenalty>(*skin.placement_, skin.head_.mesh.V, skin.mass_, *basis,
                                                      skin.settings_.contactStiffness);
  fitToBasis();
  grabTimes_.total = clock.seconds();
  grabTimes_.finish = grabTimes_.total - grabTimes_.factorisation - grabTimes_.responses - grabTimes_.basis;
  return grabTimes_.total;
}

}  // namespace myo
