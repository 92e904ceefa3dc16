// The face model on ICT-FaceKit's head (../shared/data/ict; skipped when absent): symmetry,
// agreement with the artist-made expression shapes, each muscle's action, and invariance of the
// whole model to where the head sits, how it is turned and its units.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>
#include <sstream>

#include "myoshell/io/head_files.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/obj_reader.h"
#include "myoshell/thesis/face_model.h"
#include "myoshell/thesis/simulator.h"
#include "support/basis_cache.h"
#include "support/test_data.h"

namespace myo {
namespace {

Head thesisIctHead() {
  const auto dir = test::sharedDataDir() / "ict";
  return loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string(),
                  (dir / "rigid_vertices.json").string());
}

FaceModelSettings ictSettings() {
  FaceModelSettings s;
  s.gravity = false;
  s.precision = ModalPrecision::Double;
  return s;
}

std::shared_ptr<const FaceModel> ictFace() {
  static const auto model = std::make_shared<const FaceModel>(thesisIctHead(), thesisMuscleDefs(), ictSettings(), test::sharedBasisCache());
  return model;
}

// The skin displacement after holding the given activations for `seconds` (long enough to settle).
MatX3 settledField(const std::shared_ptr<const FaceModel>& model,
                   const std::vector<std::pair<std::string, double>>& activations, double seconds = 1.5) {
  Simulator sim(model);
  for (const auto& [name, a] : activations) sim.setActivation(name, a);
  sim.advance(seconds);
  return sim.skinDisplacement();
}

double cosine(const Vec3& a, const Vec3& b) { return a.dot(b) / (a.norm() * b.norm()); }

TEST(IctFace, EachPairIsMirrorSymmetric) {
  MYO_REQUIRE_SHARED_DATA();
  const auto model = ictFace();
  const MatX3& V = model->head().mesh.V;
  // The ICT head is symmetric about x = 0: a vertex's mirror is the vertex nearest (−x, y, z).
  std::vector<int> mirror(static_cast<size_t>(V.rows()));
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Vec3 p(-V(v, 0), V(v, 1), V(v, 2));
    Eigen::Index best = 0;
    (V.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&best);
    mirror[static_cast<size_t>(v)] = static_cast<int>(best);
  }
  for (const std::string base : {"zygomaticus_major", "corrugator_supercilii", "depressor_labii_inferioris",
                                 "depressor_anguli_oris"}) {
    const MatX3 right = settledField(model, {{base + "_right", 1.0}});
    const MatX3 left = settledField(model, {{base + "_left", 1.0}});
    const MuscleUnit& unit = model->muscles()[static_cast<size_t>(model->muscleIndex(base + "_right"))];
    double diff = 0.0, norm = 0.0;
    for (int v : unit.roi) {
      Vec3 mirrored = left.row(mirror[static_cast<size_t>(v)]);
      mirrored.x() = -mirrored.x();
      diff += (Vec3(right.row(v)) - mirrored).squaredNorm();
      norm += right.row(v).squaredNorm();
    }
    RecordProperty(base + "_asymmetry", std::to_string(std::sqrt(diff / norm)));
    EXPECT_LE(std::sqrt(diff / norm), 0.05) << base << ": RMS asymmetry over the ROI";
  }
}

