#include "myoshell/anatomy/anatomical_stepper.h"

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

AnatomicalStepper::AnatomicalStepper(std::shared_ptr<const AnatomicalSkin> skin)
    : skin_(std::move(skin)),
      integrator_(skin_->basis(), [&] {
        ModalWarpingSettings s;
        s.dt = skin_->settings().dt;
        s.stepper = ModalStepper::Exact;
        s.warping = skin_->settings().warping;
        s.rayleighMass = skin_->settings().dampingMass;
        s.rayleighStiffness = skin_->settings().dampingStiffness;
        s.precision = ModalPrecision::Double;
        s.channel = "anatomical skin";
        return s;
      }()) {
  const Eigen::Index m = static_cast<Eigen::Index>(skin_->muscles().size());
  level_ = VecX::Zero(m);
  levelRate_ = VecX::Zero(m);
  for (const AnatomicalSkin::Drag& d : skin_->drags_) grips_.push_back({d.vertices, MatX()});
  if (skin_->settings().warping) force_ = MatX3::Zero(skin_->basis()->fullVertexCount, 3);
  penalty_ = skin_->penalty_;
  response_ = skin_->settings().response;
  fitToBasis();
}

void AnatomicalStepper::setResponse(SkinResponse response) {
  if (response == response_) return;
  response_ = response;
  levelRate_.setZero();  // Follow: levels are targets; Dynamic: they start at rest where they are
  fitToBasis();          // Follow: the centre from the levels; the integrator's q is kept
}

// The stepper's basis is the skin's until a grab extends it (anatomical_grab.cpp).
void AnatomicalStepper::fitToBasis() {
  const ModalBasis& B = integrator_.basis();
  const Eigen::Index d = B.modeCount();
  if (!skin_->settings().warping) {
    loadModes_ = skin_->modalLoadPatterns(B);
    const Eigen::Index first = loadModes_.cols() - 3 * static_cast<Eigen::Index>(grips_.size());
    for (size_t k = 0; k < grips_.size(); ++k) {  // a moved grip's ê_x, ê_y, ê_z spread over its vertices
      if (grips_[k].responses.size() == 0) continue;
      const std::vector<int>& vs = grips_[k].vertices;
      for (int a = 0; a < 3; ++a) {
        auto col = loadModes_.col(first + 3 * static_cast<Eigen::Index>(k) + a);
        col.setZero();
        for (int v : vs) col += B.Phi.row(3 * v + a).transpose();
        col /= static_cast<double>(vs.size());
      }
    }
    loadCoords_ = VecX::Zero(loadModes_.cols());
    modalForce_ = VecX::Zero(d);
  }
  if (response_ == SkinResponse::Follow) {
    // c = Λ⁻¹Φᵀ Σ a_m F_m: per mode the static response of the activations' loads (λ_j > 0: the
    // skin is held by the skull). After a grab the centre is re-expressed in the new basis; what
    // the old one held beyond it is carried by r.
    const Eigen::Index M = level_.size();
    quasiStatic_ = (skin_->settings().warping ? skin_->modalLoadPatterns(B) : loadModes_).leftCols(M);
    quasiStatic_.array().colwise() /= B.lambda.array();
    centre_ = quasiStatic_ * level_;
    centreNext_ = centre_;
  } else {
    quasiStatic_.resize(0, 0);
    centre_.resize(0);
    centreNext_.resize(0);
  }
  if (penalty_) {
    contact_ = penalty_->workspace();
    contactStiffness_ = MatX::Zero(d, d);
    contactForce_ = VecX::Zero(d);
    contactStep_ = VecX::Zero(d);
    contactSystem_ = MatX::Zero(d, d);
    contactLu_ = Eigen::PartialPivLU<MatX>(d);
  }
}

void AnatomicalStepper::reset() {
  level_.setZero();
  levelRate_.setZero();
  if (centre_.size()) centre_.setZero();
  integrator_.reset();
  times_ = {};
}

