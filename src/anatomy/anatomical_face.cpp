#include "myoshell/anatomy/anatomical_face.h"

#include <cmath>
#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo {

Eigen::Quaterniond headPoseRotation(const Vec3& pyr) {
  const double d = M_PI / 180.0;
  return Eigen::AngleAxisd(pyr.z() * d, Vec3::UnitZ()) * Eigen::AngleAxisd(pyr.y() * d, Vec3::UnitY()) *
         Eigen::AngleAxisd(pyr.x() * d, Vec3::UnitX());
}

Vec3 gravityForRotation(const FaceFrame& frame, const Eigen::Quaterniond& rotation, double gravity) {
  const Mat3 R = frame.axes * rotation.normalized().toRotationMatrix() * frame.axes.transpose();  // head space
  return -gravity * (R.transpose() * Vec3::UnitY());
}

AnatomicalFace::AnatomicalFace(const Head& head, const std::vector<MuscleDef>& muscles,
                               const AnatomicalSettings& settings, std::vector<DragDef> drags, bool gravity,
                               BasisCache* cache)
    : drags_(std::move(drags)), gravity_(gravity) {
  Stopwatch clock;
  std::vector<DragSite> sites;
  for (const DragDef& d : drags_) sites.push_back({d.vertex, d.radius});
  skin_ = std::make_shared<const AnatomicalSkin>(head, muscles, settings, sites, cache);
  placement_ = skin_->placementPtr();  // built with the skin (its contact patterns are in the basis)
  buildSeconds_ = clock.seconds();
}

const std::string& AnatomicalFace::muscleName(int m) const {
  return skin_->muscles()[static_cast<size_t>(m)].muscle.def.name;
}

const TriMesh& AnatomicalFace::muscleMesh(int m) const { return skin_->muscles()[static_cast<size_t>(m)].muscle.mesh; }

std::unique_ptr<FaceStepper> AnatomicalFace::makeStepper(std::shared_ptr<const FaceSystem> self) const {
  auto face = std::dynamic_pointer_cast<const AnatomicalFace>(self);
  MYO_CHECK(face.get() == this, "makeStepper: self must be this face");
  return std::make_unique<AnatomicalSimulator>(std::move(face));
}

AnatomicalSimulator::AnatomicalSimulator(std::shared_ptr<const AnatomicalFace> face) : face_(std::move(face)) {
  MYO_CHECK(face_ != nullptr, "an anatomical simulator needs a face");
  stepper_ = std::make_unique<AnatomicalStepper>(face_->skinPtr());
  loads_.activations = VecX::Zero(face_->muscleCount());
  loads_.drags.assign(face_->drags().size(), Vec3::Zero());
  for (const DragDef& d : face_->drags()) dragVertex_.push_back(d.vertex);
  loads_.contact = face_->skin().settings().contact;  // the penalty acts when the skin has one
  const MatX3& V = face_->head().mesh.V;
  runawayLimit_ = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  gravityScale_ = face_->gravityEnabled() ? 1.0 : 0.0;
  updateGravity();
}

void AnatomicalSimulator::setActivation(int muscle, double a) {
  MYO_CHECK(muscle >= 0 && muscle < face_->muscleCount(), "muscle index " << muscle);
  if (!(a >= 0.0 && a <= 1.0)) {
    std::ostringstream os;
    os << "muscle '" << face_->muscleName(muscle) << "': activation " << a
       << " is outside [0, 1] (model: anatomical; relaxing (a < 0) is model: thesis only)";
    throw InputError(os.str());
  }
  loads_.activations(muscle) = a;
}

void AnatomicalSimulator::setGravity(double scale) {
  if (!std::isfinite(scale)) throw InputError("gravity scale is not finite");
  if (!face_->gravityEnabled() && scale != 0.0)
    throw InputError("this face was built with gravity disabled (\"gravity\": {\"enabled\": false})");
  gravityScale_ = scale;
  updateGravity();
}

void AnatomicalSimulator::setHeadPose(const Eigen::Quaterniond& rotation) {
  if (!rotation.coeffs().allFinite() || !(rotation.norm() > 0)) throw InputError("head pose: not a rotation");
  pose_ = rotation.normalized();
  // Upright to round-off: keep gravity exactly g_rest (no spurious load from a rounded identity).
  posed_ = pose_.angularDistance(Eigen::Quaterniond::Identity()) > 1e-12;
  updateGravity();
}

void AnatomicalSimulator::setJaw(const JawPose& pose) {
  validateJawPose(pose);
  if (!pose.isZero() && !face_->jawRig())
    throw InputError("this head has no jaw: its landmarks have no 68-point jaw line (docs/jaw.md)",
                     face_->head().landmarks.sourcePath);
  jaw_ = pose;
  loads_.jaw = pose;
}

