#include "myoshell/muscles/tissue_attachment.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "myoshell/core/errors.h"
#include "myoshell/core/portable_math.h"
#include "myoshell/mesh/geometry.h"

namespace myo {

namespace {

// 0 below 0, 1 above 1, 3s² − 2s³ between (C¹: the maps have no kinks).
double smooth(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}
// 1 inside radius r, falling smoothly to 0 at r + width.
double bump(double distance, double r, double width) { return 1.0 - smooth((distance - r) / width); }

// Distance from p to the segment [a, b] in the (x, y) plane of the face frame.
double segmentDistance2d(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

}  // namespace

VecX lumpedVertexAreas(const MatX3& V, const MatX3i& F) {
  VecX A = VecX::Zero(V.rows());
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const double a = triangleArea(V.row(F(t, 0)), V.row(F(t, 1)), V.row(F(t, 2))) / 3.0;
    for (int k = 0; k < 3; ++k) A(F(t, k)) += a;
  }
  return A;
}

VecX TissueMap::vertexMass() const { return density * thickness.cwiseProduct(area); }

SparseMat TissueMap::stiffness() const {
  const int n = size();
  SparseMat K(3 * n, 3 * n);
  K.reserve(Eigen::VectorXi::Constant(3 * n, 1));
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) K.insert(3 * i + c, 3 * i + c) = attachment(i) * area(i);
  K.makeCompressed();
  return K;
}