TEST(IctFace, ZygomaticusAndDepressorAnguliMoveTheMouthCornerLikeTheExpressions) {
  MYO_REQUIRE_SHARED_DATA();
  const auto model = ictFace();
  const Head& head = model->head();
  const auto dir = test::sharedDataDir() / "ict";
  const int corner = head.landmarks.vertex("mouth_corner_left");
  const Vec3 up = head.frame().axes.col(1);

  const MatX3 smileShape = readObjLike((dir / "expression_mouthSmile_L.obj").string(), head.mesh).V - head.mesh.V;
  const MatX3 smile = settledField(model, {{"zygomaticus_major_left", 1.0}});
  RecordProperty("smile_corner_cm", std::to_string(smile.row(corner).norm()));
  RecordProperty("smile_corner_cosine", std::to_string(cosine(smile.row(corner), smileShape.row(corner))));
  EXPECT_GE(smile.row(corner).norm(), 0.3) << "mouth corner moved less than 3 mm (cm)";
  EXPECT_GE(cosine(smile.row(corner), smileShape.row(corner)), 0.7);
  EXPECT_GT(smile.row(corner).dot(up), 0.0) << "a smile lifts the corner";

  const MatX3 frownShape = readObjLike((dir / "expression_mouthFrown_L.obj").string(), head.mesh).V - head.mesh.V;
  const MatX3 frown = settledField(model, {{"depressor_anguli_oris_left", 1.0}});
  RecordProperty("frown_corner_down_cm", std::to_string(-frown.row(corner).dot(up)));
  RecordProperty("frown_corner_cosine", std::to_string(cosine(frown.row(corner), frownShape.row(corner))));
  EXPECT_LT(frown.row(corner).dot(up), -0.1) << "depressor anguli oris pulls the corner down (cm)";
  EXPECT_GE(cosine(frown.row(corner), frownShape.row(corner)), 0.7);

  // Over every vertex the expression moves by more than 0.5 mm: cosine and magnitude ratio
  // (reported in docs/face_model.md; the aim is 0.8, the floor here guards against regressions).
  for (const auto& [field, shape, name] :
       {std::tuple<const MatX3&, const MatX3&, const char*>{smile, smileShape, "smile"},
        std::tuple<const MatX3&, const MatX3&, const char*>{frown, frownShape, "frown"}}) {
    double dot = 0.0, uu = 0.0, ee = 0.0;
    for (Eigen::Index v = 0; v < shape.rows(); ++v)
      if (shape.row(v).norm() > 0.05) {
        dot += field.row(v).dot(shape.row(v));
        uu += field.row(v).squaredNorm();
        ee += shape.row(v).squaredNorm();
      }
    const double c = dot / std::sqrt(uu * ee);
    RecordProperty(std::string(name) + "_cosine", std::to_string(c));
    RecordProperty(std::string(name) + "_magnitude_ratio", std::to_string(std::sqrt(uu / ee)));
    EXPECT_GE(c, 0.55) << name;
  }
}

TEST(IctFace, DepressorLabiiLowersTheLowerLipAndCorrugatorPullsTheBrowDownAndIn) {
  MYO_REQUIRE_SHARED_DATA();
  const auto model = ictFace();
  const Head& head = model->head();
  const FaceFrame frame = head.frame();
  const Vec3 up = frame.axes.col(1), left = frame.axes.col(0);
  const MatX3 lip = settledField(model, {{"depressor_labii_inferioris_right", 1.0}, {"depressor_labii_inferioris_left", 1.0}});
  RecordProperty("lower_lip_down_cm", std::to_string(-lip.row(head.landmarks.vertex("lower_lip_bottom")).dot(up)));
  EXPECT_LT(lip.row(head.landmarks.vertex("lower_lip_bottom")).dot(up), -0.1) << "lower lip not lowered (cm)";
  const MatX3 brow = settledField(model, {{"corrugator_supercilii_right", 1.0}, {"corrugator_supercilii_left", 1.0}});
  const Vec3 r = brow.row(head.landmarks.vertex("right_brow_inner"));
  const Vec3 l = brow.row(head.landmarks.vertex("left_brow_inner"));
  RecordProperty("brow_down_cm", std::to_string(-r.dot(up)));
  RecordProperty("brow_in_cm", std::to_string(r.dot(left)));
  EXPECT_LT(r.dot(up), -0.02) << "right inner brow not pulled down";
  EXPECT_LT(l.dot(up), -0.02) << "left inner brow not pulled down";
  EXPECT_GT(r.dot(left), 0.02) << "right inner brow not pulled in (towards the midline)";
  EXPECT_LT(l.dot(left), -0.02) << "left inner brow not pulled in (towards the midline)";
}

