#include "myoshell/anatomy/contact_penalty.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/portable_math.h"

namespace myo {

namespace {

// Within this of the arch at rest (cm along the arch's outward ray) a tested mouth vertex is in the
// teeth pattern with weight 1 − clearance/this: the lips' inner surface (≈ the 5–8 mm of lip between
// the stomion and the incisors).
constexpr double kTeethPatternReach = 0.5;

}  // namespace

std::vector<MatX3> contactLoadPatterns(const SkinPlacement& placement, const MatX3& rest, const VecX& mass) {
  const Eigen::Index n = rest.rows();
  std::vector<MatX3> out;
  auto keep = [&](MatX3&& f) {
    if (f.squaredNorm() > 0.0) out.push_back(std::move(f));
  };
  if (const LidRig* lids = placement.lids()) {
    for (const EyeLids& eye : lids->eyes) {
      std::vector<bool> inOrbit(static_cast<size_t>(n), false);
      for (int i : eye.orbitVertices) inOrbit[static_cast<size_t>(i)] = true;
      MatX3 upper = MatX3::Zero(n, 3), lower = MatX3::Zero(n, 3);
      for (size_t k = 0; k < eye.lidVertices.size(); ++k) {
        const int i = eye.lidVertices[k];
        if (!inOrbit[static_cast<size_t>(i)]) continue;
        const Vec3 d = rest.row(i).transpose() - eye.centre;
        if (!(d.norm() > 0.0)) continue;
        const double w = eye.lidWeights[k];
        (w > 0.0 ? upper : lower).row(i) = (mass(i) * std::abs(w) * d.normalized()).transpose();
      }
      keep(std::move(upper));
      keep(std::move(lower));
    }
  }
  if (const MouthContact* mouth = placement.mouth()) {
    const JawRig& jaw = *placement.jaw();
    MatX3 upper = MatX3::Zero(n, 3), lower = MatX3::Zero(n, 3);
    for (int i : mouth->vertices) {
      const Vec3 p = rest.row(i).transpose();
      const Vec3 out = archOutward(*mouth, p);
      // The clearance along the outward ray: the distance to the arch's surface (the rest is outside).
      const Vec3 q = mouth->frame.axes.transpose() * (p - mouth->frame.origin);
      const double x = q.x() / mouth->a, z = (q.z() - mouth->zCentre) / mouth->b;
      const double s = std::sqrt(x * x + z * z);
      const double rho = planarLength(q.x(), q.z() - mouth->zCentre);
      const double clearance = s > 0.0 ? rho * (1.0 - 1.0 / s) : 0.0;
      const double w = std::max(0.0, 1.0 - clearance / kTeethPatternReach);
      if (w == 0.0) continue;
      (jaw.weights(i) >= 0.5 ? lower : upper).row(i) = (mass(i) * w * out).transpose();
    }
    keep(std::move(upper));
    keep(std::move(lower));
    const Vec3 y = mouth->frame.axes.col(1);
    MatX3 up = MatX3::Zero(n, 3), down = MatX3::Zero(n, 3);
    for (const auto& [u, l] : mouth->lipPairs) {
      up.row(u) = (mass(u) * y).transpose();
      down.row(l) = (-mass(l) * y).transpose();
    }
    keep(std::move(up));
    keep(std::move(down));
  }
  return out;
}

ContactPenalty::ContactPenalty(const SkinPlacement& placement, const MatX3& rest, const VecX& vertexMass,
                               const ModalBasis& basis, double stiffnessPerMass)
    : placement_(&placement), n_(static_cast<int>(rest.rows())), kappa_(stiffnessPerMass) {
  if (!(stiffnessPerMass > 0.0) || !std::isfinite(stiffnessPerMass))
    throw InputError("contact: the penalty stiffness per unit mass must be > 0 1/s²");
  MYO_CHECK(basis.fullVertexCount == n_ && basis.freeCount() == n_, "contact penalty: the basis must hold every vertex");
  std::vector<bool> is(static_cast<size_t>(n_), false);
  auto add = [&](int i) { is[static_cast<size_t>(i)] = true; };
  if (const LidRig* lids = placement.lids())
    for (const EyeLids& eye : lids->eyes) {
      for (int i : eye.lidVertices) add(i);
      for (int i : eye.upperMargin) add(i);
      for (int i : eye.lowerMargin) add(i);
      for (int i : eye.orbitVertices) add(i);
    }
  if (const MouthContact* mouth = placement.mouth()) {
    for (int i : mouth->vertices) add(i);
    for (const auto& [u, l] : mouth->lipPairs) add(u), add(l);
  }
  rowOf_.assign(static_cast<size_t>(n_), -1);
  for (int i = 0; i < n_; ++i)
    if (is[static_cast<size_t>(i)]) {
      rowOf_[static_cast<size_t>(i)] = static_cast<int>(rows_.size());
      rows_.push_back(i);
    }
  const auto k = static_cast<Eigen::Index>(rows_.size());
  lidSlot_.assign(rows_.size(), {-1, -1});
  if (const LidRig* lids = placement.lids())
    for (int e = 0; e < 2; ++e) {
      const EyeLids& eye = lids->eyes[static_cast<size_t>(e)];
      for (size_t j = 0; j < eye.lidVertices.size(); ++j)
        lidSlot_[static_cast<size_t>(rowOf_[static_cast<size_t>(eye.lidVertices[j])])] = {e, static_cast<int>(j)};
    }
  const Eigen::Index d = basis.modeCount();
  rest_.resize(k, 3);
  mass_.resize(k);
  Phi_.resize(3 * k, d);
  for (Eigen::Index r = 0; r < k; ++r) {
    const int i = rows_[static_cast<size_t>(r)];
    rest_.row(r) = rest.row(i);
    mass_(r) = vertexMass(i);
    Phi_.middleRows(3 * r, 3) = basis.Phi.middleRows(3 * i, 3);
  }
}

ContactPenalty::Workspace ContactPenalty::workspace() const {
  Workspace ws;
  ws.positions = MatX3::Zero(n_, 3);
  const auto k = static_cast<Eigen::Index>(rows_.size());
  ws.u.resize(3 * k);
  ws.J.assign(rows_.size(), Mat3::Identity());
  ws.gradient = MatX3::Zero(k, 3);
  ws.active.reserve(rows_.size());
  ws.flagged.assign(rows_.size(), 0);
  ws.closureTerms.reserve(rows_.size());
  ws.closureReads.reserve(32);  // a term reads its own row and up to nine margin entries
  ws.a = VecX::Zero(Phi_.cols());
  if (const LidRig* lids = placement_->lids()) {
    ws.jawed = MatX3::Zero(n_, 3);
    size_t margin = 0;
    for (size_t e = 0; e < 2; ++e) {
      ws.lidTurns[e].reserve(lids->eyes[e].lidVertices.size());
      margin = std::max({margin, lids->eyes[e].upperMargin.size(), lids->eyes[e].lowerMargin.size()});
    }
    for (LidMarginCurve* c : {&ws.fissure.upper, &ws.fissure.lower, &ws.movedFissure.upper, &ws.movedFissure.lower}) {
      c->byX.reserve(margin);
      c->elevation.reserve(margin);
      c->distance.reserve(margin);
    }
  }
  return ws;
}

double ContactPenalty::evaluate(const VecX& q, const JawPose& jaw, const LidPose& lids, Workspace& ws, VecX* force,
                                MatX* stiffness, double* maxDepth) const {
  MYO_CHECK(q.size() == Phi_.cols(), "contact penalty: q has " << q.size() << " amplitudes, the basis " << Phi_.cols());
  const auto k = static_cast<Eigen::Index>(rows_.size());
  if (maxDepth) *maxDepth = 0.0;
  if (k == 0) return 0.0;
  ws.u.noalias() = Phi_ * q;
  // Place the candidates as SkinPlacement::place does: the jaw's blended turn, then the lids'.
  for (Eigen::Index r = 0; r < k; ++r)
    ws.positions.row(rows_[static_cast<size_t>(r)]) =
        jawed(r, ws.u.segment<3>(3 * r), jaw, &ws.J[static_cast<size_t>(r)]).transpose();
  const LidRig* lr = placement_->lids();
  if (lr && !lids.isZero()) {
    turnLids(*lr, lids, ws.positions, &ws.lidTurns, &ws.fissure);
    for (size_t e = 0; e < 2; ++e) {
      const EyeLids& eye = lr->eyes[e];
      for (size_t j = 0; j < eye.lidVertices.size(); ++j) {
        const int r = rowOf_[static_cast<size_t>(eye.lidVertices[j])];
        ws.J[static_cast<size_t>(r)] = ws.lidTurns[e][j] * ws.J[static_cast<size_t>(r)];
      }
    }
  }

  // The violated constraints: E_t = ½ k_t δ_t², ∂E/∂x = k_t δ_t ∇δ_t per vertex of the term.
  double energy = 0.0, deepest = 0.0;
  for (int r : ws.active) {
    ws.gradient.row(r).setZero();
    ws.flagged[static_cast<size_t>(r)] = 0;
  }
  ws.active.clear();
  auto term = [&](double depth, double kt, std::initializer_list<std::pair<int, Vec3>> parts) {
    energy += 0.5 * kt * depth * depth;
    deepest = std::max(deepest, depth);
    VecX& a = ws.a;
    if (stiffness) a.setZero();
    for (const auto& [r, grad] : parts) {
      if (!ws.flagged[static_cast<size_t>(r)]) {
        ws.flagged[static_cast<size_t>(r)] = 1;
        ws.active.push_back(r);
      }
      ws.gradient.row(r) += (kt * depth * grad).transpose();
      if (stiffness) a.noalias() += Phi_.middleRows(3 * r, 3).transpose() * (ws.J[static_cast<size_t>(r)].transpose() * grad);
    }
    if (stiffness) stiffness->selfadjointView<Eigen::Lower>().rankUpdate(a, kt);
  };
  ws.closureTerms.clear();
  if (lr)
    for (int e = 0; e < 2; ++e) {
      const EyeLids& eye = lr->eyes[static_cast<size_t>(e)];
      // Does this eye's turn depend on the skin's rows (a closure, or the gaze's share Δ(x)/Δmax)?
      const bool chained = lids.close[static_cast<size_t>(e)] != 0.0 || lids.gaze.pitchDeg[static_cast<size_t>(e)] != 0.0 ||
                           lids.gaze.yawDeg[static_cast<size_t>(e)] != 0.0;
      for (int i : eye.orbitVertices) {
        const Vec3 dv = ws.positions.row(i).transpose() - eye.centre;
        const double dist = dv.norm();
        if (dist >= eye.contactRadius || dist == 0.0) continue;
        const int r = rowOf_[static_cast<size_t>(i)];
        const double depth = eye.contactRadius - dist, kt = kappa_ * mass_(r);
        if (!chained || lidSlot_[static_cast<size_t>(r)][0] != e) {
          term(depth, kt, {{r, Vec3(-dv / dist)}});
          continue;
        }
        // Its a_t comes from the turn's chain below (the row's gradient stays zero).
        energy += 0.5 * kt * depth * depth;
        deepest = std::max(deepest, depth);
        if (!ws.flagged[static_cast<size_t>(r)]) {
          ws.flagged[static_cast<size_t>(r)] = 1;
          ws.active.push_back(r);
        }
        ws.closureTerms.push_back({r, e, lidSlot_[static_cast<size_t>(r)][1], kt, depth, Vec3(-dv / dist)});
      }
    }
  if (const MouthContact* mouth = placement_->mouth()) {
    const Vec3 y = mouth->frame.axes.col(1);
    for (size_t p = 0; p < mouth->lipPairs.size(); ++p) {
      const double v = lipPairViolation(*mouth, p, ws.positions);
      if (v <= 0.0) continue;
      const int ru = rowOf_[static_cast<size_t>(mouth->lipPairs[p].first)];
      const int rl = rowOf_[static_cast<size_t>(mouth->lipPairs[p].second)];
      term(v, 0.5 * kappa_ * std::min(mass_(ru), mass_(rl)), {{ru, Vec3(-y)}, {rl, y}});
    }
    const RigidMotion mandible = jawMotion(*placement_->jaw(), jaw, 1.0);
    for (int i : mouth->vertices) {
      Vec3 g;
      const double depth = teethPenetration(*mouth, mandible, ws.positions.row(i).transpose(), &g);
      if (depth <= 0.0) continue;
      const int r = rowOf_[static_cast<size_t>(i)];
      term(depth, kappa_ * mass_(r), {{r, g}});
    }
  }
  if (!ws.closureTerms.empty() && (force || stiffness)) closureChain(jaw, lids, ws, force, stiffness);
  if (stiffness) stiffness->triangularView<Eigen::StrictlyUpper>() = stiffness->transpose();
  // −∂E/∂q = −Σ Φ_iᵀ J_iᵀ ∂E/∂x_i over the violated rows only.
  if (force)
    for (int r : ws.active)
      force->noalias() -= Phi_.middleRows(3 * r, 3).transpose() * (ws.J[static_cast<size_t>(r)].transpose() * ws.gradient.row(r).transpose());
  if (maxDepth) *maxDepth = deepest;
  return energy;
}

Vec3 ContactPenalty::jawed(Eigen::Index r, const Vec3& u, const JawPose& jaw, Mat3* turn) const {
  const JawRig* jr = placement_->jaw();
  const Vec3 X = rest_.row(r).transpose();
  const double w = jr && !jaw.isZero() ? jr->weights(rows_[static_cast<size_t>(r)]) : 0.0;
  if (w == 0.0) {
    turn->setIdentity();
    return X + u;
  }
  const RigidMotion m = jawMotion(*jr, jaw, w);
  *turn = m.R;
  return m.apply(X) + m.R * u;
}

void ContactPenalty::closureChain(const JawPose& jaw, const LidPose& lids, Workspace& ws, VecX* force, MatX* stiffness) const {
  const LidRig& lr = *placement_->lids();
  // The rows the turn reads, the margins and the touching vertices, at their jawed place.
  Mat3 jawTurn;
  auto place = [&](int i) {
    const auto r = static_cast<Eigen::Index>(rowOf_[static_cast<size_t>(i)]);
    ws.jawed.row(i) = jawed(r, ws.u.segment<3>(3 * r), jaw, &jawTurn).transpose();
  };
  for (int e = 0; e < 2; ++e) {
    const EyeLids& eye = lr.eyes[static_cast<size_t>(e)];
    if (std::none_of(ws.closureTerms.begin(), ws.closureTerms.end(), [&](const ClosureTerm& t) { return t.eye == e; }))
      continue;
    for (int i : eye.upperMargin) place(i);
    for (int i : eye.lowerMargin) place(i);
    for (const ClosureTerm& t : ws.closureTerms)
      if (t.eye == e) place(rows_[static_cast<size_t>(t.row)]);
    const EyeClosure closure = measureClosure(eye, lids, static_cast<size_t>(e), ws.jawed, ws.movedFissure);
    // a_t = Σ_v Φ_vᵀ R_jaw,vᵀ ∂(∇δ_t · x_i)/∂p_v over the rows the turn reads; then −k_t δ_t a_t to
    // the force and k_t a_t a_tᵀ to the stiffness's lower triangle (evaluate mirrors it).
    for (const ClosureTerm& t : ws.closureTerms) {
      if (t.eye != e) continue;
      const int i = rows_[static_cast<size_t>(t.row)];
      turnLidVertexGradient(eye, closure, ws.movedFissure, static_cast<size_t>(t.slot), ws.jawed.row(i).transpose(), t.grad,
                            ws.closureReads);
      ws.a.setZero();
      for (const auto& [v, byP] : ws.closureReads) {
        const auto r = static_cast<Eigen::Index>(rowOf_[static_cast<size_t>(v)]);
        jawed(r, ws.u.segment<3>(3 * r), jaw, &jawTurn);
        ws.a.noalias() += Phi_.middleRows(3 * r, 3).transpose() * (jawTurn.transpose() * byP);
      }
      if (force) force->noalias() -= (t.k * t.depth) * ws.a;
      if (stiffness) stiffness->selfadjointView<Eigen::Lower>().rankUpdate(ws.a, t.k);
    }
  }
}

}  // namespace myo
