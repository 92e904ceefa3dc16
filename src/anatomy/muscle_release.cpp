// The relaxed muscles' release in the anatomical skin (docs/anatomical_model.md, "Relaxed muscles
// follow the skin", "Released across", "A ring is released in halves"): the columns a relaxed muscle
// lets go of, the released basis and the strengths that hold each muscle to its shortening.
#include "myoshell/anatomy/anatomical_skin.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/rotation_operator.h"

namespace myo {

namespace {

// The pieces a relaxed muscle is released in: (spring index, share of its stiffness) pairs. A ring's
// two halves when `splitRings` (a ring's path runs from anchor to anchor, so its first and second
// halves are the mouth parts' right and left quadrants, which interlace at the philtrum, and the eye
// rings' upper and lower arcs, which meet at the medial palpebral ligament and the lateral raphe);
// the whole muscle otherwise. A spring belongs to the first half by the barycentric weight its point
// has on first-half nodes, so a spring whose point lies between the halves is shared (two springs of
// μk and (1 − μ)k at one place: K̂ unchanged). A share rather than a side: the point is the same
// whichever triangle the closest-point search returns, the nearest node is not, and on a symmetric
// head the midline's springs are ties that an ulp of the geometry decides.
using ReleasePiece = std::vector<std::pair<size_t, double>>;
std::vector<ReleasePiece> releasePieces(const CoupledMuscle& cm, bool splitRings) {
  if (!splitRings || !cm.muscle.def.isRing()) {
    ReleasePiece all(cm.springs.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = {i, 1.0};
    return {all};
  }
  const int stations = cm.muscle.def.stations;
  std::vector<ReleasePiece> halves(2);
  for (size_t i = 0; i < cm.springs.size(); ++i) {
    const CoupledMuscle::Spring& spring = cm.springs[i];
    double first = 0.0;
    for (size_t b = 0; b < spring.nodes.size(); ++b)
      if (2 * cm.muscle.stationOf(spring.nodes[b]) < stations) first += spring.weights[b];
    first = std::clamp(first, 0.0, 1.0);
    if (first > 0.0) halves[0].emplace_back(i, first);
    if (first < 1.0) halves[1].emplace_back(i, 1.0 - first);
  }
  return halves;
}

}  // namespace


// Relaxed muscles follow the skin (docs/anatomical_model.md, "Relaxed muscles follow the skin" and
// "Released across"). Muscle m moves with coordinates p in the shapes Q̃_m (at its springs), the
// first its own shape U_m/√s_m (s_m = Σ k_i |w_i|², w = U at the springs; U the shape's tangent at
// rest, CoupledMuscle::releaseShape, where it differs: a ring in a lip's body), the others its motion
// across: |w_i| ê_a (a = x, y, z: weighted as the shape, so nothing moves at the origin), made
// S-orthogonal to the shape and S-orthonormal (S the coupling metric Σ k_i v_i·v'_i; a direction
// already spanned is dropped). Its energy: the passive belly ½ (κ_m/s_m) |p|² (κ_m = E_p A σ² L along
// the shape, the same per unit of coupling energy across), the active force along the shape, and the
// couplings ½ Σ k_i |Q̃_i p − u_i|². Eliminating p, the skin sees K̂ − ρ_m C̃_m C̃_mᵀ with
// C̃_m = K_c,m Q̃_m and ρ_m = s_m/(s_m + κ_m), and the load a_m α_m c_m (c_m = K_c,m w).
void AnatomicalSkin::buildReleaseColumns() {
  const int n = head_.mesh.vertexCount();
  const auto M = static_cast<Eigen::Index>(muscles_.size());
  release_.resize(0);
  extraReleaseColumns_ = 0;
  shapeEnergy_ = VecX::Zero(M);
  std::vector<Triplet> pulls;  // c_m = K_c,m w, column m
  for (Eigen::Index m = 0; m < M; ++m) {
    const CoupledMuscle& cm = muscles_[static_cast<size_t>(m)];
    for (const auto& spring : cm.springs) {
      const Vec3 w = spring.muscleDisplacement(cm.fullShape);
      const Vec3 pull = spring.tie(w);
      shapeEnergy_(m) += w.dot(pull);
      for (int c = 0; c < 3; ++c) pulls.emplace_back(3 * spring.skin + c, m, pull(c));
    }
  }
  couplingColumns_.resize(3 * n, M);
  couplingColumns_.setFromTriplets(pulls.begin(), pulls.end());
  if (!(settings_.relaxedMuscleModulus > 0) || M == 0) {
    releaseColumns_.resize(0, 0);
    releaseRho_.resize(0);
    return;
  }
  const double scale = head_.frame().scale;
  release_.resize(M);
  // Columns: the muscles' first shapes (0..M−1), then the extra ones (other halves, across).
  std::vector<Triplet> axial, extra;
  std::vector<double> rho(static_cast<size_t>(M)), rhoExtra;
  for (Eigen::Index m = 0; m < M; ++m) {
    const CoupledMuscle& cm = muscles_[static_cast<size_t>(m)];
    const MuscleDef& def = cm.muscle.def;
    const std::vector<ReleasePiece> pieces = releasePieces(cm, settings_.releaseRingHalves);
    // κ = E_p A σ² L for the whole belly; a piece of it has its share of the length.
    const double area = 0.25 * std::numbers::pi * (def.width * scale) * (def.thickness * scale);
    const double sigma = def.isRing() ? def.ring.shortening : settings_.coupling.shortening;
    const double kappaWhole = settings_.relaxedMuscleModulus * area * sigma * sigma * cm.muscle.restLength;
    const double kappa = kappaWhole / static_cast<double>(pieces.size());
    release_(m) = 1.0 / (kappaWhole + shapeEnergy_(m));
    for (size_t piece = 0; piece < pieces.size(); ++piece) {
      const ReleasePiece& springs = pieces[piece];
      const size_t ns = springs.size();
      std::vector<Vec3> w(ns);
      std::vector<int> skinVertex(ns);
      // K_i v: the spring's tie (a push's along its direction only) at its share.
      auto K = [&](size_t i, const Vec3& v) { return cm.springs[springs[i].first].tie(v, springs[i].second); };
      double s = 0.0;
      for (size_t i = 0; i < ns; ++i) {
        const CoupledMuscle::Spring& spring = cm.springs[springs[i].first];
        w[i] = spring.muscleDisplacement(cm.releaseShape.rows() ? cm.releaseShape : cm.fullShape);
        skinVertex[i] = spring.skin;
        s += w[i].dot(K(i, w[i]));
      }
      if (!(s > 0)) {
        if (piece == 0) rho[static_cast<size_t>(m)] = 0.0;
        continue;
      }
      const double root = std::sqrt(s);
      // The piece's shape: muscle m's own column for the first piece, an extra column for the other.
      const bool first = piece == 0;
      const Eigen::Index shapeCol = first ? m : extraReleaseColumns_++;
      for (size_t i = 0; i < ns; ++i) {
        const Vec3 pull = K(i, w[i]);
        for (int c = 0; c < 3; ++c) (first ? axial : extra).emplace_back(3 * skinVertex[i] + c, shapeCol, pull(c) / root);
      }
      if (first)
        rho[static_cast<size_t>(m)] = s / (s + kappa);
      else
        rhoExtra.push_back(s / (s + kappa));
      if (!settings_.releaseAcross) continue;
      // Across: v_a = |w| ê_a − (S(v_a, w)/s) w, then S-orthonormal through the eigenvectors of their Gram.
      std::vector<std::array<Vec3, 3>> v(ns);
      for (size_t i = 0; i < ns; ++i)
        for (int a = 0; a < 3; ++a) v[i][static_cast<size_t>(a)] = w[i].norm() * Vec3::Unit(a);
      Vec3 vw = Vec3::Zero();
      for (size_t i = 0; i < ns; ++i)
        for (int a = 0; a < 3; ++a) vw(a) += v[i][static_cast<size_t>(a)].dot(K(i, w[i]));
      for (size_t i = 0; i < ns; ++i)
        for (int a = 0; a < 3; ++a) v[i][static_cast<size_t>(a)] -= (vw(a) / s) * w[i];
      Mat3 G = Mat3::Zero();
      for (size_t i = 0; i < ns; ++i)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) G(a, b) += v[i][static_cast<size_t>(a)].dot(K(i, v[i][static_cast<size_t>(b)]));
      const Eigen::SelfAdjointEigenSolver<Mat3> eig(G);
      for (int j = 0; j < 3; ++j) {
        const double g = eig.eigenvalues()(j);
        if (!(g > 1e-6 * s)) continue;  // already spanned by the shape (a straight muscle's axis)
        const Vec3 e = eig.eigenvectors().col(j) / std::sqrt(g);
        const Eigen::Index col = extraReleaseColumns_++;
        for (size_t i = 0; i < ns; ++i) {
          const Vec3 vi = v[i][0] * e(0) + v[i][1] * e(1) + v[i][2] * e(2);
          const Vec3 pull = K(i, vi);
          for (int c = 0; c < 3; ++c) extra.emplace_back(3 * skinVertex[i] + c, col, pull(c));
        }
        rhoExtra.push_back(s / (s + kappa));
      }
    }
  }
  for (Triplet& t : extra) t = Triplet(t.row(), t.col() + static_cast<int>(M), t.value());
  axial.insert(axial.end(), extra.begin(), extra.end());
  releaseColumns_.resize(3 * n, M + extraReleaseColumns_);
  releaseColumns_.setFromTriplets(axial.begin(), axial.end());
  releaseRho_.resize(M + extraReleaseColumns_);
  for (Eigen::Index j = 0; j < M; ++j) releaseRho_(j) = rho[static_cast<size_t>(j)];
  for (int j = 0; j < extraReleaseColumns_; ++j) releaseRho_(M + j) = rhoExtra[static_cast<size_t>(j)];
}

// The release in the basis (the held basis spans K̂⁻¹C̃, so by the Woodbury identity every static
// response of K = K̂ − C̃ Ρ C̃ᵀ lies in it: the reduced model stays exact). K_r = Λ − P Ρ Pᵀ
// (P = ΦᵀC̃); F_m is set so that at a_m = 1, alone among the relaxed others, the muscle shortens by
// σ_m: α_m = 1/(1 + γ_m c_mᵀ K⁻¹ c_m). Then K_r is diagonalised, K_r = Z Λ' Zᵀ, and the basis turned,
// Φ' = ΦZ (still M-orthonormal: M_r = I), Ψ' = ΨZ. Released across, the held basis carries one vector
// per across column; it is cut back to the d lowest modes of K_r and K_r⁻¹Φᵀf for every load pattern
// f (the muscles' c_m, gravity along x, y, z, each drag's x, y, z), so the step costs what it did.
void AnatomicalSkin::releaseRelaxedMuscles() {
  ensureHeldBasis();
  const ModalBasis& held = *heldBasis_;
  const auto M = static_cast<Eigen::Index>(muscles_.size());
  if (releaseColumns_.cols() == 0 || M == 0 || held.modeCount() == 0) {
    basis_ = heldBasis_;
    setMuscleStrengths();
    makeContactPenalty();
    return;
  }
  const MatX P = (releaseColumns_.transpose() * held.Phi).transpose();  // D × R
  MatX Kr = held.lambda.asDiagonal();
  Kr.noalias() -= P * releaseRho_.asDiagonal() * P.transpose();
  const Eigen::SelfAdjointEigenSolver<MatX> eig(Kr);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues().minCoeff() > 0))
    throw NumericalError("anatomical model: the skin with its relaxed muscles released is not positive definite");
  const MatX& Z = eig.eigenvectors();
  const VecX& lam = eig.eigenvalues();
  auto solveKr = [&](const MatX& rhs) -> MatX { return Z * ((Z.transpose() * rhs).array().colwise() / lam.array()).matrix(); };
  MatX T;  // the final basis in the held one's coordinates
  VecX lambda;
  if (extraReleaseColumns_ == 0) {
    T = Z;
    lambda = lam;
  } else {
    const Eigen::Index dModes = std::min<Eigen::Index>(ritz_.modes.modeCount, Kr.rows());
    const MatX patterns = (cutBackPatternColumns().transpose() * held.Phi).transpose();
    const Eigen::Index nPatterns = patterns.cols();
    MatX Y(P.rows(), dModes + nPatterns);
    Y.leftCols(dModes) = Z.leftCols(dModes);
    Y.rightCols(nPatterns) = solveKr(patterns);
    // Orthonormalise (M_r = I), twice, dropping what is already spanned (the Ritz deflation).
    Eigen::Index kept = 0;
    for (Eigen::Index j = 0; j < Y.cols(); ++j) {
      VecX y = Y.col(j);
      const double before = y.norm();
      if (!(before > 0)) continue;
      for (int pass = 0; pass < 2; ++pass) y -= Y.leftCols(kept) * (Y.leftCols(kept).transpose() * y);
      if (y.norm() < ritz_.deflationTolerance * before) continue;
      Y.col(kept++) = y / y.norm();
    }
    Y.conservativeResize(Eigen::NoChange, kept);
    const Eigen::SelfAdjointEigenSolver<MatX> cut(Y.transpose() * Kr * Y);
    if (cut.info() != Eigen::Success || !(cut.eigenvalues().minCoeff() > 0))
      throw NumericalError("anatomical model: the released skin's cut-back basis is not positive definite");
    T = Y * cut.eigenvectors();
    lambda = cut.eigenvalues();
  }
  // Every field of `held` but Φ and Ψ (not copied: they are replaced, and are tens of MB).
  ModalBasis b;
  b.fullVertexCount = held.fullVertexCount;
  b.freeVertices = held.freeVertices;
  b.freeMass = held.freeMass;
  b.solveSeconds = held.solveSeconds;
  b.solver = held.solver;
  b.fromCache = held.fromCache;
  b.Phi = held.Phi * T;
  b.Psi = held.Psi * T;
  b.lambda = lambda;
  basis_ = std::make_shared<const ModalBasis>(std::move(b));
  setMuscleStrengths();
  makeContactPenalty();
}

