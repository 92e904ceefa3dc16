#include "myoshell/thesis/simulator.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"

namespace myo {

Simulator::Simulator(std::shared_ptr<const FaceModel> model) : model_(std::move(model)) {
  MYO_CHECK(model_ != nullptr, "a simulator needs a model");
  const FaceModelSettings& s = model_->settings();
  for (const MuscleUnit& unit : model_->muscles()) {
    ModalWarpingSettings ms;
    ms.dt = s.dt;
    ms.stepper = s.stepper;
    ms.warping = s.warping;
    ms.precision = ModalPrecision::Double;  // one column: precision costs nothing here
    // One mode: its damping c = ξ = 2·ratio·ω (mass-proportional), so the ratio is exactly as set.
    ms.rayleighMass = 2.0 * s.muscleDampingRatio * std::sqrt(std::max(unit.basis->lambda(0), 0.0));
    ms.channel = "muscle " + unit.muscle.def.name;
    muscleIntegrators_.emplace_back(unit.basis, ms);
    muscleForce_.push_back(MatX3::Zero(unit.basis->freeCount(), 3));
  }
  for (const SkinChannel& ch : model_->channels()) {
    ModalWarpingSettings cs;
    cs.dt = s.dt;
    cs.stepper = s.stepper;
    cs.warping = s.warping;
    cs.precision = s.precision;
    cs.rayleighMass = s.skinDampingMass;
    cs.rayleighStiffness = s.skinDampingStiffness;
    cs.channel = "skin channel " + ch.name;
    channelIntegrators_.emplace_back(ch.basis, cs);
    channelForce_.push_back(MatX3::Zero(ch.basis->freeCount(), 3));
  }
  channelLoaded_.assign(model_->channels().size(), false);
  activation_.assign(model_->muscles().size(), 0.0);
  dragForce_.assign(s.drags.size(), Vec3::Zero());
  dragVertex_.resize(s.drags.size());
  for (size_t d = 0; d < s.drags.size(); ++d) dragVertex_[d] = s.drags[d].vertex;
  for (const SkinChannel& ch : model_->channels()) dragRows_.push_back(ch.dragRows);
  skinU_ = MatX3::Zero(model_->head().mesh.vertexCount(), 3);
  // The runaway guard: a displacement larger than the head's bounding-box diagonal.
  const MatX3& V = model_->head().mesh.V;
  runawayLimit_ = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  setGravity(s.gravity ? 1.0 : 0.0);
}

void Simulator::setActivation(int muscle, double a) {
  MYO_CHECK(muscle >= 0 && muscle < static_cast<int>(activation_.size()), "muscle index " << muscle);
  if (std::isnan(a))
    throw InputError("activation of muscle '" + model_->muscles()[static_cast<size_t>(muscle)].muscle.def.name +
                     "' is NaN");
  if (a < -1.0 || a > 1.0) {
    ++clamped_;
    const double clamped = std::clamp(a, -1.0, 1.0);
    if (warnings_.size() < 64) {
      std::ostringstream w;
      w << "activation " << a << " of muscle '" << model_->muscles()[static_cast<size_t>(muscle)].muscle.def.name
        << "' clamped to " << clamped;
      warnings_.push_back(w.str());
    }
    a = clamped;
  }
  activation_[static_cast<size_t>(muscle)] = a;
}

void Simulator::setActivation(const std::string& muscle, double a) { setActivation(model_->muscleIndex(muscle), a); }

void Simulator::setGravity(double scale) {
  if (!std::isfinite(scale)) throw InputError("gravity scale is not finite");
  const int g = model_->gravityChannel();
  if (g < 0) {
    if (scale != 0.0) throw InputError("this face model was built without a gravity channel");
    gravity_ = 0.0;
    return;
  }
  gravity_ = scale;
  const ModalBasis& b = *model_->channels()[static_cast<size_t>(g)].basis;
  MatX3& F = channelForce_[static_cast<size_t>(g)];
  F.setZero();
  F.col(1) = -scale * model_->settings().gravityAcceleration * b.freeMass;  // f_i = m_i g (thesis Fig. 21–22)
  channelLoaded_[static_cast<size_t>(g)] = scale != 0.0;
}

void Simulator::setDragForce(int drag, const Vec3& force) {
  MYO_CHECK(drag >= 0 && drag < static_cast<int>(dragForce_.size()), "drag index " << drag);
  if (!force.allFinite()) throw InputError("drag force is not finite");
  dragForce_[static_cast<size_t>(drag)] = force;
  const auto& channels = model_->channels();
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c].kind != ChannelKind::Drag || channels[c].source != drag) continue;
    MatX3& F = channelForce_[c];
    F.setZero();
    const Vec3 share = force / static_cast<double>(dragRows_[c].size());
    for (int r : dragRows_[c]) F.row(r) = share.transpose();
    channelLoaded_[c] = force.squaredNorm() > 0.0;
  }
}

