#include "myoshell/head/head_checks.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/head/face_frame.h"

namespace myo {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A number for a message: 3 significant digits, no trailing zeros ("8.92", "0.0892", "8.92e+03").
std::string num(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

std::string meshName(const TriMesh& mesh) {
  return mesh.sourcePath.empty() ? std::string("the mesh") : "mesh " + mesh.sourcePath;
}

// Connected pieces of the mesh over its triangles (union–find): a label per vertex, −1 for a vertex
// on no triangle.
std::vector<int> pieceLabels(const MatX3i& F, int vertexCount) {
  std::vector<int> parent(static_cast<size_t>(vertexCount));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[static_cast<size_t>(v)] != v) {
      parent[static_cast<size_t>(v)] = parent[static_cast<size_t>(parent[static_cast<size_t>(v)])];
      v = parent[static_cast<size_t>(v)];
    }
    return v;
  };
  std::vector<char> used(static_cast<size_t>(vertexCount), 0);
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      used[static_cast<size_t>(F(t, k))] = 1;
      const int a = find(F(t, k)), b = find(F(t, (k + 1) % 3));
      if (a != b) parent[static_cast<size_t>(a)] = b;
    }
  std::vector<int> label(static_cast<size_t>(vertexCount), -1);
  for (int v = 0; v < vertexCount; ++v)
    if (used[static_cast<size_t>(v)]) label[static_cast<size_t>(v)] = find(v);
  return label;
}

// The landmarks whose neighbourhood makes the face region (eyes, nose, mouth).
constexpr const char* kFaceRegionLandmarks[] = {
    "right_eye_outer", "right_eye_inner",    "left_eye_inner",     "left_eye_outer", "nose_tip",
    "mouth_corner_right", "mouth_corner_left", "upper_lip_top", "lower_lip_bottom"};

// Area-weighted mean normal (Σ (b−a)×(c−a) / 2 over the region's triangles, not normalised) and the
// number of triangles whose centroid lies within kFaceRegionRadius · frame.scale of a region
// landmark.
std::pair<Vec3, int> faceRegionNormal(const MatX3& V, const MatX3i& F, const Landmarks& lm,
                                      const FaceFrame& frame) {
  std::vector<Vec3> centres;
  for (const char* name : kFaceRegionLandmarks) centres.push_back(V.row(lm.vertex(name)).transpose());
  const double r2 = std::pow(kFaceRegionRadius * frame.scale, 2);
  Vec3 sum = Vec3::Zero();
  int count = 0;
  for (int t = 0; t < F.rows(); ++t) {
    const Vec3 a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    const Vec3 centroid = (a + b + c) / 3.0;
    bool inside = false;
    for (const Vec3& p : centres) inside = inside || (centroid - p).squaredNorm() <= r2;
    if (!inside) continue;
    sum += 0.5 * (b - a).cross(c - a);
    ++count;
  }
  return {sum, count};
}

double angleDeg(const Vec3& a, const Vec3& b) {
  const double n = a.norm() * b.norm();
  if (!(n > 0.0)) return 180.0;
  return std::acos(std::clamp(a.dot(b) / n, -1.0, 1.0)) * 180.0 / kPi;
}

// Face-frame coordinates of the required landmarks, looked up by name, with the message helper.
class FitCheck {
 public:
  FitCheck(const TriMesh& mesh, const Landmarks& lm)
      : mesh_(mesh), lm_(lm), frame_(faceFrame(mesh.V, lm)) {}

  const FaceFrame& frame() const { return frame_; }
  Vec3 q(const char* name) const { return frame_.toFrame(Vec3(mesh_.V.row(lm_.vertex(name)))); }

  [[noreturn]] void refuse(const std::string& name, const std::string& why) const {
    throw InputError("landmark '" + name + "' (vertex " + std::to_string(lm_.vertex(name)) +
                         ") does not fit " + meshName(mesh_) + ": " + why +
                         " (is this the landmark file of another mesh? docs/heads.md, \"Checks on load\")",
                     lm_.sourcePath);
  }
  // Requires `value` < `bound` (both face-frame coordinates, outer-canthus distances).
  void below(const char* name, double value, double bound, const std::string& what) const {
    if (!(value < bound)) refuse(name, what + " (face-frame " + num(value) + " vs " + num(bound) + ")");
  }

 private:
  const TriMesh& mesh_;
  const Landmarks& lm_;
  FaceFrame frame_;
};

}  // namespace

LengthUnit parseLengthUnit(std::string_view text, const std::string& file) {
  if (text == "cm") return LengthUnit::cm;
  if (text == "m") return LengthUnit::m;
  if (text == "mm") return LengthUnit::mm;
  throw InputError("unknown length unit '" + std::string(text) + "' (use m, mm or cm)", file);
}