void AnatomicalStepper::step(const SkinLoads& loads) {
  skin_->validateLoads(loads);
  Stopwatch clock;
  const double h = skin_->settings().dt;
  const bool follow = response_ == SkinResponse::Follow;
  if (follow) {
    // Follow: the levels are the targets; the centre their quasi-static response (d×M).
    level_ = loads.activations;
    centreNext_.noalias() = quasiStatic_ * level_;
  }
  // Muscles: critically damped follow of the target at ω (implicit Euler: stable for any ω).
  for (Eigen::Index m = 0; !follow && m < level_.size(); ++m) {
    const double w = skin_->muscles()[static_cast<size_t>(m)].naturalFrequency;
    const double a = loads.activations(m);
    levelRate_(m) = (levelRate_(m) + h * w * w * (a - level_(m))) / (1.0 + 2.0 * h * w + h * h * w * w);
    level_(m) += h * levelRate_(m);
  }
  times_.levels = clock.seconds();
  const Vec3 dg = loads.gravity - skin_->gRest_;
  if (!skin_->settings().warping) {
    // f̃ = Φᵀ(Σ level_m F_m + M(g − g_rest) + drags) = loadModes_ [levels, g − g_rest, drags].
    const Eigen::Index M = level_.size();
    MYO_CHECK(M + 3 + 3 * static_cast<Eigen::Index>(loads.drags.size()) <= loadCoords_.size(),
              "a drag added to the skin after its stepper was made");
    loadCoords_.head(M) = level_;
    loadCoords_.segment<3>(M) = dg;
    loadCoords_.tail(loadCoords_.size() - M - 3).setZero();
    for (size_t k = 0; k < loads.drags.size(); ++k)
      loadCoords_.segment<3>(M + 3 + 3 * static_cast<Eigen::Index>(k)) = loads.drags[k];
    // Follow: the activations' columns are balanced by the centre (Λc = their f̃): r gets the rest.
    if (follow) {
      const Eigen::Index rest = loadCoords_.size() - M;
      modalForce_.noalias() = loadModes_.rightCols(rest) * loadCoords_.tail(rest);
    } else {
      modalForce_.noalias() = loadModes_ * loadCoords_;
    }
    if (loads.modalForce.size() != 0) {
      MYO_CHECK(loads.modalForce.size() == modalForce_.size(),
                "a modal force of " << loads.modalForce.size() << " for " << modalForce_.size() << " modes");
      modalForce_ += loads.modalForce;
    }
    // The contact penalty, linearly implicit (docs/mouth_contact.md, "Penalty forces"): at q_n its
    // force f_c and stiffness K_c; the step's force f_c − K_c Δ with Δ = q⁺ − q_n, so that
    // q⁺ = a q + b q̇ + g (f̃ + f_c − K_c Δ) gives (I + diag(g) K_c) Δ = a q + b q̇ + g (f̃ + f_c) − q.
    if (const ContactPenalty* pen = loads.contact ? penalty_.get() : nullptr) {
      contactForce_.setZero();
      contactStiffness_.setZero();
      LidPose lids = skin_->placement_->lidPose(loads.activations);
      lids.gaze = loads.gaze;
      pen->evaluate(integrator_.q(), loads.jaw, lids, contact_, &contactForce_, &contactStiffness_);
      if (!contact_.active.empty()) {
        const VecX& q = integrator_.q();
        const VecX& g = integrator_.stepQFromForce();
        modalForce_ += contactForce_;
        contactStep_ = integrator_.stepQFromQ().cwiseProduct(q) +
                       integrator_.stepQFromQdot().cwiseProduct(integrator_.qdot()) + g.cwiseProduct(modalForce_) - q;
        // Follow: the same about the centre, q⁺ = c⁺ + a (q − c) + b ṙ + g (f̃ + f_c − K_c Δ).
        if (follow) contactStep_ += centreNext_ - integrator_.stepQFromQ().cwiseProduct(centre_);
        // The dashpot βK_c on the step's motion Δ/h joins the stiffness (AnatomicalSettings::contactDamping).
        contactStiffness_ *= 1.0 + skin_->settings().contactDamping / h;
        contactSystem_.noalias() = g.asDiagonal() * contactStiffness_;
        contactSystem_.diagonal().array() += 1.0;
        contactLu_.compute(contactSystem_);
        contactStep_ = contactLu_.solve(contactStep_).eval();
        modalForce_.noalias() -= contactStiffness_ * contactStep_;
      }
    }
    times_.force = clock.seconds() - times_.levels;
    if (follow) {
      integrator_.stepModalAbout(modalForce_, centre_, centreNext_);
      centre_.swap(centreNext_);
    } else {
      integrator_.stepModal(modalForce_);
    }
    times_.modal = clock.seconds() - times_.levels - times_.force;
    return;
  }
  MYO_CHECK(loads.modalForce.size() == 0, "a modal force (SkinLoads::modalForce) needs linear modes: warping is on");
  // Reading (b): Σ level_m F_m + M(g − g_rest) + drags, built in place.
  const VecX& mass = skin_->mass_;
  for (Eigen::Index i = 0; i < force_.rows(); ++i) force_.row(i) = mass(i) * dg.transpose();
  for (Eigen::Index m = 0; m < level_.size(); ++m)
    if (level_(m) != 0.0) force_.noalias() += level_(m) * skin_->muscleLoads_[static_cast<size_t>(m)];
  MYO_CHECK(loads.drags.size() <= grips_.size(), "a drag added to the skin after its stepper was made");
  for (size_t k = 0; k < loads.drags.size(); ++k) {
    const auto& vs = grips_[k].vertices;
    for (int v : vs) force_.row(v) += loads.drags[k].transpose() / static_cast<double>(vs.size());
  }
  // Warped: no contact penalty in the step (the projection at output still holds; the warped
  // settle has it). docs/mouth_contact.md, "Penalty forces".
  times_.force = clock.seconds() - times_.levels;
  if (follow) {
    integrator_.stepAbout(force_, centre_, centreNext_);
    centre_.swap(centreNext_);
  } else {
    integrator_.step(force_);
  }
  times_.modal = clock.seconds() - times_.levels - times_.force;
}

bool AnatomicalStepper::isAtRest(double tol) const {
  return integrator_.isAtRest(tol) && (levelRate_.size() == 0 || levelRate_.cwiseAbs().maxCoeff() < tol);
}

}  // namespace myo
