// The page's bindings (docs/web.md): the anatomical face built in the browser from the same sources
// as the native library (web/web_face.h), with its muscles and released basis read from the face
// data the native build wrote (io/web_face_file.h), stepped through the one frame loop, ScenePlayer
// (an empty scene under the sliders, a take's scene while it plays, as `myoshell run` plays it),
// and settled by AnatomicalSkin::settle as `myoshell pose` settles it. The page draws positions()
// each frame.
#include <emscripten/bind.h>

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../web_face.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/fit/facs_route.h"
#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/timer.h"
#include "myoshell/io/web_face_file.h"

namespace myo::web {

class Page {
 public:
  // Builds the face from the face data's bytes; throws (the page shows the message) when the data
  // is not this face's.
  explicit Page(const std::string& data) {
    Stopwatch clock;
    WebFace w = readWebFace(data, "face.myoweb");
    WebFaceBasisCache cache(w.basisKey, std::move(w.basis));
    face_ = buildWebFace(w.muscles, &cache);
    if (face_->skin().settings().warping) throw InputError("the page steps linear modes: warping must be off");
    takes_ = std::move(w.takes);
    facs_ = std::move(w.facs);
    player_ = std::make_unique<ScenePlayer>(SceneDesc{}, face_);
    sim_ = &dynamic_cast<AnatomicalSimulator&>(player_->simulator());
    activations_ = VecX::Zero(face_->muscleCount());
    buildSeconds_ = clock.seconds();
    const TriMesh& mesh = face_->head().mesh;
    triangles_.resize(static_cast<size_t>(mesh.F.size()));
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
      for (int k = 0; k < 3; ++k) triangles_[static_cast<size_t>(3 * t + k)] = static_cast<uint32_t>(mesh.F(t, k));
    positions_.resize(static_cast<size_t>(3 * mesh.vertexCount()));
    shape_ = mesh.V;
    copyShape();
  }

  double buildSeconds() const { return buildSeconds_; }
  int vertexCount() const { return face_->head().mesh.vertexCount(); }
  int triangleCount() const { return static_cast<int>(face_->head().mesh.F.rows()); }
  int modeCount() const { return face_->skin().basis()->modeCount(); }
  double dt() const { return face_->dt(); }
  std::vector<std::string> muscleNames() const { return face_->skin().muscleNames(); }

  // Any load set by hand stops a take where it is.
  void setActivation(const std::string& name, double a) {
    stopPlaying();
    const int m = face_->muscleIndex(name);
    if (!(a >= 0.0 && a <= 1.0)) sim_->setActivation(m, a);  // the library's message
    activations_(m) = a;
    applyDrives();
  }
  // The activation the face has: the muscle's slider plus what the action units drive, clamped.
  double activation(const std::string& name) const { return sim_->activation(face_->muscleIndex(name)); }

  // The action units the page offers: those of the FACS map that drive a muscle, the jaw or the
  // eyes (AU34's air in the mouth is not a load the simulator takes; AUs that `need` something drive
  // nothing), as "AU: name".
  std::vector<std::string> actionUnits() const {
    std::vector<std::string> out;
    for (const FacsEntry& e : facs_.entries)
      if (!e.muscles.empty() || e.movesJaw() || e.turnsEyes()) out.push_back(std::to_string(e.au) + ": " + e.name);
    return out;
  }
  // An action unit's intensity in [0, 1]. Each AU goes to muscles, the jaw and the eyes through
  // facsDriveOfAu (fit/facs_route.h), the path `myoshell drive` takes from an OpenFace curve; the
  // drives add to the muscle sliders and the jaw slider and are clamped to the muscles' [0, 1], the
  // jaw's and the eyes' ranges as drive clamps them (anim/performance_map.cpp).
  void setActionUnit(int au, double x) {
    if (!(x >= 0.0 && x <= 1.0)) throw InputError("AU" + std::to_string(au) + ": intensity outside [0, 1]");
    if (!facsDriveOfAu(facs_, au, "")) throw InputError("AU" + std::to_string(au) + " drives nothing in the FACS map");
    stopPlaying();
    if (x == 0.0) aus_.erase(au);
    else aus_[au] = x;
    applyDrives();
  }
  double actionUnit(int au) const { return aus_.count(au) ? aus_.at(au) : 0.0; }
  // Gravity as `myoshell pose --gravity on|off` reads it: the rest shape already hangs under upright
  // gravity, so only its turn with the head loads the skin (reading (b)); off, gravity stays the rest
  // gravity whatever the head's tilt (no load at all). Not weightlessness (a gravity scale of 0).
  void setGravity(bool on) {
    gravityOn_ = on;
    updateGravity();
  }
  // The head's pitch (degrees about the face frame's x; + nods forward, 90 face-down): it turns
  // gravity (headPoseRotation); the head is drawn upright.
  void setHeadPitch(double degrees) {
    pitch_ = degrees;
    updateGravity();
  }
  void setJaw(double openDeg) {
    stopPlaying();
    jawOpen_ = openDeg;
    applyDrives();
  }