const char* lengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::m: return "m";
    case LengthUnit::mm: return "mm";
    case LengthUnit::cm: break;
  }
  return "cm";
}

double centimetresPer(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::m: return 100.0;
    case LengthUnit::mm: return 0.1;
    case LengthUnit::cm: break;
  }
  return 1.0;
}

void rescaleToCentimetres(TriMesh& mesh, LengthUnit unit) {
  if (unit != LengthUnit::cm) mesh.V *= centimetresPer(unit);
}

void rescaleToCentimetres(Head& head, LengthUnit unit) {
  rescaleToCentimetres(head.mesh, unit);
  rescaleToCentimetres(head.skull, unit);
}

HeadFitMeasures measureHeadFit(const TriMesh& mesh, const Landmarks& landmarks) {
  const FaceFrame frame = faceFrame(mesh.V, landmarks);
  const auto [normal, count] = faceRegionNormal(mesh.V, mesh.F, landmarks, frame);
  HeadFitMeasures m;
  m.outerCanthusDistance = frame.scale;
  m.frameNormalAngleDeg = angleDeg(frame.axes.col(2), normal);
  m.faceRegionTriangles = count;
  return m;
}

void checkHeadScale(const TriMesh& mesh, const Landmarks& landmarks, LengthUnit unitGiven) {
  const double d = (mesh.V.row(landmarks.vertex("left_eye_outer")) -
                    mesh.V.row(landmarks.vertex("right_eye_outer"))).norm();
  if (d >= kMinOuterCanthusCm && d <= kMaxOuterCanthusCm) return;
  const double fileValue = d / centimetresPer(unitGiven);  // the distance in the file's own numbers
  std::string readAs, propose;
  for (LengthUnit u : {LengthUnit::m, LengthUnit::mm, LengthUnit::cm}) {
    if (u == unitGiven) continue;
    const double asCm = fileValue * centimetresPer(u);
    readAs += std::string(readAs.empty() ? "" : ", ") + "in " + lengthUnitName(u) + " it would be " +
              num(asCm) + " cm";
    if (asCm >= kMinOuterCanthusCm && asCm <= kMaxOuterCanthusCm) propose = lengthUnitName(u);
  }
  throw InputError(
      "head scale: outer-canthus distance (right_eye_outer to left_eye_outer) is " + num(d) +
          " cm with the mesh read in " + lengthUnitName(unitGiven) + ", outside the " +
          num(kMinOuterCanthusCm) + "-" + num(kMaxOuterCanthusCm) + " cm of a human face (" + readAs +
          "); give the mesh's unit with --units m|mm|cm (scene key head.units)" +
          (propose.empty() ? std::string() : ": probably --units " + propose),
      mesh.sourcePath);
}