TEST(IctFace, WithTheSkullMuscleOriginsSitOnTheBone) {
  MYO_REQUIRE_SHARED_DATA();
  Head head = thesisIctHead();
  head.skull = readObj((test::sharedDataDir() / "skull" / "skull_in_ict_head.obj").string());
  const MatX3 skullNormals = vertexNormals(head.skull.V, head.skull.F);
  for (const MuscleDef& def : thesisMuscleDefs()) {
    const Muscle withSkull = buildMuscle(def, head);
    const SurfacePoint bone = closestSurfacePoint(head.skull.V, head.skull.F, skullNormals, withSkull.originPoint);
    RecordProperty(def.name + "_origin_to_skull_cm", std::to_string(bone.distance));
    EXPECT_LT(bone.distance, 0.35) << def.name << ": origin centre is not on the skull (cm)";
  }
  // The face still works with skull-anchored origins.
  const auto model = std::make_shared<const FaceModel>(head, std::vector<MuscleDef>{thesisMuscleDefs()[1]}, ictSettings());
  const MatX3 smile = settledField(model, {{"zygomaticus_major_left", 1.0}});
  const int corner = head.landmarks.vertex("mouth_corner_left");
  RecordProperty("skull_smile_corner_cm", std::to_string(smile.row(corner).norm()));
  EXPECT_GE(smile.row(corner).norm(), 0.3);
  EXPECT_GT(smile.row(corner).dot(head.frame().axes.col(1)), 0.0);
}

TEST(IctFace, MusclesAndFieldsMoveWithTheHeadAndItsUnits) {
  MYO_REQUIRE_SHARED_DATA();
  // The head rotated 30° about a skew axis, moved, and given in metres (s = 0.01). Materials are
  // converted so the physics is the same: k_A/s, k_L, k_B·s, thickness·s and a density that keeps
  // every vertex mass over s (then M ü + K u = F is the same equation in both).
  const double s = 0.01;
  const Mat3 R = Eigen::AngleAxisd(30.0 * M_PI / 180.0, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const Vec3 t(0.3, -1.2, 2.5);
  Head moved = thesisIctHead();
  for (Eigen::Index v = 0; v < moved.mesh.V.rows(); ++v)
    moved.mesh.V.row(v) = (s * R * Vec3(moved.mesh.V.row(v)) + t).transpose();
  FaceModelSettings a = ictSettings(), b = ictSettings();
  for (ShellMaterial* m : {&b.skin, &b.muscle}) {
    m->kA /= s;
    m->kB *= s;
    m->thickness *= s;
    m->density /= s * s * s * s;
  }
  const std::vector<MuscleDef> defs = {thesisMuscleDefs()[0], thesisMuscleDefs()[6]};
  const auto original = std::make_shared<const FaceModel>(thesisIctHead(), defs, a);
  const auto transformed = std::make_shared<const FaceModel>(moved, defs, b);
  for (size_t m = 0; m < defs.size(); ++m) {
    const MatX3& x = original->muscles()[m].muscle.mesh.V;
    const MatX3& y = transformed->muscles()[m].muscle.mesh.V;
    for (Eigen::Index v = 0; v < x.rows(); ++v)
      EXPECT_LE((s * R * Vec3(x.row(v)) + t - Vec3(y.row(v))).norm(), 1e-6 * s) << defs[m].name << " node " << v;
    EXPECT_EQ(original->muscles()[m].roi, transformed->muscles()[m].roi) << defs[m].name;
  }
  Simulator sa(original), sb(transformed);
  for (Simulator* sim : {&sa, &sb})
    for (const MuscleDef& d : defs) sim->setActivation(d.name, 1.0);
  sa.advance(0.3);
  sb.advance(0.3);
  const MatX3& ua = sa.skinDisplacement();
  const MatX3& ub = sb.skinDisplacement();
  double err = 0.0;
  for (Eigen::Index v = 0; v < ua.rows(); ++v) err = std::max(err, (s * R * Vec3(ua.row(v)) - Vec3(ub.row(v))).norm());
  std::ostringstream relative;
  relative << err / (s * ua.rowwise().norm().maxCoeff());
  RecordProperty("invariance_relative_error", relative.str());
  EXPECT_LE(err / (s * ua.rowwise().norm().maxCoeff()), 1e-6);
}

}  // namespace
}  // namespace myo