  // Steps `count` times (while not held on a settled shape), then places the skin; returns the
  // stepping's wall time (s). While a take plays, it plays on instead, to its clock time
  // min(playTime, duration) (ScenePlayer::playTo: the steps `myoshell run` takes, however the page's
  // frames cut them), and then holds its last frame until a load changes.
  double step(int count, double playTime) {
    if (settled_ && !playing_) return 0.0;
    Stopwatch clock;
    if (playing_) {
      const double end = player_->scene().duration;
      player_->playTo(std::min(playTime, end));
      if (player_->time() >= end - 0.5 * face_->dt()) {
        stopPlaying();
        settled_ = true;  // the take's last frame is held, as a settled shape is, until a load changes
      }
    } else {
      for (int i = 0; i < count; ++i) player_->step();
    }
    const double s = clock.seconds();
    if (placeOnCpu_) {
      sim_->skinPositions(shape_);
      copyShape();
    }
    return s;
  }

  std::vector<std::string> takeNames() const {
    std::vector<std::string> names;
    for (const SceneDesc& t : takes_) names.push_back(t.name);
    return names;
  }
  // Starts take `name` from the neutral face at rest, every load as a scene starts it (a fresh
  // stepper: the sliders' activations, the jaw and the head's pitch are dropped), clock at 0.
  double play(const std::string& name) {
    const auto it = std::find_if(takes_.begin(), takes_.end(), [&](const SceneDesc& t) { return t.name == name; });
    if (it == takes_.end()) throw InputError("no take '" + name + "' in the face data");
    player_ = std::make_unique<ScenePlayer>(*it, face_);
    sim_ = &dynamic_cast<AnatomicalSimulator&>(player_->simulator());
    activations_.setZero();
    aus_.clear();
    jawOpen_ = 0.0;
    pitch_ = 0.0;
    grabbed_ = -1;
    gravityOn_ = true;
    playing_ = true;
    settled_ = false;
    takeDuration_ = it->duration;
    return it->duration;
  }
  // Stops the take where it is; the sliders take the face from there.
  void stopPlaying() {
    if (!playing_) return;
    playing_ = false;
    for (int m = 0; m < face_->muscleCount(); ++m) activations_(m) = sim_->activation(m);
    jawOpen_ = sim_->jaw().openDeg;
    aus_.clear();
    player_->setScene(SceneDesc{});  // the clock and the stepper's state kept
  }
  bool playing() const { return playing_; }
  double jawOpen() const { return sim_->jaw().openDeg; }
  double time() const { return player_->time(); }
  double duration() const { return takeDuration_; }  // the take playing or last played (0 before any)

  // The static shape under the current loads, as `myoshell pose` computes it (AnatomicalSkin::settle
  // with the simulator's loads, linear modes, the contact penalty as the skin's settings say; placed
  // by the face's SkinPlacement). Held until a load changes. Returns the wall time (s).
  double settle() {
    stopPlaying();
    Stopwatch clock;
    const AnatomicalSkin& skin = face_->skin();
    SkinLoads loads = sim_->loads();
    const SettledSkin s = skin.settle(loads, /*warped=*/false);
    if (!s.converged || !s.u.allFinite()) throw NumericalError("settle: the static solve did not converge");
    face_->placeSkin(s.u, sim_->jaw(), loads.activations, shape_, loads.gaze);
    copyShape();
    settled_ = true;
    return clock.seconds();
  }
  bool settled() const { return settled_; }

