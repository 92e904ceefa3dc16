#include "myoshell/head/jaw.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "myoshell/core/check.h"
#include "myoshell/core/curves.h"
#include "myoshell/core/errors.h"
#include "myoshell/mesh/surface_paths.h"

namespace myo {

namespace {

constexpr double kDeg = M_PI / 180.0;

void requireJawLine(const Landmarks& landmarks) {
  if (landmarks.multipie68.size() != 68)
    throw InputError("the jaw needs the 68-point landmarks (jaw line 0–16, lips 48–67); " +
                     (landmarks.sourcePath.empty() ? std::string("these landmarks") : landmarks.sourcePath) +
                     " has none");
}

Vec3 point(const MatX3& V, const Landmarks& l, int multipie) {
  return V.row(l.multipie68[static_cast<size_t>(multipie)]).transpose();
}

// The pivot's angle (degrees) about the axis of a frame point q: atan2(Δy, Δz), 0 straight ahead
// (+z), negative below.
double angleAbout(const Vec3& pf, const Vec3& q) { return std::atan2(q.y() - pf.y(), q.z() - pf.z()) / kDeg; }

}  // namespace

void validateJawPose(const JawPose& p, const std::string& what) {
  auto check = [&](const char* name, double v, double lo, double hi, const char* unit) {
    if (std::isfinite(v) && v >= lo && v <= hi) return;
    std::ostringstream os;
    os << what << ": " << name << " " << v << " " << unit << " is " << (std::isfinite(v) ? "outside" : "not a number in")
       << " [" << lo << ", " << hi << "] " << unit;
    throw InputError(os.str());
  };
  check("open", p.openDeg, kJawOpenMinDeg, kJawOpenMaxDeg, "degrees");
  check("forward", p.forwardCm, kJawForwardMinCm, kJawForwardMaxCm, "cm");
  check("lateral", p.lateralCm, -kJawLateralMaxCm, kJawLateralMaxCm, "cm");
}

Vec3 jawPivot(const MatX3& V, const Landmarks& landmarks) {
  requireJawLine(landmarks);
  const FaceFrame frame = faceFrame(V, landmarks);
  const Vec3 ear = 0.5 * (frame.toFrame(point(V, landmarks, 0)) + frame.toFrame(point(V, landmarks, 16)));
  const Vec3 gonion = 0.5 * (frame.toFrame(point(V, landmarks, 4)) + frame.toFrame(point(V, landmarks, 12)));
  const Vec3 pf(0.0, 0.5 * (ear.y() + gonion.y()), ear.z() - kPivotDepthBehindEarContour);
  return frame.fromFrame(pf);
}

VecX jawWeights(const TriMesh& skin, const Landmarks& landmarks, const Vec3& pivot, const JawWeightSettings& s) {
  requireJawLine(landmarks);
  const MatX3& V = skin.V;
  const MatX3& P = skin.V;
  const FaceFrame frame = faceFrame(V, landmarks);
  auto fp = [&](int k) { return frame.toFrame(point(V, landmarks, k)); };
  const Vec3 pf = frame.toFrame(pivot);

  // The mouth line: outer corner 48, the inner lip pairs (61, 67), (62, 66), (63, 65), corner 54,
  // as angles about the axis over x.
  std::vector<std::pair<double, double>> split;
  split.emplace_back(fp(48).x(), angleAbout(pf, fp(48)));
  for (auto [up, lo] : {std::pair{61, 67}, std::pair{62, 66}, std::pair{63, 65}}) {
    const Vec3 m = 0.5 * (fp(up) + fp(lo));
    split.emplace_back(m.x(), angleAbout(pf, m));
  }
  split.emplace_back(fp(54).x(), angleAbout(pf, fp(54)));
  std::sort(split.begin(), split.end());
  // The lips part up to the inner corners (60, 64): there the commissure has fully blended.
  const double innerCornerX = 0.5 * (std::abs(fp(60).x()) + std::abs(fp(64).x()));
  const double blendFrom = std::max(0.0, innerCornerX - s.commissureBlend);

  // The mandible's lower border from gonion (4) to gonion (12): y over x, level beyond.
  std::vector<std::pair<double, double>> border;
  for (int k = 4; k <= 12; ++k) border.emplace_back(fp(k).x(), fp(k).y());
  std::sort(border.begin(), border.end());

  const Vec3 stomion = 0.5 * (fp(62) + fp(66));
  const std::vector<double> toUpper = surfaceDistances(skin, landmarks.multipie68[51]);
  const std::vector<double> toLower = surfaceDistances(skin, landmarks.multipie68[57]);

  const double h = s.cheekHalfWidthDeg;
  MYO_CHECK(h > 0 && s.posteriorFullDeg > s.posteriorZeroDeg && s.neckFalloff > 0, "jaw weight settings");
  VecX w(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Vec3 q = frame.toFrame(Vec3(P.row(i).transpose()));
    const double phi = angleAbout(pf, q);
    const double posterior = smoothStep((phi - s.posteriorZeroDeg) / (s.posteriorFullDeg - s.posteriorZeroDeg));
    const double neck = smoothStep((q.y() - (interpolateLinear(border, q.x()) - s.neckFalloff)) / s.neckFalloff);
    const double below = interpolateLinear(split, q.x()) - phi;  // degrees below the mouth line
    const double lambda = smoothStep((std::abs(q.x()) - blendFrom) / (innerCornerX - blendFrom));
    const bool lower = (q - stomion).norm() < s.lipRegion ? toLower[static_cast<size_t>(i)] < toUpper[static_cast<size_t>(i)]
                                                          : below > 0.0;
    const double wSplit = (1.0 - lambda) * (lower ? 1.0 : 0.0) + lambda * smoothStep(0.5 * (below / h + 1.0));
    w(i) = wSplit * neck * posterior;
  }
  return w;
}

JawRig jawRig(const TriMesh& skin, const Landmarks& landmarks, const JawWeightSettings& settings) {
  JawRig rig;
  rig.pivot = jawPivot(skin.V, landmarks);
  const FaceFrame frame = faceFrame(skin.V, landmarks);
  rig.axis = frame.axes.col(0);
  rig.forward = frame.axes.col(2);
  rig.weights = jawWeights(skin, landmarks, rig.pivot, settings);
  rig.pivotRule = "mid-ramus: halfway between the jaw-line points 0/16 and 4/12 in height, " +
                  std::to_string(kPivotDepthBehindEarContour) + " face-frame units behind 0/16";
  return rig;
}

RigidMotion jawMotion(const JawRig& rig, const JawPose& pose, double w) {
  RigidMotion m;
  m.R = Eigen::AngleAxisd(w * pose.openDeg * kDeg, rig.axis).toRotationMatrix();
  const Vec3 t = w * (pose.forwardCm * rig.forward + pose.lateralCm * rig.axis);
  m.d = rig.pivot - m.R * rig.pivot + t;
  return m;
}

void jawedPositions(const JawRig& rig, const JawPose& pose, const MatX3& rest, const MatX3& u, MatX3& out) {
  const Eigen::Index n = rest.rows();
  MYO_CHECK(u.rows() == n && rig.weights.size() == n,
            "jawedPositions: rest " << n << ", u " << u.rows() << ", weights " << rig.weights.size());
  out = rest + u;
  if (pose.isZero()) return;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = rig.weights(i);
    if (w == 0.0) continue;
    const RigidMotion m = jawMotion(rig, pose, w);
    out.row(i) = (m.apply(rest.row(i).transpose()) + m.R * u.row(i).transpose()).transpose();
  }
}

MatX3 jawedRest(const JawRig& rig, const JawPose& pose, const MatX3& rest) {
  MatX3 out;
  jawedPositions(rig, pose, rest, MatX3::Zero(rest.rows(), 3), out);
  return out;
}

bool isMandibleMuscle(const std::string& name) {
  for (const char* prefix : {"depressor_anguli_oris", "depressor_labii_inferioris", "mentalis", "platysma"})
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace myo