TissueMap tissueMap(const Head& head, const AttachmentSettings& s) {
  if (!(s.fatShearModulus > 0) || !(s.heldStiffness > 0) || !(s.thinTissue > 0) || !(s.cheekTissue > 0) ||
      !(s.lipChinTissue > 0) || !(s.tissueDensity > 0))
    throw InputError("tissue attachment: moduli, stiffnesses, thicknesses and density must be > 0");
  if (!(s.foreheadColumnStiffness >= 0) || !std::isfinite(s.foreheadColumnStiffness))
    throw InputError("tissue attachment: the forehead column's stiffness must be ≥ 0");
  const FaceFrame frame = head.frame();
  const Landmarks& lm = head.landmarks;
  const MatX3& V = head.mesh.V;
  auto at = [&](const char* name) { return frame.toFrame(Vec3(V.row(lm.vertex(name)))); };
  // Landmarks in the face frame (ICT values in brackets, docs/anatomical_model.md).
  const Vec3 eyeR = at("right_eye_outer"), eyeL = at("left_eye_outer");            // (∓0.50, 0, 0)
  const Vec3 innerR = at("right_eye_inner"), innerL = at("left_eye_inner");        // (∓0.21, −0.03)
  const Vec3 nasion = at("nasion_approx"), tip = at("nose_tip");                   // y −0.01, −0.42
  const Vec3 cornerR = at("mouth_corner_right"), cornerL = at("mouth_corner_left");// (∓0.28, −0.80)
  const Vec3 menton = at("chin_menton");                                           // y −1.25
  const double browY = 0.25 * (at("right_brow_inner").y() + at("left_brow_inner").y() +
                               at("right_brow_outer").y() + at("left_brow_outer").y());  // 0.22
  const double lipTopY = at("upper_lip_top").y();
  const Vec3 browInR = at("right_brow_inner"), browInL = at("left_brow_inner");
  const Vec3 browOutR = at("right_brow_outer"), browOutL = at("left_brow_outer");

  const int n = static_cast<int>(V.rows());
  TissueMap map;
  map.density = s.tissueDensity;
  map.area = lumpedVertexAreas(V, head.mesh.F);
  map.attachment.resize(n);
  map.thickness.resize(n);
  map.held.resize(n);
  map.forehead.resize(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 q = frame.toFrame(Vec3(V.row(i)));
    const Vec2 p(q.x(), q.y());
    const double side = q.x() >= 0 ? 1.0 : -1.0;  // mirror: evaluate the subject's left regions at |x|
    const Vec3& eye = side > 0 ? eyeL : eyeR;
    const Vec3& inner = side > 0 ? innerL : innerR;
    const Vec3& corner = side > 0 ? cornerL : cornerR;
    double w = 0.0;
    // Behind the face (ears, temples behind the orbit, back of the head): the face's front lies
    // within ~0.45 of the canthal plane.
    w = std::max(w, smooth((-0.45 - q.z()) / 0.25));
    // Scalp behind the hairline: about 0.45 above the brows (forehead 4–6 cm).
    w = std::max(w, smooth((q.y() - (browY + 0.40)) / 0.20));
    // Neck: below the menton.
    w = std::max(w, smooth((menton.y() - 0.05 - q.y()) / 0.20));
    // Nasal dorsum: the bony and cartilaginous bridge, nasion to 70 % of the way to the tip.
    const Vec2 dorsumTop(nasion.x(), nasion.y()), dorsumEnd = dorsumTop + 0.7 * (Vec2(tip.x(), tip.y()) - dorsumTop);
    w = std::max(w, bump(segmentDistance2d(p, dorsumTop, dorsumEnd), 0.05, 0.06));
    // Zygomatic arch: a band ~0.15 below the canthal line, lateral of the outer canthus.
    w = std::max(w, bump(std::abs(q.y() - (eye.y() - 0.15)), 0.04, 0.06) * smooth((std::abs(q.x()) - std::abs(eye.x()) - 0.05) / 0.10));
    // Orbital retaining ligament: the inferior and lateral orbital rim, an ellipse around the eye
    // (centre between the canthi, semi-axes 0.30 × 0.22), lower half only (the brow stays free).
    {
      const Vec2 c(0.5 * (eye.x() + inner.x()), 0.5 * (eye.y() + inner.y()));
      const double r = planarLength((q.x() - c.x()) / 0.30, (q.y() - c.y()) / 0.22);
      w = std::max(w, bump(std::abs(r - 1.0) * 0.26, 0.02, 0.04) * smooth((c.y() + 0.05 - q.y()) / 0.05));
    }
    // Zygomatic ligament (McGregor's patch): below the outer canthus on the zygomatic body.
    w = std::max(w, bump((p - Vec2(eye.x(), eye.y() - 0.32)).norm(), 0.05, 0.06));

    // Soft-tissue thickness: cheek (lateral of the nasolabial region, between the zygoma and the
    // mandible), lips and chin, thin elsewhere.
    const double cheek = smooth((std::abs(q.x()) - 0.20) / 0.10) * smooth((eye.y() - 0.20 - q.y()) / 0.15) *
                         smooth((q.y() - (menton.y() + 0.20)) / 0.15) * smooth((q.z() + 0.45) / 0.15);
    const double lipChin = smooth((0.40 - std::abs(q.x())) / 0.10) * smooth((lipTopY + 0.10 - q.y()) / 0.10) *
                           smooth((q.y() - menton.y()) / 0.10) * (1.0 - smooth((-0.3 - q.z()) / 0.1));
    const double soft = std::max(cheek, lipChin);
    const double hSoft = cheek >= lipChin ? s.cheekTissue : s.lipChinTissue;
    const double h = (1.0 - soft) * s.thinTissue + soft * hSoft;
    const double kFree = s.fatShearModulus / h;

    // Mandibular ligament: anterior mandible, below and just lateral of the mouth corner. Its hold
    // reaches the skin through the chin's fat and fades geometrically with the distance d from it:
    // k = k_free (k_held / k_free)^b(d), b = 1 at its centre falling smoothly to 0 at 0.25, so the
    // compliance 1/k grows smoothly over the whole 0.25 (docs/anatomical_model.md, "The chin's
    // notch"). As a held weight of the linear mix below, w = (k − k_free)/(k_held − k_free).
    if (s.heldStiffness > kFree) {
      const double b = bump((p - Vec2(corner.x() + side * 0.02, menton.y() + 0.12)).norm(), 0.0, 0.25);
      w = std::max(w, kFree * (std::pow(s.heldStiffness / kFree, b) - 1.0) / (s.heldStiffness - kFree));
    }
    // The forehead over the frontal bone: from the brows (their skin lies on the supraorbital rim)
    // up, in front of the temples; the lids below have no bone under them.
    const Vec3& browIn = side > 0 ? browInL : browInR;
    const Vec3& browOut = side > 0 ? browOutL : browOutR;
    const double along = std::clamp((std::abs(q.x()) - std::abs(browIn.x())) / (std::abs(browOut.x()) - std::abs(browIn.x())), 0.0, 1.0);
    const double browLine = browIn.y() + along * (browOut.y() - browIn.y());  // the brow's height over this x
    map.forehead(i) = smooth((q.y() - (browLine - 0.06)) / 0.06) * smooth((q.z() + 0.45) / 0.15);
    map.held(i) = w;
    map.thickness(i) = h;
    map.attachment(i) = (1.0 - w) * kFree + w * s.heldStiffness;
  }
  return map;
}