  // The mouse grab (docs/web.md, "Mouse drag"): a force f spread over a grip around vertex i,
  // projected on the basis the face steps in (SkinLoads::modalForce = Gᵀf), sized so that the
  // reduced static response moves the grip by δ (the mouse's motion since the grab): the grip's
  // reduced compliance C = G Λ⁻¹ Gᵀ (3×3, cm/dyn; G its weighted rows of Φ) gives f = C⁻¹δ. No
  // factorisation and no data beyond Φ: a grab is a read of the grip's rows and a 3×3 inverse. The response is the basis's (its
  // low modes and static responses), smoother than a point load's K⁻¹f, which the native viewer's
  // grab adds to the basis (AnatomicalStepper::grab: K̂'s factorisation and the held basis).
  // Returns the grab's wall time (s), or −1 for a vertex the basis holds fixed.
  double grab(int vertex) {
    Stopwatch clock;
    if (vertex < 0 || vertex >= vertexCount()) throw InputError("grab: vertex " + std::to_string(vertex) + " is outside the head");
    const ModalBasis& B = *face_->skin().basis();
    if (freeRow_.empty()) {  // full vertex → its first row of Φ, or −1 where the basis holds it fixed
      freeRow_.assign(static_cast<size_t>(vertexCount()), -1);
      for (size_t k = 0; k < B.freeVertices.size(); ++k) freeRow_[static_cast<size_t>(B.freeVertices[k])] = static_cast<int>(3 * k);
    }
    if (freeRow_[static_cast<size_t>(vertex)] < 0) return -1.0;
    stopPlaying();
    // The grip: the free vertices within kGripRadiusCm of the grabbed one at rest, weighted
    // (1 − (r/R)²)², Σw = 1; its rows G = Σ w_j Φ_j (3×d). A force f spread as w_j f loads the modes by
    // Gᵀf, and moves the grip's weighted mean by C f, C = G Λ⁻¹ Gᵀ.
    const MatX3& V = face_->head().mesh.V;
    grabRows_ = MatX::Zero(3, B.modeCount());
    double total = 0.0;
    for (Eigen::Index j = 0; j < V.rows(); ++j) {
      const int row = freeRow_[static_cast<size_t>(j)];
      const double r2 = (V.row(j) - V.row(vertex)).squaredNorm() / (kGripRadiusCm * kGripRadiusCm);
      if (row < 0 || r2 >= 1.0) continue;
      const double w = (1.0 - r2) * (1.0 - r2);
      grabRows_ += w * B.Phi.middleRows(row, 3);
      total += w;
    }
    grabRows_ /= total;
    const Eigen::Matrix3d C = grabRows_ * B.lambda.cwiseInverse().asDiagonal() * grabRows_.transpose();
    grabInverse_ = C.inverse();
    grabbed_ = vertex;
    return clock.seconds();
  }
  // Moves the grip's target by δ (cm, head space; |δ| capped at 2 cm): f = C⁻¹δ.
  // Returns |f| (dyn).
  double moveGrab(double dx, double dy, double dz) {
    if (grabbed_ < 0) return 0.0;
    Vec3 d(dx, dy, dz);
    if (!d.allFinite()) throw InputError("grab: the motion is not finite");
    if (d.norm() > kGrabReachCm) d *= kGrabReachCm / d.norm();
    const Vec3 f = grabInverse_ * d;
    sim_->setModalForce(grabRows_.transpose() * f);
    settled_ = false;
    return f.norm();
  }
  void release() {
    if (grabbed_ < 0) return;
    grabbed_ = -1;
    sim_->setModalForce(VecX());
    settled_ = false;
  }
  int grabbed() const { return grabbed_; }

  // The modes as morph targets (docs/web.md, "GPU morph targets"): Φ for every vertex (zero rows
  // where the basis holds a vertex fixed), float32, texel (i·d + j) = (Φx, Φy, Φz) of vertex i,
  // mode j: the address of n·d·3 floats, made on the first call.
  uintptr_t morphTargetsAddress() {
    if (morph_.empty()) {
      const ModalBasis& B = *face_->skin().basis();
      const size_t d = static_cast<size_t>(B.modeCount());
      morph_.assign(static_cast<size_t>(vertexCount()) * d * 3, 0.0f);
      for (size_t k = 0; k < B.freeVertices.size(); ++k)
        for (size_t j = 0; j < d; ++j)
          for (size_t c = 0; c < 3; ++c)
            morph_[(static_cast<size_t>(B.freeVertices[k]) * d + j) * 3 + c] =
                static_cast<float>(B.Phi(static_cast<Eigen::Index>(3 * k + c), static_cast<Eigen::Index>(j)));
    }
    return reinterpret_cast<uintptr_t>(morph_.data());
  }
  // The modal coordinates q the skin stands at (d, float32; the GPU's weights: u = Φq), and the
  // address of that copy. Stepping with `place` false skips the CPU's u = Φq and the placement.
  uintptr_t modalCoordinatesAddress() {
    const VecX& q = sim_->stepper().integrator().q();
    qFloat_.resize(static_cast<size_t>(q.size()));
    for (Eigen::Index j = 0; j < q.size(); ++j) qFloat_[static_cast<size_t>(j)] = static_cast<float>(q(j));
    return reinterpret_cast<uintptr_t>(qFloat_.data());
  }
  void setPlaceOnCpu(bool on) { placeOnCpu_ = on; }