void Simulator::setDragVertex(int drag, int vertex, double radius) {
  MYO_CHECK(drag >= 0 && drag < static_cast<int>(dragForce_.size()), "drag index " << drag);
  const DragDef& def = model_->settings().drags[static_cast<size_t>(drag)];
  const MatX3& rest = model_->head().mesh.V;
  if (vertex < 0 || vertex >= rest.rows())
    throw InputError("drag '" + def.name + "': vertex " + std::to_string(vertex) + " is outside [0, " +
                     std::to_string(rest.rows()) + ")");
  if (!(radius > 0.0)) radius = def.radius;
  const auto& channels = model_->channels();
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c].kind != ChannelKind::Drag || channels[c].source != drag) continue;
    const ModalBasis& basis = *channels[c].basis;
    std::vector<int> rows;
    const Vec3 centre = rest.row(vertex);
    for (int r = 0; r < basis.freeCount(); ++r)
      if ((Vec3(rest.row(basis.freeVertices[static_cast<size_t>(r)])) - centre).norm() <= radius) rows.push_back(r);
    if (rows.empty())
      throw InputError("drag '" + def.name + "': no free skin vertex within " + std::to_string(radius) +
                       " cm of vertex " + std::to_string(vertex) + " (is it pinned?)");
    dragRows_[c] = std::move(rows);
  }
  dragVertex_[static_cast<size_t>(drag)] = vertex;
  setDragForce(drag, dragForce_[static_cast<size_t>(drag)]);  // re-spread the current force
}

void Simulator::setSkinStiffnessScale(double s) {
  if (!std::isfinite(s) || s <= 0.0)
    throw InputError("skin stiffness scale must be finite and > 0, got " + std::to_string(s));
  for (size_t c = 0; c < channelIntegrators_.size(); ++c) {
    try {
      channelIntegrators_[c].setStiffnessScale(s);
    } catch (...) {  // an unstable semi-implicit step: every channel keeps the previous scale
      for (size_t done = 0; done < c; ++done) channelIntegrators_[done].setStiffnessScale(skinStiffnessScale_);
      throw;
    }
  }
  skinStiffnessScale_ = s;
}

void Simulator::step() {
  Stopwatch total;
  const auto& muscles = model_->muscles();

  // 1. Muscles: the activation force along the centre line on the central nodes (eq. 13).
  Stopwatch phase;
  for (size_t m = 0; m < muscles.size(); ++m) {
    const MuscleUnit& unit = muscles[m];
    MatX3& F = muscleForce_[m];
    const double magnitude = activation_[m] * unit.maxForce;
    for (size_t c = 0; c < unit.centralFreeRows.size(); ++c)
      F.row(unit.centralFreeRows[c]) = magnitude * unit.muscle.contractDirection.row(static_cast<Eigen::Index>(c));
    ModalWarpingIntegrator& integrator = muscleIntegrators_[m];
    if (magnitude == 0.0 && integrator.isAtRest(1e-12)) continue;
    integrator.step(F);
  }
  timings_.muscles = phase.seconds();

  // 2. Springs: each muscle node's displacement pulls its skin node (eq. 14–16).
  phase.restart();
  for (size_t m = 0; m < muscles.size(); ++m) {
    const MuscleUnit& unit = muscles[m];
    const size_t c = static_cast<size_t>(unit.skinChannel);
    MatX3& F = channelForce_[c];
    for (const auto& s : unit.springs)
      if (s.skinFreeRow >= 0) F.row(s.skinFreeRow).setZero();
    const bool loaded = addSpringForces(unit, muscleIntegrators_[m].freeDisplacement(), model_->settings().springModel, F);
    channelLoaded_[c] = loaded;
  }
  timings_.springs = phase.seconds();

  // 3–4. Every skin channel on its own (eq. 22–24), then the sum of the fields (eq. 21, 25).
  phase.restart();
  skinU_.setZero();
  for (size_t c = 0; c < channelIntegrators_.size(); ++c) {
    ModalWarpingIntegrator& integrator = channelIntegrators_[c];
    // A channel is skipped only when it is unloaded and at rest: a relaxing channel keeps moving.
    if (!channelLoaded_[c] && integrator.isAtRest(1e-9)) continue;
    integrator.step(channelForce_[c]);
    integrator.addDisplacementTo(skinU_);
  }
  timings_.channels = phase.seconds();
  time_ += model_->settings().dt;
  ++steps_;
  checkHealth();
  timings_.total = total.seconds();
}