void AnatomicalSimulator::setGaze(const EyeGaze& gaze) {
  validateEyeGaze(gaze);
  loads_.gaze = gaze;
}

void AnatomicalSimulator::updateGravity() {
  const AnatomicalSkin& skin = face_->skin();
  if (!face_->gravityEnabled()) loads_.gravity = skin.restGravity();  // no change from rest: no load
  else if (!posed_) loads_.gravity = gravityScale_ * skin.restGravity();
  else loads_.gravity = gravityScale_ * gravityForRotation(face_->head().frame(), pose_, skin.settings().gravity);
}

void AnatomicalSimulator::setDragForce(int drag, const Vec3& force) {
  MYO_CHECK(drag >= 0 && drag < static_cast<int>(loads_.drags.size()), "drag index " << drag);
  if (!force.allFinite()) throw InputError("drag '" + face_->drags()[static_cast<size_t>(drag)].name + "': force is not finite");
  loads_.drags[static_cast<size_t>(drag)] = force;
}

void AnatomicalSimulator::setModalForce(const VecX& force) {
  const Eigen::Index d = stepper_->integrator().basis().modeCount();
  if (force.size() != 0 && force.size() != d)
    throw InputError("modal force: " + std::to_string(force.size()) + " values for a basis of " + std::to_string(d) + " modes");
  if (!force.allFinite()) throw InputError("modal force: a value is not finite");
  loads_.modalForce = force;
}

void AnatomicalSimulator::setDragVertex(int drag, int vertex, double radius) {
  MYO_CHECK(drag >= 0 && drag < static_cast<int>(loads_.drags.size()), "drag index " << drag);
  const DragDef& d = face_->drags()[static_cast<size_t>(drag)];
  const int n = face_->head().mesh.vertexCount();
  if (vertex < 0 || vertex >= n)
    throw InputError("drag '" + d.name + "': vertex " + std::to_string(vertex) + " is outside [0, " + std::to_string(n) +
                     ")");
  if (!(radius > 0.0)) radius = d.radius;
  grabSeconds_ = stepper_->grab(drag, vertex, radius);
  dragVertex_[static_cast<size_t>(drag)] = vertex;
}

void AnatomicalSimulator::setSkinStiffnessScale(double) {
  throw InputError("the skin stiffness scale is model: thesis only (the anatomical model has one skin, set by "
                   "skin.young_modulus)");
}

void AnatomicalSimulator::step() {
  Stopwatch clock;
  stepper_->step(loads_);
  ++steps_;
  const AnatomicalStepper::Times& t = stepper_->lastTimes();
  timings_.muscles = t.levels;
  timings_.springs = t.force;   // the one skin's force assembly (the thesis's step 2 slot)
  timings_.channels = t.modal;
  timings_.total = clock.seconds();
  // The bound needs no u = Φq (computed only when read): finite and below the limit, so is u.
  const double bound = stepper_->displacementBound();
  if (bound * (1.0 + 1e-12) < runawayLimit_ && std::isfinite(bound)) return;
  const MatX3& u = stepper_->displacement();
  const double worst = u.cwiseAbs().maxCoeff();
  if (worst < runawayLimit_ && u.allFinite()) return;
  std::ostringstream os;
  os << "the simulation blew up at step " << steps_ << ": the anatomical skin reached a displacement of " << worst
     << " cm, more than the head's size (" << runawayLimit_ << " cm). Likely causes: drag forces too strong for "
     << "the skin (skin.young_modulus) or a head in the wrong units.";
  throw NumericalError(os.str());
}

void AnatomicalSimulator::reset() {
  stepper_->reset();
  steps_ = 0;
}

void AnatomicalSimulator::skinPositions(MatX3& out) const {
  face_->placeSkin(stepper_->displacement(), jaw_, loads_.activations, out, loads_.gaze);
}

void AnatomicalSimulator::channelDisplacement(int channel, MatX3& out) const {
  MYO_CHECK(channel == 0, "the anatomical model has one channel, 'skin' (asked for " << channel << ")");
  out = stepper_->displacement();
}

void AnatomicalSimulator::musclePositions(int muscle, MatX3& out) const {
  const CoupledMuscle& m = face_->skin().muscles()[static_cast<size_t>(muscle)];
  out = m.muscle.mesh.V + stepper_->muscleLevels()(muscle) * m.fullShape;
  if (jaw_.isZero() || !isMandibleMuscle(m.muscle.def.name)) return;
  const RigidMotion j = jawMotion(*face_->jawRig(), jaw_, 1.0);
  for (Eigen::Index i = 0; i < out.rows(); ++i) out.row(i) = j.apply(out.row(i).transpose()).transpose();
}

}  // namespace myo
