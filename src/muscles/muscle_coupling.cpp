#include "myoshell/muscles/muscle_coupling.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <functional>

#include "myoshell/core/errors.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/muscles/tissue_attachment.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

namespace {
// How squarely the muscle must lie beneath a skin vertex to couple to it: −(direction to the
// muscle)·(skin normal) above this (about 73° from straight down).
constexpr double kBeneath = 0.3;

// The outer-canthus distance (cm) of the head the muscles' material was set on: the built-in head.
constexpr double kMuscleMaterialHeadScale = 8.8917179;

// The skin's closest point to a point (a SurfaceLocator's query, or the brute-force one).
using ClosestOnSkin = std::function<SurfacePoint(const Vec3&)>;

double smooth(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

}  // namespace

double CouplingProfile::modulus(double t) const {
  if (t <= originEnd) return 0.0;
  if (t < bellyStart) return bellyModulus * smooth((t - originEnd) / (bellyStart - originEnd));
  return bellyModulus + (insertionModulus - bellyModulus) * smooth((t - insertionStart) / (1.0 - insertionStart));
}

void CouplingProfile::validate(const std::string& owner) const {
  auto bad = [&](const std::string& what) { throw InputError(owner + ": " + what); };
  if (!(insertionModulus > 0) || !std::isfinite(insertionModulus)) bad("insertion_modulus must be > 0 dyn/cm²");
  if (!(bellyModulus >= 0) || !std::isfinite(bellyModulus)) bad("belly_modulus must be ≥ 0 dyn/cm²");
  if (!(originEnd >= 0 && originEnd < bellyStart && bellyStart <= insertionStart && insertionStart < 1.0))
    bad("profile positions must satisfy 0 ≤ origin_end < belly_start ≤ insertion_start < 1");
}

// The mean motion of the insertion ring towards the origin along `axis` (unit), cm.
double insertionShortening(const Muscle& mu, const MatX3& U, const Vec3& axis) {
  double along = 0.0;
  for (int v : mu.insertionNodes) along += U.row(v).dot(axis.transpose());
  return along / static_cast<double>(mu.insertionNodes.size());
}

// The muscle moved by U along its bed (docs/anatomical_model.md, "Muscles slide over their bed"):
// each node v hangs under its skin point c_v (the skin's closest point, normal n_v) at the offset
// r_v = p_v − c_v, whose part along the normal is h_v = r_v·n_v < 0. Its motion across the skin's
// tangent plane walks that point along the skin, in steps of at most a quarter of |r_v|, each step
// re-projected onto the skin and onto its tangent plane there, to c' (normal n'); the node follows
// at the same depth, q' = p_v + (c' − c_v) + h_v (n' − n_v), which is p_v when u_v = 0. Its motion
// into or out of the face is gone: a curved muscle follows the face's curve instead of straightening
// through the deep tissue under it. The short steps keep the walk on the skin beside c_v, never
// across a lip's seam or a fold.
// A node whose walk does not carry its skin point ¾ as far as its motion across the skin is not
// under the face's skin but beside a rim (near the mouth's corner its closest skin is the lip's
// inner side, which turns into the mouth, and the walk stalls there): it moves as its walked
// neighbours on the muscle's mesh do, by the mean of their slid motions ("A node beside the mouth's
// rim", docs/anatomical_model.md). Its own motion would not do: its skin normal is the lip's, so the
// bed's correction there sinks it into the face. Without this, stalled nodes of the insertion ring
// left the others to carry the ring's mean shortening: up to twice σ × length.
MatX3 slideOverBed(const Muscle& mu, const MatX3& U, const std::vector<SurfacePoint>& restFoot,
                   const ClosestOnSkin& onSkin) {
  constexpr double kStalled = 0.75;  // a walk whose chord is shorter than this fraction of the motion across the skin
  MatX3 slid = U;
  std::vector<char> walked(static_cast<size_t>(U.rows()), 1);
  for (Eigen::Index v = 0; v < U.rows(); ++v) {
    if (U.row(v).squaredNorm() == 0.0) continue;  // the pinned origin
    const SurfacePoint& c = restFoot[static_cast<size_t>(v)];
    const Vec3 u = U.row(v).transpose();
    const Vec3 offset = Vec3(mu.mesh.V.row(v)) - c.point;  // from the skin down to the node
    const double below = offset.dot(c.normal);                 // its part along the normal (< 0)
    const Vec3 along = u - u.dot(c.normal) * c.normal;
    const int steps = std::clamp(static_cast<int>(std::ceil(along.norm() / (0.25 * offset.norm()))), 1, 64);
    SurfacePoint foot = c;
    for (int k = 0; k < steps; ++k) {
      const Vec3 step = along / steps;
      foot = onSkin(foot.point + step - step.dot(foot.normal) * foot.normal);
    }
    slid.row(v) = ((foot.point - c.point) + below * (foot.normal - c.normal)).transpose();
    walked[static_cast<size_t>(v)] = (foot.point - c.point).norm() >= kStalled * along.norm();
  }
  if (std::all_of(walked.begin(), walked.end(), [](char w) { return w != 0; })) return slid;
  // Stalled nodes take the mean slid motion of their walked (or already filled) mesh neighbours,
  // ring after ring outwards; with none anywhere they keep their own motion.
  std::vector<std::vector<int>> neighbours(static_cast<size_t>(U.rows()));
  for (Eigen::Index f = 0; f < mu.mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mu.mesh.F(f, k), b = mu.mesh.F(f, (k + 1) % 3);
      neighbours[static_cast<size_t>(a)].push_back(b);
      neighbours[static_cast<size_t>(b)].push_back(a);
    }
  for (bool filled = true; filled;) {
    filled = false;
    std::vector<char> next = walked;
    for (Eigen::Index v = 0; v < U.rows(); ++v) {
      if (walked[static_cast<size_t>(v)]) continue;
      Vec3 motion = Vec3::Zero();
      int count = 0;
      for (int w : neighbours[static_cast<size_t>(v)])
        if (walked[static_cast<size_t>(w)] && U.row(w).squaredNorm() > 0.0) {
          motion += slid.row(w).transpose();
          ++count;
        }
      if (count == 0) continue;
      slid.row(v) = (motion / count).transpose();
      next[static_cast<size_t>(v)] = 1;
      filled = true;
    }
    walked = std::move(next);
  }
  for (Eigen::Index v = 0; v < U.rows(); ++v)
    if (!walked[static_cast<size_t>(v)]) slid.row(v) = U.row(v);
  return slid;
}

// A muscle bound to the dermis along its belly (`thickens`: the frontalis) bunches the skin out of
// the face as it shortens (docs/muscles.md, "The compressed forehead thickens"). The column from the
// skin down to the muscle's deep face, D thick, is squeezed along the fibres by the muscle's strain
// ε = σ and held across them by the sheet beside it (plane strain); keeping its volume it grows to
// D/(1 − ε), so every free node rises by D ε/(1 − ε) along the skin's outward normal at its foot.
// D at a node is the muscle's depth there (its anchors' depths, origin to insertion by t) plus half
// its thickness, in cm. The pinned origin (toFree < 0) stays.
MatX3 thickeningOverBelly(const Muscle& mu, double strain, const std::vector<SurfacePoint>& restFoot,
                          const std::vector<int>& toFree, double scaleCm) {
  const MuscleDef& def = mu.def;
  const Vec3 axis = (mu.originPoint - mu.insertionPoint).normalized();
  const double grow = strain / (1.0 - strain);
  MatX3 rise = MatX3::Zero(mu.mesh.vertexCount(), 3);
  for (Eigen::Index v = 0; v < rise.rows(); ++v) {
    if (toFree[static_cast<size_t>(v)] < 0) continue;
    const Vec3 p = mu.mesh.V.row(v);
    const double t = std::clamp((p - mu.originPoint).dot(-axis) / mu.restLength, 0.0, 1.0);
    const double column = ((1.0 - t) * def.origin.depth + t * def.insertion.depth + 0.5 * def.thickness) * scaleCm;
    rise.row(v) = (grow * column * restFoot[static_cast<size_t>(v)].normal).transpose();
  }
  return rise;
}

// The frontalis arises from the galea aponeurotica, not from bone, and the galea slides with the
// scalp's first three layers over the loose areolar layer (docs/muscles.md, "The galea slides:
// the forehead's line of convergence"). Shortening, the muscle draws the brow up and the galea
// down; measured on the skin at maximal contraction (Cotofana et al. 2020, Plast Reconstr Surg
// 145:1155, 27 volunteers), the two motions meet at a line 60.6 % (women; men 60.9 %) of the
// forehead's height above the brows: the line of convergence. A band contracting about that line
// moves its ends in the ratio of their distances from it: the galea's end down by 0.394/0.606 of
// the brow's rise.
constexpr double kConvergenceAboveBrow = 0.606;

// A linear muscle's shape at a = 1: the static response of the pinned muscle to its activation load
// (unit forces along the contraction direction on the central nodes): K_FF⁻¹P (METHOD.md §8's
// static-shape variant), scaled so that the insertion ring moves shortening × length along the
// muscle's chord. With `slideOverBed`, the nodes then walk along the skin at their rest depth
// (slideOverBed above), and the scale is found so that the slid insertion moves shortening × length
// along the fibres' direction at the insertion.
void linearShape(CoupledMuscle& cm, const DiscreteShell& shell, const MuscleCouplingSettings& settings,
                 const std::vector<SurfacePoint>& restFoot, const ClosestOnSkin& onSkin, double scaleCm) {
  const Muscle& mu = cm.muscle;
  const MuscleDef& def = mu.def;
  const int nm = mu.mesh.vertexCount();
  const std::vector<int> freeV = freeVerticesOf(nm, mu.originNodes, mu.mesh.F);
  std::vector<int> toFree(static_cast<size_t>(nm), -1);
  for (size_t k = 0; k < freeV.size(); ++k) toFree[static_cast<size_t>(freeV[k])] = static_cast<int>(k);
  const SparseMat Kff = restrictToFree(shell.stiffnessAtRest(), freeV, nm);
  VecX P = VecX::Zero(Kff.rows());
  for (size_t c = 0; c < mu.centralNodes.size(); ++c) {
    const int r = toFree[static_cast<size_t>(mu.centralNodes[c])];
    if (r >= 0) P.segment<3>(3 * r) += mu.contractDirection.row(static_cast<Eigen::Index>(c)).transpose();
  }
  Eigen::SimplicialLDLT<SparseMat> ldlt(Kff);
  if (ldlt.info() != Eigen::Success) throw NumericalError("muscle '" + def.name + "': stiffness is singular");
  const VecX x = ldlt.solve(P);
  MatX3 response = MatX3::Zero(nm, 3);
  for (int v = 0; v < nm; ++v) {
    const int r = toFree[static_cast<size_t>(v)];
    if (r >= 0) response.row(v) = x.segment<3>(3 * r).transpose();
  }
  // A thickening muscle's rise (above) is added to the shape; the fibres' shortening is σ × length
  // with it, so the contraction makes up what the rise carries along the fibres.
  const MatX3 rise = def.thickens ? thickeningOverBelly(mu, settings.shortening, restFoot, toFree, scaleCm)
                                  : MatX3::Zero(nm, 3);
  // The pinned tube shortens along its chord. On the bed the fibres follow the skin, so their
  // shortening is measured along their own direction at the insertion (the contraction direction of
  // the insertion ring's central nodes: the centre line's tangent there, which follows the skin);
  // fixed-point steps on the scale make it σ × length.
  Vec3 axis = (mu.originPoint - mu.insertionPoint).normalized();
  if (settings.slideOverBed) {
    Vec3 fibre = Vec3::Zero();
    for (size_t c = 0; c < mu.centralNodes.size(); ++c)
      if (std::find(mu.insertionNodes.begin(), mu.insertionNodes.end(), mu.centralNodes[c]) != mu.insertionNodes.end())
        fibre += mu.contractDirection.row(static_cast<Eigen::Index>(c)).transpose();
    if (fibre.norm() > 0.0) axis = fibre.normalized();
  }
  const double target = settings.shortening * mu.restLength - insertionShortening(mu, rise, axis);
  auto checkedScale = [&](double along) {
    if (!(along > 0.0) || !(target > 0.0))
      throw NumericalError("muscle '" + def.name + "': its activation load does not move the insertion towards the origin");
    return target / along;
  };
  double scale = checkedScale(insertionShortening(mu, response, axis));
  cm.fullShape = scale * response;
  if (settings.slideOverBed) {
    for (int it = 0; it < 30; ++it) {
      cm.fullShape = slideOverBed(mu, scale * response, restFoot, onSkin);
      const double along = insertionShortening(mu, cm.fullShape, axis);
      if (std::abs(along - target) <= 1e-9 * target) break;
      scale *= checkedScale(along);
    }
  }
  if (def.thickens) {
    // The galea slides (above): the whole tube shifted along the muscle by the galea's share of the
    // insertion's motion (the origin then moves −0.394 and the insertion 0.606 of it, the ends of a
    // contraction about the line), slid over the bed again, and scaled so that the insertion still moves
    // σ × length: the strength rule is the insertion's measured excursion (the brow's, 7.6–9.0 mm at
    // maximal contraction, Cruz & Cruz 2004), and the galea's descent comes on top of it.
    MatX3 shifted = scale * response;
    Vec3 lift = Vec3::Zero();  // the pinned tube's insertion: the ring's mean motion
    for (int v : mu.insertionNodes) lift += shifted.row(v).transpose();
    lift /= static_cast<double>(mu.insertionNodes.size());
    const Vec3 shift = (1.0 - kConvergenceAboveBrow) * lift;
    for (Eigen::Index v = 0; v < shifted.rows(); ++v) shifted.row(v) -= shift.transpose();
    double grow = 1.0;
    for (int it = 0; it < 30; ++it) {
      cm.fullShape = settings.slideOverBed ? slideOverBed(mu, grow * shifted, restFoot, onSkin) : MatX3(grow * shifted);
      const double along = insertionShortening(mu, cm.fullShape, axis);
      if (std::abs(along - target) <= 1e-9 * target) break;
      grow *= checkedScale(along);
    }
    cm.fullShape += rise;
  }
  {
    const VecX& mass = shell.lumpedMass();
    double mm2 = 0.0;
    for (size_t k = 0; k < freeV.size(); ++k) mm2 += mass(freeV[k]) * x.segment<3>(3 * static_cast<Eigen::Index>(k)).squaredNorm();
    cm.naturalFrequency = std::sqrt(x.dot(Kff * x) / mm2);
  }
}

// A ring muscle's shape at a = 1 (docs/muscles.md, "Ring muscles"): the fibres shorten by the
// ring's `shortening` σ, drawing every node towards the ring's centre c in the face's plane,
//   u_v = −σ P(p_v − c) + π σ |P(p_v − c)| ẑ,
// P the projection onto the face frame's x–y plane, ẑ its forward axis, π the ring's `protrusion`.
// A band of uniform fibres under uniform tension contracts uniformly about its centre: its length
// falls by σ. The forward term is the lip's incompressibility: tissue squeezed towards the mouth's
// centre bulges out of the face (π = 0 for the eye, whose ring slides over the bone). A ring
// `along_skin` (the eye's orbital part on the rim and cheek) turns each node's P(p_v − c) into the
// skin's tangent plane at the node's foot, keeping its length: it draws the skin along its bed
// instead of into it. A ring in a lip (`lip_body`) runs in a body that keeps its volume: its fibres
// pull along themselves, so the lip shortens by σ along the ring but is not squeezed across it, and
// its cross-section's area grows by 1/(1 − σ), alike in height and thickness (each by 1/√(1 − σ)).
// The teeth lie behind the lip and its forward motion is the protrusion term, so the growth shows
// in the lip's height: each node's vertical offset h from its station's axis (the lip's own axis)
// becomes h/√(1 − σ) instead of shrinking by σ with the ring,
//   u_v += (σ + 1/√(1 − σ) − 1) h ŷ   (docs/muscles.md, "The lip's body").
void ringShape(CoupledMuscle& cm, const DiscreteShell& shell, const FaceFrame& frame, const std::vector<SurfacePoint>& foot) {
  const Muscle& mu = cm.muscle;
  const MuscleDef::Ring& ring = mu.def.ring;
  const int nm = mu.mesh.vertexCount();
  const Vec3 x = frame.axes.col(0), y = frame.axes.col(1), z = frame.axes.col(2);
  cm.fullShape.resize(nm, 3);
  // Each station's axis point (the mean of its nodes): the lip's own axis where the ring is a lip.
  const int stations = nm / mu.def.ringNodes;
  std::vector<Vec3> axisPoint(static_cast<size_t>(stations), Vec3::Zero());
  for (int v = 0; v < nm; ++v) axisPoint[static_cast<size_t>(mu.stationOf(v))] += Vec3(mu.mesh.V.row(v)) / mu.def.ringNodes;
  const double swell = ring.shortening + 1.0 / std::sqrt(1.0 - ring.shortening) - 1.0;
  // The release's shape (CoupledMuscle::releaseShape): the same with the growth's tangent at rest,
  // d/dσ (1/√(1 − σ)) = ½, so the height grows by ½σ h where the ring draws it in by σ h.
  const double linearSwell = 1.5 * ring.shortening;
  if (ring.lipBody) cm.releaseShape.resize(nm, 3);
  for (int v = 0; v < nm; ++v) {
    if (ring.hoop) {
      // A band held at both ends and pressed round the dental arch by its own tension (a string
      // under a uniform load): its deflection towards the arch's centre of curvature h, in the
      // face's x–z plane, runs as 4ξ(1 − ξ) along it, nothing at the held ends,
      // σ of its distance at the middle. The lip it presses on the teeth keeps its volume: with
      // `lip_body` it grows in height by 1/√(1 − ε) about its axis, ε = σ·4ξ(1 − ξ) the local
      // squeeze (docs/muscles.md, "The marginal part rolls the lower lip in").
      const double xi = static_cast<double>(mu.stationOf(v)) / static_cast<double>(stations - 1);
      const double eps = ring.shortening * 4.0 * xi * (1.0 - xi);
      const Vec3 d = Vec3(mu.mesh.V.row(v)) - mu.hoopCentre;
      Vec3 u = -eps * (d.dot(x) * x + d.dot(z) * z);
      if (ring.lipBody) {
        const double h = (Vec3(mu.mesh.V.row(v)) - axisPoint[static_cast<size_t>(mu.stationOf(v))]).dot(y);
        cm.releaseShape.row(v) = (u + 0.5 * eps * h * y).transpose();
        u += (1.0 / std::sqrt(1.0 - eps) - 1.0) * h * y;
      }
      cm.fullShape.row(v) = u.transpose();
      continue;
    }
    const Vec3 d = Vec3(mu.mesh.V.row(v)) - mu.ringCentre;
    Vec3 inPlane = d.dot(x) * x + d.dot(y) * y;
    if (ring.alongSkin) {
      // Sliding over a curved bed (the orbital rim, the cheek), the fibres draw the skin along it:
      // the same length of motion, turned into the skin's tangent plane under the node.
      const Vec3 n = foot[static_cast<size_t>(v)].normal;
      const double length = inPlane.norm();
      inPlane -= inPlane.dot(n) * n;
      if (inPlane.norm() > 0.0) inPlane *= length / inPlane.norm();
    }
    Vec3 u = -ring.shortening * inPlane + ring.protrusion * ring.shortening * inPlane.norm() * z;
    if (ring.lipBody) {
      const double h = (Vec3(mu.mesh.V.row(v)) - axisPoint[static_cast<size_t>(mu.stationOf(v))]).dot(y);
      cm.releaseShape.row(v) = (u + linearSwell * h * y).transpose();
      u += swell * h * y;
    }
    cm.fullShape.row(v) = u.transpose();
  }
  // ω from the free band's Rayleigh quotient (the shape has no rigid part: it shrinks the band).
  VecX u(3 * nm);
  for (int v = 0; v < nm; ++v) u.segment<3>(3 * v) = cm.fullShape.row(v).transpose();
  const VecX& mass = shell.lumpedMass();
  double mm2 = 0.0;
  for (int v = 0; v < nm; ++v) mm2 += mass(v) * u.segment<3>(3 * v).squaredNorm();
  cm.naturalFrequency = std::sqrt(u.dot(shell.stiffnessAtRest() * u) / mm2);
}

// A muscle that `pushes` (the mentalis; docs/muscles.md, "The chin's pad pushes the lower lip"):
// the soft tissue it squeezes between its insertion and its origin keeps its volume, and the bone
// holds only the muscle's deep end, so the tissue flows on past the origin and carries the skin
// ahead of it — the lower lip, up to the pushed anchor — along with the insertion. Each skin vertex
// ahead of the origin along the fibres (0 ≤ (x − o)·â ≤ (p − o)·â, â from the insertion to the
// origin, p the pushed point), in front of the origin, facing out of the face or up (not the lip's
// inner face, which faces the teeth) and within the muscle's width of its axis across the face, is
// tied to the insertion ring's mean motion by the insertion's shear layer (modulus G_ins, the
// origin's depth δ as the pad's thickness under it), faded to nothing at that width as the
// footprint's springs are: k = G_ins A / δ (1 − s²)².
static void addPushSprings(CoupledMuscle& cm, const Head& head, const MatX3& skinNormals, const VecX& skinArea,
                    const CouplingProfile& profile) {
  const Muscle& mu = cm.muscle;
  const MuscleDef& def = mu.def;
  const FaceFrame frame = head.frame();
  const Vec3 across = frame.axes.col(0), out = frame.axes.col(2);
  const Vec3 ahead = (mu.originPoint - mu.insertionPoint).normalized();
  const double reach = (mu.pushPoint - mu.originPoint).dot(ahead);
  if (!(reach > 0.0))
    throw InputError("muscle '" + def.name + "': the pushed anchor '" + def.pushes->landmark +
                     "' does not lie ahead of the origin along the muscle on this head");
  const double halfWidth = def.width * frame.scale, pad = def.origin.depth * frame.scale;
  const MatX3& S = head.mesh.V;
  for (Eigen::Index i = 0; i < S.rows(); ++i) {
    const Vec3 d = Vec3(S.row(i)) - mu.originPoint;
    const double along = d.dot(ahead), s = std::abs(d.dot(across)) / halfWidth;
    if (along < 0.0 || along > reach || s >= 1.0 || d.dot(out) <= 0.0) continue;
    if (Vec3(skinNormals.row(i)).dot(out) < -kBeneath) continue;
    CoupledMuscle::Spring spring;
    spring.skin = static_cast<int>(i);
    spring.nodes = mu.insertionNodes;
    spring.weights.assign(mu.insertionNodes.size(), 1.0 / static_cast<double>(mu.insertionNodes.size()));
    spring.t = 1.0;
    spring.depth = pad;
    spring.stiffness = profile.insertionModulus * skinArea(i) / pad * (1.0 - s * s) * (1.0 - s * s);
    spring.along = ahead;
    cm.springs.push_back(spring);
  }
}

// A muscle that `continues_into` another (the medial frontalis into the procerus; docs/muscles.md,
// "The medial frontalis draws the nose's root"): the muscle in series runs from the insertion I to
// its fixed end C (the anchor, under the skin). Pulled at I and held at C, it stretches evenly, so
// its point at s along the segment (s = (x − I)·(C − I)/|C − I|², 0 at I, 1 at C) moves with the
// insertion ring's mean motion times (1 − s). Each skin vertex x over the segment (0 ≤ s ≤ 1, the
// segment beneath it as the footprint's springs require, facing out of the face or up) within the
// muscle's half-width w of it across the skin (q = the distance from the segment's point to x, its
// part along x's normal removed, over w) is tied to that motion by the insertion's shear layer,
// δ = the distance to the segment's point: k = G_ins A / δ (1 − q²)², as the footprint's springs.
static void addContinuationSprings(CoupledMuscle& cm, const Head& head, const MatX3& skinNormals, const VecX& skinArea,
                                   const CouplingProfile& profile) {
  const Muscle& mu = cm.muscle;
  const MuscleDef& def = mu.def;
  const FaceFrame frame = head.frame();
  const Vec3 out = frame.axes.col(2);
  const Vec3 d = mu.continuePoint - mu.insertionPoint;
  if (!(d.squaredNorm() > 1e-6 * frame.scale * frame.scale))
    throw InputError("muscle '" + def.name + "': the anchor it continues into, '" + def.continuesInto->landmark +
                     "', lies at its insertion on this head");
  const double halfWidth = 0.5 * def.width * frame.scale;
  const double floorDepth = 1e-3 * mu.restLength;
  const size_t ring = mu.insertionNodes.size();
  const MatX3& S = head.mesh.V;
  for (Eigen::Index i = 0; i < S.rows(); ++i) {
    const Vec3 x = S.row(i), n = skinNormals.row(i);
    const double s = (x - mu.insertionPoint).dot(d) / d.squaredNorm();
    if (s < 0.0 || s > 1.0) continue;
    const Vec3 r = x - (mu.insertionPoint + s * d);  // from the segment up to the skin
    const double q = (r - r.dot(n) * n).norm() / halfWidth;
    if (q >= 1.0 || n.dot(out) < -kBeneath) continue;
    if (r.dot(n) < kBeneath * r.norm()) continue;  // the segment must lie beneath the skin
    CoupledMuscle::Spring spring;
    spring.skin = static_cast<int>(i);
    spring.nodes = mu.insertionNodes;
    spring.weights.assign(ring, (1.0 - s) / static_cast<double>(ring));
    spring.t = 1.0 + s;
    spring.depth = r.norm();
    spring.stiffness = profile.insertionModulus * skinArea(i) / std::max(r.norm(), floorDepth) * (1.0 - q * q) * (1.0 - q * q);
    cm.springs.push_back(spring);
  }
}

CoupledMuscle coupleMuscle(const MuscleDef& def, const Head& head, const MuscleCouplingSettings& settings,
                           const SurfaceLocator* skin) {
  const CouplingProfile& profile = def.coupling ? *def.coupling : settings.profile;
  profile.validate(def.coupling ? "muscle '" + def.name + "': coupling" : "muscle coupling");
  settings.muscle.validate();
  if (!(settings.shortening > 0.0 && settings.shortening < 1.0))
    throw InputError("muscle '" + def.name + "': shortening must lie in (0, 1)");
  CoupledMuscle cm;
  cm.muscle = buildMuscle(def, head, TubeOrientation::MirrorRightSide, skin);
  const Muscle& mu = cm.muscle;
  const TriMesh& mm = mu.mesh;
  const int nm = mm.vertexCount();
  // The tube's material is the thesis face's, set on the built-in head: scaled with the head (k_L
  // with its size, k_B with its square; k_A's term already scales as the area), the tube's static
  // response keeps its form on a head of any size, and the strength rule sets its magnitude.
  ShellMaterial material = settings.muscle;
  const double size = head.frame().scale / kMuscleMaterialHeadScale;
  material.kL *= size;
  material.kB *= size * size;
  const DiscreteShell shell(mm.V, mm.F, buildEdgeTable(mm.F, nm), material);

  const MatX3& S = head.mesh.V;
  const MatX3i& F = head.mesh.F;
  const MatX3 skinNormals = skin ? skin->vertexNormals() : vertexNormals(S, F);
  const ClosestOnSkin onSkin = [&](const Vec3& p) { return skin ? skin->closest(p) : closestSurfacePoint(S, F, skinNormals, p); };
  const double L = mu.restLength;
  // Per muscle node: its place along the muscle (t) and its depth below the skin. A ring's fibres
  // insert into the skin all along it (the lips, the lids): t = 1, the insertion's modulus.
  const Vec3 axis = (mu.originPoint - mu.insertionPoint).normalized();
  VecX nodeT(nm), nodeDepth(nm);
  std::vector<SurfacePoint> foot(static_cast<size_t>(nm));  // each node's closest skin point
  for (int v = 0; v < nm; ++v) {
    const Vec3 p = mm.V.row(v);
    nodeT(v) = def.isRing() ? 1.0 : std::clamp((p - mu.originPoint).dot(-axis) / L, 0.0, 1.0);
    foot[static_cast<size_t>(v)] = onSkin(p);
    nodeDepth(v) = foot[static_cast<size_t>(v)].distance;
    if (!(nodeDepth(v) > 1e-9 * L))
      throw InputError("muscle '" + def.name + "': node " + std::to_string(v) + " lies on the skin (depth must be > 0)");
  }

  if (mu.def.isRing()) ringShape(cm, shell, head.frame(), foot);
  else linearShape(cm, shell, settings, foot, onSkin, head.frame().scale);

  // Springs from every skin vertex over the muscle to the muscle's surface point below it.
  const SurfaceLocator muscleSurface(mm.V, mm.F, vertexNormals(mm.V, mm.F));
  const VecX skinArea = lumpedVertexAreas(S, F);
  // Skin farther than `searchRadius` from `middle` cannot lie over the muscle: skip the search.
  const Vec3 middle = def.isRing() ? mu.ringCentre : 0.5 * (mu.originPoint + mu.insertionPoint);
  double searchRadius = L;
  if (def.isRing()) {
    searchRadius = 0.0;
    for (int v = 0; v < nm; ++v)
      searchRadius = std::max(searchRadius, (Vec3(mm.V.row(v)) - middle).norm() + settings.footprintReach * nodeDepth(v));
  }
  const double reachFactor = settings.footprintReach;
  for (Eigen::Index i = 0; i < S.rows(); ++i) {
    const Vec3 x = S.row(i);
    if ((x - middle).norm() > searchRadius) continue;
    const SurfacePoint below = muscleSurface.closest(x);
    const Eigen::Vector3i tri = mm.F.row(below.triangle).transpose();
    double t = 0.0, depth = 0.0;
    for (int k = 0; k < 3; ++k) {
      t += below.barycentric(k) * nodeT(tri(k));
      depth += below.barycentric(k) * nodeDepth(tri(k));
    }
    const double G = profile.modulus(t);
    if (G <= 0.0) continue;
    // The muscle must lie beneath this skin, not beside or in front of it (the other lip, the
    // inside of the mouth).
    const Vec3 down = (below.point - x) / std::max(below.distance, 1e-12 * L);
    if (down.dot(Vec3(skinNormals.row(i))) > -kBeneath) continue;
    const double reach = reachFactor * depth;
    if (below.distance >= reach) continue;
    const double s = below.distance / reach;
    CoupledMuscle::Spring spring;
    spring.skin = static_cast<int>(i);
    spring.nodes = {tri(0), tri(1), tri(2)};
    spring.weights = {below.barycentric(0), below.barycentric(1), below.barycentric(2)};
    spring.t = t;
    spring.depth = below.distance;
    // A shear layer of modulus G and thickness δ under the vertex's area, faded out towards the
    // footprint's edge so the coupling has no step.
    spring.stiffness = G * skinArea(i) / std::max(below.distance, 1e-3 * L) * (1.0 - s * s) * (1.0 - s * s);
    cm.springs.push_back(spring);
  }
  if (def.pushes) addPushSprings(cm, head, skinNormals, skinArea, profile);
  if (def.continuesInto) addContinuationSprings(cm, head, skinNormals, skinArea, profile);
  if (def.isRing() && def.ring.hoop) {
    // A hoop presses the lip onto the arch: its springs tie the skin along the pressing line only,
    // towards the arch's centre of curvature in the face's x–z plane (K = k r̂r̂ᵀ, as a push's along
    // its fibres). The lip's tissue is already tied to the mouth's ring that runs in it; the
    // marginal band adds its press, not a second shear layer (docs/muscles.md, "The marginal part
    // rolls the lower lip in": tied in full, the relaxed band held the lip and the corners in every
    // other shape, the funnel −0.025, the smile −0.022).
    const Vec3 ax = head.frame().axes.col(0), az = head.frame().axes.col(2);
    for (auto& spring : cm.springs) {
      const Vec3 d = Vec3(S.row(spring.skin)) - mu.hoopCentre;
      const Vec3 r = d.dot(ax) * ax + d.dot(az) * az;
      if (r.norm() > 0.0) spring.along = -r.normalized();
    }
  }
  return cm;
}

void addCouplingStiffness(const CoupledMuscle& m, std::vector<Triplet>& triplets) {
  for (const auto& s : m.springs) {
    if (s.along.isZero()) {
      for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * s.skin + c, 3 * s.skin + c, s.stiffness);
      continue;
    }
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) triplets.emplace_back(3 * s.skin + a, 3 * s.skin + b, s.stiffness * s.along(a) * s.along(b));
  }
}

Vec3 CoupledMuscle::Spring::muscleDisplacement(const MatX3& muscleU) const {
  Vec3 u = Vec3::Zero();
  for (size_t b = 0; b < nodes.size(); ++b) u += weights[b] * muscleU.row(nodes[b]).transpose();
  return u;
}

MatX3 couplingLoad(const CoupledMuscle& m, int skinVertexCount) {
  MatX3 f = MatX3::Zero(skinVertexCount, 3);
  for (const auto& s : m.springs) f.row(s.skin) += s.tie(s.muscleDisplacement(m.fullShape)).transpose();
  return f;
}

}  // namespace myo
