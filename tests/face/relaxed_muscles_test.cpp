// Relaxed muscles follow the skin (AnatomicalSettings::relaxedMuscleModulus; docs/anatomical_model.md):
// a muscle alone acts exactly as when muscles are held; among others it shortens by its σ (q = 1)
// and moves the skin more than when the others hold it; the reduced settle equals the full-space
// response of the released stiffness (Woodbury) for muscle, gravity and drag loads; the modulus
// → ∞ limit is the held model.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "myoshell/core/errors.h"
#include "myoshell/face/anatomical_skin.h"
#include "myoshell/face/muscle_def.h"
#include "myoshell/io/head_files.h"

namespace myo {
namespace {

AnatomicalSettings withModulus(double e) {
  AnatomicalSettings s;
  s.relaxedMuscleModulus = e;
  return s;
}

SkinLoads activate(const AnatomicalSkin& skin, const std::vector<std::pair<std::string, double>>& acts) {
  SkinLoads l;
  l.activations = VecX::Zero(static_cast<Eigen::Index>(skin.muscles().size()));
  for (const auto& [name, a] : acts) l.activations(skin.muscleIndex(name)) = a;
  l.gravity = skin.restGravity();
  l.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
  return l;
}

double relative(const MatX3& a, const MatX3& b) { return (a - b).norm() / b.norm(); }

// The muscle's coordinate at the settled skin u: q_m = γ_m (F_m + c_mᵀu) = a α_m + γ_m c_mᵀu, with
// c_m = Σ_springs k_i w_i (its couplings' pull) and α_m the ratio of its load to c_m.
double muscleCoordinate(const AnatomicalSkin& skin, int m, double a, const MatX3& u) {
  const CoupledMuscle& cm = skin.muscles()[static_cast<size_t>(m)];
  MatX3 c = MatX3::Zero(u.rows(), 3);
  for (const auto& s : cm.springs) c.row(s.skin) += s.stiffness * s.muscleDisplacement(cm.fullShape).transpose();
  const double alpha = flat(skin.muscleLoad(m)).dot(flat(c)) / flat(c).squaredNorm();
  return a * alpha + skin.muscleRelease(m) * flat(c).dot(flat(u));
}

TEST(RelaxedMuscles, AMuscleAloneActsExactlyAsWhenHeldAndShortensByItsSigma) {
  const Head head = loadDefaultHead();
  const std::vector<MuscleDef> one = {thesisMuscleDefs()[1]};  // zygomaticus major, left
  const AnatomicalSkin held(head, one, withModulus(0.0)), released(head, one, withModulus(1.0e5));
  const SkinLoads l = activate(held, {{one[0].name, 1.0}});
  const MatX3 uh = held.settle(l, false).u, ur = released.settle(l, false).u;
  EXPECT_LT(relative(ur, uh), 1e-8);
  EXPECT_EQ(held.muscleRelease(0), 0.0);
  EXPECT_GT(released.muscleRelease(0), 0.0);
  EXPECT_NEAR(muscleCoordinate(released, 0, 1.0, ur), 1.0, 1e-8);
}

TEST(RelaxedMuscles, AmongRelaxedOthersAMuscleShortensByItsSigmaAndMovesTheSkinMore) {
  const Head head = loadDefaultHead();
  const AnatomicalSkin held(head, thesisMuscleDefs(), withModulus(0.0));
  const AnatomicalSkin released(head, thesisMuscleDefs(), withModulus(1.0e5));
  const std::string zyg = "zygomaticus_major_left";
  const SkinLoads l = activate(held, {{zyg, 1.0}});
  const MatX3 uh = held.settle(l, false).u, ur = released.settle(l, false).u;
  const int corner = head.landmarks.vertex("mouth_corner_left");
  RecordProperty("corner_held_mm", std::to_string(10 * uh.row(corner).norm()));
  RecordProperty("corner_released_mm", std::to_string(10 * ur.row(corner).norm()));
  EXPECT_GT(ur.row(corner).norm(), 1.05 * uh.row(corner).norm());
  EXPECT_NEAR(muscleCoordinate(released, released.muscleIndex(zyg), 1.0, ur), 1.0, 1e-8);
  // Linear in the activation, as before.
  const SkinLoads half = activate(released, {{zyg, 0.5}});
  EXPECT_LT(relative(released.settle(half, false).u, 0.5 * ur), 1e-9);
}

TEST(RelaxedMuscles, TheReducedSettleEqualsTheFullSpaceResponseOfTheReleasedStiffness) {
  const Head head = loadDefaultHead();
  AnatomicalSkin skin(head, thesisMuscleDefs(), withModulus(1.0e5));
  skin.addDrag(head.landmarks.vertex("mouth_corner_right"), 0.5);
  SkinLoads l = activate(skin, {{"zygomaticus_major_left", 0.7}, {"corrugator_supercilii_right", 0.4}});
  l.gravity = Vec3(0.0, -981.0 * 0.8, 300.0);
  l.drags[0] = Vec3(-500.0, 200.0, 100.0);
  const MatX3 reduced = skin.settle(l, false).u;
  const MatX3 full = skin.linearFullResponse(l);
  RecordProperty("reduced_vs_full", std::to_string(relative(reduced, full)));
  EXPECT_LT(relative(reduced, full), 1e-6);
}

TEST(RelaxedMuscles, AStiffBellyIsTheHeldModelAndANegativeModulusIsRefused) {
  const Head head = loadDefaultHead();
  const AnatomicalSkin held(head, thesisMuscleDefs(), withModulus(0.0));
  const AnatomicalSkin stiff(head, thesisMuscleDefs(), withModulus(1.0e14));
  const SkinLoads l = activate(held, {{"zygomaticus_major_left", 1.0}, {"depressor_anguli_oris_right", 0.5}});
  EXPECT_LT(relative(stiff.settle(l, false).u, held.settle(l, false).u), 1e-5);
  EXPECT_THROW(AnatomicalSkin(head, thesisMuscleDefs(), withModulus(-1.0)), InputError);
}

}  // namespace
}  // namespace myo