SparseMat columnVolumeStiffness(const MatX3& V, const MatX3i& F, const VecX& depth, const VecX& area, const VecX& kappa) {
  const int n = static_cast<int>(V.rows());
  const MatX3 normals = vertexNormals(V, F);
  // The rows of C over the vertices with κ_i > 0: c_i = n_iᵀu_i + h_i div_s(u)_i.
  std::vector<Triplet> rows;
  std::vector<int> rowOf(static_cast<size_t>(n), -1);
  std::vector<double> rowKappa;
  for (int i = 0; i < n; ++i)
    if (kappa(i) > 0.0 && area(i) > 0.0) {
      rowOf[static_cast<size_t>(i)] = static_cast<int>(rowKappa.size());
      for (int c = 0; c < 3; ++c) rows.emplace_back(rowOf[static_cast<size_t>(i)], 3 * i + c, normals(i, c));
      rowKappa.push_back(kappa(i));
    }
  if (rowKappa.empty()) return SparseMat(3 * n, 3 * n);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    const Vec3 cross = (b - a).cross(c - a);
    const double twiceArea = cross.norm();
    if (!(twiceArea > 0.0)) continue;
    const Vec3 nt = cross / twiceArea;
    // ∇φ_j = n_t × (the edge opposite j, counter-clockwise) / 2A_t.
    const Vec3 grad[3] = {nt.cross(c - b) / twiceArea, nt.cross(a - c) / twiceArea, nt.cross(b - a) / twiceArea};
    for (int k = 0; k < 3; ++k) {
      const int i = F(t, k);
      const int r = rowOf[static_cast<size_t>(i)];
      if (r < 0) continue;
      const double share = depth(i) * (0.5 * twiceArea / 3.0) / area(i);  // h_i A_t / 3A_i
      for (int j = 0; j < 3; ++j)
        for (int d = 0; d < 3; ++d) rows.emplace_back(r, 3 * F(t, j) + d, share * grad[j](d));
    }
  }
  SparseMat C(static_cast<Eigen::Index>(rowKappa.size()), 3 * n);
  C.setFromTriplets(rows.begin(), rows.end());
  const VecX w = Eigen::Map<const VecX>(rowKappa.data(), static_cast<Eigen::Index>(rowKappa.size()));
  return SparseMat(C.transpose() * w.asDiagonal() * C);
}

SparseMat foreheadColumnStiffness(const Head& head, const TissueMap& map, double stiffness) {
  const int n = map.size();
  if (!(stiffness > 0)) return SparseMat(3 * n, 3 * n);
  return columnVolumeStiffness(head.mesh.V, head.mesh.F, map.thickness, map.area,
                               stiffness * map.forehead.cwiseProduct(map.area));
}

void applyAttachmentOverrides(TissueMap& map, const std::vector<AttachmentOverride>& overrides) {
  for (size_t k = 0; k < overrides.size(); ++k) {
    const AttachmentOverride& o = overrides[k];
    if (o.vertex < 0 || o.vertex >= map.size())
      throw InputError("skin.attachment[" + std::to_string(k) + "]: vertex " + std::to_string(o.vertex) +
                       " is outside [0, " + std::to_string(map.size()) + ")");
    if (!(o.stiffness > 0) || !std::isfinite(o.stiffness))
      throw InputError("skin.attachment[" + std::to_string(k) + "]: stiffness must be > 0 dyn/cm³ (got " +
                       std::to_string(o.stiffness) + ")");
    map.attachment(o.vertex) = o.stiffness;
  }
}

}  // namespace myo