RitzBasisBuilder& AnatomicalSkin::builder() const {
  std::lock_guard<std::mutex> lock(builderMutex_);
  ensureHeldBasis();
  if (!builder_)
    builder_ = std::make_unique<RitzBasisBuilder>(Khat_, mass_, head_.mesh.V, head_.mesh.F, ritz_, *heldBasis_);
  return *builder_;
}

const AnatomicalSkin::ReleaseSolve& AnatomicalSkin::releaseSolve() const {
  const ModalBasis& held = builder().basis();  // builder() takes the lock itself
  std::lock_guard<std::mutex> lock(builderMutex_);
  if (!releaseSolve_) {
    auto r = std::make_unique<ReleaseSolve>();
    r->CtPhi = releaseColumns_.transpose() * held.Phi;                 // R × D_h
    r->PL = r->CtPhi * held.lambda.cwiseInverse().asDiagonal();        // C̃ᵀΦ_h Λ_h⁻¹
    r->S = releaseRho_.cwiseSqrt();
    MatX D = -(r->S.asDiagonal() * (r->PL * r->CtPhi.transpose()) * r->S.asDiagonal());
    D.diagonal().array() += 1.0;
    r->D.compute(D);
    releaseSolve_ = std::move(r);
  }
  return *releaseSolve_;
}

}  // namespace myo