  // The face frame (head/face_frame.h): origin, then the axes' columns x (subject's left), y (up),
  // z (out of the face), 12 numbers: the native renderer's front view looks along −z.
  std::vector<double> frame() const {
    const FaceFrame f = face_->head().frame();
    std::vector<double> out(f.origin.data(), f.origin.data() + 3);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) out.push_back(f.axes(r, c));
    return out;
  }

  // Vertex i's position (cm, the head's order) in the shape last placed.
  std::vector<double> vertex(int i) const {
    if (i < 0 || i >= vertexCount()) throw InputError("vertex " + std::to_string(i) + " is outside the head");
    return {shape_(i, 0), shape_(i, 1), shape_(i, 2)};
  }
  std::vector<double> restVertex(int i) const {
    const MatX3& V = face_->head().mesh.V;
    if (i < 0 || i >= vertexCount()) throw InputError("vertex " + std::to_string(i) + " is outside the head");
    return {V(i, 0), V(i, 1), V(i, 2)};
  }
  // Addresses in the module's memory, for WebGL uploads without copies: float32 n×3 positions (cm)
  // and uint32 triangle indices.
  uintptr_t positionsAddress() const { return reinterpret_cast<uintptr_t>(positions_.data()); }
  uintptr_t trianglesAddress() const { return reinterpret_cast<uintptr_t>(triangles_.data()); }
  double stepCount() const { return static_cast<double>(sim_->stepCount()); }
  // The vertex of a landmark by name ("mouth_corner_left", …; head/landmarks.h).
  int landmarkVertex(const std::string& name) const { return face_->head().landmarks.vertex(name); }

 private:
  void copyShape() {
    for (Eigen::Index i = 0; i < shape_.rows(); ++i)
      for (int c = 0; c < 3; ++c) positions_[static_cast<size_t>(3 * i + c)] = static_cast<float>(shape_(i, c));
  }
  // The sliders' loads on the simulator: activations = the muscle sliders + Σ AU intensity · weight,
  // the jaw = its slider + Σ AU intensity · the AU's jaw, the eyes Σ AU intensity · turn, each
  // clamped to its range.
  void applyDrives() {
    VecX a = activations_;
    Vec3 jaw(jawOpen_, 0.0, 0.0);
    EyeGaze gaze;
    for (const auto& [au, x] : aus_) {
      const std::optional<FacsDrive> d = facsDriveOfAu(facs_, au, "");
      for (const auto& [muscle, w] : d->muscles) a(face_->muscleIndex(muscle)) += x * w;
      jaw += x * d->jaw;
      for (size_t e = 0; e < 2; ++e) {
        gaze.pitchDeg[e] += x * d->gaze[e].x();
        gaze.yawDeg[e] += x * d->gaze[e].y();
      }
    }
    for (Eigen::Index m = 0; m < a.size(); ++m) sim_->setActivation(static_cast<int>(m), std::clamp(a(m), 0.0, 1.0));
    JawPose j;
    j.openDeg = std::clamp(jaw.x(), kJawOpenMinDeg, kJawOpenMaxDeg);
    j.forwardCm = std::clamp(jaw.y(), kJawForwardMinCm, kJawForwardMaxCm);
    j.lateralCm = std::clamp(jaw.z(), -kJawLateralMaxCm, kJawLateralMaxCm);
    sim_->setJaw(j);
    for (size_t e = 0; e < 2; ++e) {
      gaze.pitchDeg[e] = std::clamp(gaze.pitchDeg[e], -kGazeMaxDeg, kGazeMaxDeg);
      gaze.yawDeg[e] = std::clamp(gaze.yawDeg[e], -kGazeMaxDeg, kGazeMaxDeg);
    }
    sim_->setGaze(gaze);
    settled_ = false;
  }
  void updateGravity() {
    stopPlaying();
    sim_->setGravity(1.0);
    sim_->setHeadPose(gravityOn_ ? headPoseRotation(Vec3(pitch_, 0.0, 0.0)) : Eigen::Quaterniond::Identity());
    settled_ = false;
  }
  std::shared_ptr<const AnatomicalFace> face_;
  std::vector<SceneDesc> takes_;
  std::vector<float> morph_;     // n·d·3: the modes as morph targets (morphTargetsAddress)
  std::vector<float> qFloat_;    // d: q for the GPU
  bool placeOnCpu_ = true;       // false: the GPU reconstructs rest + Φq (no placement)
  double takeDuration_ = 0.0;    // s: the take playing or last played
  FacsMap facs_;
  std::map<int, double> aus_;  // AU → intensity (> 0)
  double jawOpen_ = 0.0;       // the jaw slider (degrees)
  static constexpr double kGrabReachCm = 2.0;
  static constexpr double kGripRadiusCm = 1.0;  // the grip's radius at rest (a scene drag's default)
  std::vector<int> freeRow_;     // per vertex: its first row of Φ, −1 where held fixed
  int grabbed_ = -1;             // the grabbed vertex, or −1
  MatX grabRows_;                // 3×d: its rows of Φ
  Eigen::Matrix3d grabInverse_;  // Cᵢ⁻¹, dyn/cm
  std::unique_ptr<ScenePlayer> player_;
  AnatomicalSimulator* sim_ = nullptr;  // player_'s
  bool playing_ = false;
  VecX activations_;
  MatX3 shape_;
  std::vector<float> positions_;
  std::vector<uint32_t> triangles_;
  double buildSeconds_ = 0.0;
  bool settled_ = false;
  bool gravityOn_ = true;
  double pitch_ = 0.0;
};