void Simulator::checkHealth() const {
  // One pass over the summed field: a NaN, an infinity or a displacement larger than the head
  // itself means a channel ran away. Only then is the culprit looked for.
  const double limit = runawayLimit_;
  const double worst = skinU_.cwiseAbs().maxCoeff();
  if (worst < limit && skinU_.allFinite()) return;  // (maxCoeff may skip NaNs: allFinite does not)
  std::string culprit = "the summed field";
  double culpritSize = worst;
  const auto& channels = model_->channels();
  for (size_t c = 0; c < channels.size(); ++c) {
    const MatX3& u = channelIntegrators_[c].freeDisplacement();
    const double size = u.allFinite() ? u.cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
    if (!(size < limit)) {
      culprit = "skin channel '" + channels[c].name + "'";
      culpritSize = size;
      break;
    }
  }
  std::ostringstream os;
  os << "the simulation blew up at step " << steps_ << " (t = " << time_ << " s): " << culprit << " reached a displacement of "
     << culpritSize << " cm, more than the head's size (" << limit << " cm). Likely causes: activations or drag forces too "
     << "strong for the springs' stiffness, a skin that bends too easily under modal warping (raise skin.k_b; "
        "docs/face_model.md), or a time step too large for the semi-implicit stepper.";
  throw NumericalError(os.str());
}

int Simulator::advance(double seconds) {
  const int steps = static_cast<int>(std::lround(seconds / model_->settings().dt));
  for (int i = 0; i < steps; ++i) step();
  return steps;
}

MatX3 Simulator::skinPositions() const { return model_->head().mesh.V + skinU_; }

void Simulator::skinPositions(MatX3& out) const { out.noalias() = model_->head().mesh.V + skinU_; }

MatX3 Simulator::skinLoad() const {
  MatX3 F = MatX3::Zero(skinU_.rows(), 3);
  const auto& channels = model_->channels();
  for (size_t c = 0; c < channels.size(); ++c) {
    const auto& fv = channels[c].basis->freeVertices;
    for (size_t i = 0; i < fv.size(); ++i) F.row(fv[i]) += channelForce_[c].row(static_cast<Eigen::Index>(i));
  }
  return F;
}

MatX3 Simulator::channelDisplacement(int channel) const {
  MatX3 u;
  channelDisplacement(channel, u);
  return u;
}

void Simulator::channelDisplacement(int channel, MatX3& out) const {
  out.setZero(skinU_.rows(), 3);
  channelIntegrators_.at(static_cast<size_t>(channel)).addDisplacementTo(out);
}

MatX3 Simulator::musclePositions(int muscle) const {
  MatX3 x;
  musclePositions(muscle, x);
  return x;
}

void Simulator::musclePositions(int muscle, MatX3& out) const {
  out = model_->muscles().at(static_cast<size_t>(muscle)).muscle.mesh.V;
  muscleIntegrators_[static_cast<size_t>(muscle)].addDisplacementTo(out);
}

double Simulator::muscleAmplitude(int muscle) const {
  return muscleIntegrators_.at(static_cast<size_t>(muscle)).q()(0);
}

void Simulator::reset() {
  for (auto& i : muscleIntegrators_) i.reset();
  for (auto& i : channelIntegrators_) i.reset();
  skinU_.setZero();
  time_ = 0.0;
  steps_ = 0;
}

}  // namespace myo

namespace myo {

void Simulator::setHeadPose(const Eigen::Quaterniond&) {
  throw InputError("the head pose (timeline.head_pose) needs \"model\": \"anatomical\"; the thesis model has no head pose");
}

void Simulator::setJaw(const JawPose& pose) {
  if (pose.isZero()) return;
  throw InputError("the jaw (timeline.jaw, pose --jaw) needs \"model\": \"anatomical\"; the thesis model has no jaw");
}

void Simulator::setGaze(const EyeGaze& gaze) {
  if (gaze.isZero()) return;
  throw InputError(
      "the eyes' turn (timeline.gaze) needs \"model\": \"anatomical\"; the thesis model has no eyes to turn");
}

}  // namespace myo