void checkLandmarksFitMesh(const TriMesh& mesh, const Landmarks& landmarks) {
  // Off the surface: on no triangle, or on another piece than the face.
  const std::vector<int> piece = pieceLabels(mesh.F, mesh.vertexCount());
  const auto resolved = landmarks.resolved();
  const int noseVertex = landmarks.vertex("nose_tip");
  const int facePiece = piece[static_cast<size_t>(noseVertex)];
  auto refuseOff = [&](const std::string& name, int v, const std::string& why) {
    throw InputError("landmark '" + name + "' (vertex " + std::to_string(v) + ") does not fit " +
                         meshName(mesh) + ": it is off the surface: " + why,
                     landmarks.sourcePath);
  };
  for (const auto& [name, v] : resolved)
    if (piece[static_cast<size_t>(v)] < 0) refuseOff(name, v, "the vertex is on no triangle");
  for (const auto& [name, v] : resolved)
    if (piece[static_cast<size_t>(v)] != facePiece)
      refuseOff(name, v, "it lies on another connected piece of the mesh than nose_tip (vertex " +
                             std::to_string(noseVertex) + ")");

  // In the face frame: x from the right to the left outer eye corner (so those two sit at x = ∓0.5,
  // y = z = 0), y up, z out of the face; lengths in outer-canthus distances.
  const FitCheck c(mesh, landmarks);
  const Vec3 eyeRo = c.q("right_eye_outer"), eyeRi = c.q("right_eye_inner");
  const Vec3 eyeLi = c.q("left_eye_inner"), eyeLo = c.q("left_eye_outer");
  const Vec3 browRo = c.q("right_brow_outer"), browRi = c.q("right_brow_inner");
  const Vec3 browLi = c.q("left_brow_inner"), browLo = c.q("left_brow_outer");
  const Vec3 nasion = c.q("nasion_approx"), nose = c.q("nose_tip");
  const Vec3 mouthR = c.q("mouth_corner_right"), mouthL = c.q("mouth_corner_left");
  const Vec3 lipTop = c.q("upper_lip_top"), lipBottom = c.q("lower_lip_bottom");
  const Vec3 chin = c.q("chin_menton");

  // Sides: the inner eye corners between the outer ones, each on its own side; brows and mouth
  // corners on their sides, outer brow ends farther out than the inner ones.
  const std::string between = "the inner eye corners lie between the outer ones, ";
  c.below("right_eye_inner", eyeRo.x(), eyeRi.x(), between + "so right_eye_inner must be right of right_eye_outer");
  c.below("right_eye_inner", eyeRi.x(), 0.0, between + "so right_eye_inner must be on the subject's right (x < 0)");
  c.below("left_eye_inner", 0.0, eyeLi.x(), between + "so left_eye_inner must be on the subject's left (x > 0)");
  c.below("left_eye_inner", eyeLi.x(), eyeLo.x(), between + "so left_eye_inner must be left of left_eye_outer");
  c.below("right_brow_outer", browRo.x(), browRi.x(), "right_brow_outer must be farther right than right_brow_inner");
  c.below("right_brow_inner", browRi.x(), 0.0, "right_brow_inner must be on the subject's right (x < 0)");
  c.below("left_brow_inner", 0.0, browLi.x(), "left_brow_inner must be on the subject's left (x > 0)");
  c.below("left_brow_outer", browLi.x(), browLo.x(), "left_brow_outer must be farther left than left_brow_inner");
  c.below("mouth_corner_right", mouthR.x(), 0.0, "mouth_corner_right must be on the subject's right (x < 0)");
  c.below("mouth_corner_left", 0.0, mouthL.x(), "mouth_corner_left must be on the subject's left (x > 0)");

  // Heights: brows above the eyes, eyes above the nose tip, nose tip above the mouth, upper lip
  // above the lower lip, chin below the mouth.
  const double eyeLow = std::min({0.0, eyeRi.y(), eyeLi.y()});
  const double eyeHigh = std::max({0.0, eyeRi.y(), eyeLi.y()});
  c.below("right_brow_outer", eyeHigh, browRo.y(), "the brows must be above the eye corners");
  c.below("right_brow_inner", eyeHigh, browRi.y(), "the brows must be above the eye corners");
  c.below("left_brow_inner", eyeHigh, browLi.y(), "the brows must be above the eye corners");
  c.below("left_brow_outer", eyeHigh, browLo.y(), "the brows must be above the eye corners");
  c.below("nose_tip", nose.y(), eyeLow, "the nose tip must be below the eye corners");
  c.below("nose_tip", nose.y(), nasion.y(), "the nose tip must be below nasion_approx");
  c.below("mouth_corner_right", mouthR.y(), eyeLow, "the mouth corners must be below the eyes");
  c.below("mouth_corner_left", mouthL.y(), eyeLow, "the mouth corners must be below the eyes");
  c.below("mouth_corner_right", mouthR.y(), nose.y(), "the mouth corners must be below the nose tip");
  c.below("mouth_corner_left", mouthL.y(), nose.y(), "the mouth corners must be below the nose tip");
  c.below("upper_lip_top", lipTop.y(), nose.y(), "the upper lip must be below the nose tip");
  c.below("lower_lip_bottom", lipBottom.y(), lipTop.y(), "the lower lip must be below the upper lip");
  c.below("chin_menton", chin.y(), lipBottom.y(), "the chin must be below the lower lip");

  // Depth: the nose tip in front of the eye and mouth corners.
  const double behind = std::max({0.0, eyeRi.z(), eyeLi.z(), mouthR.z(), mouthL.z()});
  c.below("nose_tip", behind, nose.z(), "the nose tip must be in front of the eye and mouth corners");

  // The frame's z along the face: the area-weighted mean normal of the face region.
  const auto [normal, count] = faceRegionNormal(mesh.V, mesh.F, landmarks, c.frame());
  const double angle = angleDeg(c.frame().axes.col(2), normal);
  if (count == 0 || angle > kMaxFrameNormalAngleDeg)
    throw InputError(
        "landmarks right_eye_outer, left_eye_outer, chin_menton do not fit " + meshName(mesh) +
            ": the face frame's z (out of the face) makes " + num(angle) +
            " degrees with the mean normal of the face around the eyes, nose and mouth (at most " +
            num(kMaxFrameNormalAngleDeg) + "; " + std::to_string(count) +
            " triangles): left and right swapped, or the mesh's triangles face inward",
        landmarks.sourcePath);
}

void checkLoadedHead(const Head& head, LengthUnit unitGiven) {
  checkLandmarksFitMesh(head.mesh, head.landmarks);
  checkHeadScale(head.mesh, head.landmarks, unitGiven);
}

}  // namespace myo