// The message of the exception at `address` (a C++ exception caught in JavaScript is a number).
std::string exceptionMessage(uintptr_t address) {
  return reinterpret_cast<const std::exception*>(address)->what();
}

}  // namespace myo::web

EMSCRIPTEN_BINDINGS(myoshell) {
  using namespace emscripten;
  using myo::web::Page;
  register_vector<std::string>("StringList");
  register_vector<double>("DoubleList");
  class_<Page>("Page")
      .constructor<const std::string&>()
      .function("buildSeconds", &Page::buildSeconds)
      .function("vertexCount", &Page::vertexCount)
      .function("triangleCount", &Page::triangleCount)
      .function("modeCount", &Page::modeCount)
      .function("dt", &Page::dt)
      .function("muscleNames", &Page::muscleNames)
      .function("setActivation", &Page::setActivation)
      .function("activation", &Page::activation)
      .function("actionUnits", &Page::actionUnits)
      .function("setActionUnit", &Page::setActionUnit)
      .function("actionUnit", &Page::actionUnit)
      .function("setGravity", &Page::setGravity)
      .function("setJaw", &Page::setJaw)
      .function("setHeadPitch", &Page::setHeadPitch)
      .function("step", &Page::step)
      .function("settle", &Page::settle)
      .function("settled", &Page::settled)
      .function("vertex", &Page::vertex)
      .function("restVertex", &Page::restVertex)
      .function("positionsAddress", &Page::positionsAddress)
      .function("trianglesAddress", &Page::trianglesAddress)
      .function("stepCount", &Page::stepCount)
      .function("frame", &Page::frame)
      .function("morphTargetsAddress", &Page::morphTargetsAddress)
      .function("modalCoordinatesAddress", &Page::modalCoordinatesAddress)
      .function("setPlaceOnCpu", &Page::setPlaceOnCpu)
      .function("grab", &Page::grab)
      .function("moveGrab", &Page::moveGrab)
      .function("release", &Page::release)
      .function("grabbed", &Page::grabbed)
      .function("takeNames", &Page::takeNames)
      .function("play", &Page::play)
      .function("stopPlaying", &Page::stopPlaying)
      .function("playing", &Page::playing)
      .function("jawOpen", &Page::jawOpen)
      .function("time", &Page::time)
      .function("duration", &Page::duration)
      .function("landmarkVertex", &Page::landmarkVertex);
  function("exceptionMessage", &myo::web::exceptionMessage);
}
