// Relaxed muscles follow the skin (AnatomicalSettings::relaxedMuscleModulus, releaseAcross, strength;
// docs/anatomical_model.md): released along its shape only, a muscle alone acts exactly as when
// muscles are held; among others it shortens by its σ (q = 1, StrengthRule::MuscleShortens) or the
// skin it is tied to follows it by σ (cᵀu/s = 1, SkinFollows, the default) and moves more than when
// the others hold it; released across, a relaxed muscle no longer holds the skin sideways; the reduced
// settle equals the full-space response of the released stiffness (Woodbury) for muscle, gravity
// and drag loads, with the cut-back basis no larger than the along-only one; the modulus → ∞ limit
// is the held model.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_skin.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/head_files.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace {

AnatomicalSettings withModulus(double e, bool across = true, StrengthRule rule = StrengthRule::SkinFollows) {
  AnatomicalSettings s;
  s.relaxedMuscleModulus = e;
  s.releaseAcross = across;
  s.strength = rule;
  return s;
}

// The first release: along each muscle's shape only, the muscle's own coordinate held to σ.
AnatomicalSettings alongOnly(double e) { return withModulus(e, false, StrengthRule::MuscleShortens); }

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
MatX3 couplingPull(const AnatomicalSkin& skin, int m) {
  const CoupledMuscle& cm = skin.muscles()[static_cast<size_t>(m)];
  MatX3 c = MatX3::Zero(skin.head().mesh.vertexCount(), 3);
  for (const auto& s : cm.springs) c.row(s.skin) += s.stiffness * s.muscleDisplacement(cm.fullShape).transpose();
  return c;
}
double muscleCoordinate(const AnatomicalSkin& skin, int m, double a, const MatX3& u) {
  const MatX3 c = couplingPull(skin, m);
  const double alpha = flat(skin.muscleLoad(m)).dot(flat(c)) / flat(c).squaredNorm();
  return a * alpha + skin.muscleRelease(m) * flat(c).dot(flat(u));
}
// The skin's motion along muscle m's shape, weighted by its couplings: cᵀu / s (1: the skin follows
// the muscle's shape at a = 1).
double skinAlongShape(const AnatomicalSkin& skin, int m, const MatX3& u) {
  const CoupledMuscle& cm = skin.muscles()[static_cast<size_t>(m)];
  double s = 0.0;
  for (const auto& sp : cm.springs) s += sp.stiffness * sp.muscleDisplacement(cm.fullShape).squaredNorm();
  return flat(couplingPull(skin, m)).dot(flat(u)) / s;
}

TEST(RelaxedMuscles, ReleasedAlongItsShapeAMuscleAloneActsExactlyAsWhenHeldAndShortensByItsSigma) {
  const Head head = loadDefaultHead();
  const std::vector<MuscleDef> one = {thesisMuscleDefs()[1]};  // zygomaticus major, left
  const AnatomicalSkin held(head, one, alongOnly(0.0)), released(head, one, alongOnly(1.0e5));
  const SkinLoads l = activate(held, {{one[0].name, 1.0}});
  const MatX3 uh = held.settle(l, false).u, ur = released.settle(l, false).u;
  EXPECT_LT(relative(ur, uh), 1e-8);
  EXPECT_EQ(held.muscleRelease(0), 0.0);
  EXPECT_GT(released.muscleRelease(0), 0.0);
  EXPECT_NEAR(muscleCoordinate(released, 0, 1.0, ur), 1.0, 1e-8);
}

TEST(RelaxedMuscles, AmongRelaxedOthersAMuscleShortensByItsSigmaAndMovesTheSkinMore) {
  const Head head = loadDefaultHead();
  const AnatomicalSkin held(head, thesisMuscleDefs(), alongOnly(0.0));
  const AnatomicalSkin along(head, thesisMuscleDefs(), alongOnly(1.0e5));
  const AnatomicalSkin across(head, thesisMuscleDefs(), withModulus(1.0e5, true, StrengthRule::MuscleShortens));
  const std::string zyg = "zygomaticus_major_left";
  const int m = along.muscleIndex(zyg);
  const SkinLoads l = activate(held, {{zyg, 1.0}});
  const MatX3 uh = held.settle(l, false).u, ua = along.settle(l, false).u, ux = across.settle(l, false).u;
  const int corner = head.landmarks.vertex("mouth_corner_left");
  RecordProperty("corner_held_mm", std::to_string(10 * uh.row(corner).norm()));
  RecordProperty("corner_released_along_mm", std::to_string(10 * ua.row(corner).norm()));
  RecordProperty("corner_released_across_mm", std::to_string(10 * ux.row(corner).norm()));
  EXPECT_GT(ua.row(corner).norm(), 1.05 * uh.row(corner).norm());
  EXPECT_GT(ux.row(corner).norm(), 1.05 * ua.row(corner).norm());
  EXPECT_NEAR(muscleCoordinate(along, m, 1.0, ua), 1.0, 1e-8);
  // Released across, the coordinate along the shape is S-orthogonal to the across ones: still q = 1.
  EXPECT_NEAR(muscleCoordinate(across, m, 1.0, ux), 1.0, 1e-8);
  // Linear in the activation, as before.
  const SkinLoads half = activate(across, {{zyg, 0.5}});
  EXPECT_LT(relative(across.settle(half, false).u, 0.5 * ux), 1e-9);
}

TEST(RelaxedMuscles, TheSkinFollowsTheMuscleBySigmaAndFollowsFartherThanUnderTheShorteningRule) {
  const Head head = loadDefaultHead();
  const AnatomicalSkin shortens(head, thesisMuscleDefs(), withModulus(1.0e5, true, StrengthRule::MuscleShortens));
  const AnatomicalSkin follows(head, thesisMuscleDefs(), withModulus(1.0e5, true, StrengthRule::SkinFollows));
  for (const std::string name : {"zygomaticus_major_left", "depressor_anguli_oris_right", "corrugator_supercilii_left"}) {
    const int m = follows.muscleIndex(name);
    const MatX3 us = shortens.settle(activate(shortens, {{name, 1.0}}), false).u;
    const MatX3 uf = follows.settle(activate(follows, {{name, 1.0}}), false).u;
    EXPECT_NEAR(skinAlongShape(follows, m, uf), 1.0, 1e-8) << name;
    // The skin lags the muscle when only the muscle is held to σ; the same field, scaled.
    const double lag = skinAlongShape(shortens, m, us);
    RecordProperty(name + "_skin_follows_under_shortening_rule", std::to_string(lag));
    EXPECT_GT(lag, 0.0) << name;
    EXPECT_LT(lag, 1.0) << name;
    EXPECT_LT(relative(uf, us / lag), 1e-8) << name;
  }
}

TEST(RelaxedMuscles, ReleasedAcrossARelaxedMuscleNoLongerHoldsTheSkinSideways) {
  // A drag at the zygomaticus's insertion, across its fibres (along the face frame's z, out of the
  // face): the relaxed muscle's couplings hold the skin there when released along its shape only.
  const Head head = loadDefaultHead();
  const std::vector<MuscleDef> defs = thesisMuscleDefs();
  AnatomicalSkin along(head, defs, alongOnly(1.0e5)), across(head, defs, withModulus(1.0e5));
  const CoupledMuscle& zyg = across.muscles()[static_cast<size_t>(across.muscleIndex("zygomaticus_major_left"))];
  int site = zyg.springs.front().skin;
  double best = -1.0;
  for (const auto& sp : zyg.springs)
    if (sp.stiffness > best) best = sp.stiffness, site = sp.skin;
  along.addDrag(site, 0.3);
  across.addDrag(site, 0.3);
  SkinLoads l = activate(along, {});
  l.drags[0] = 200.0 * head.frame().axes.col(2);
  const double ua = along.settle(l, false).u.row(site).norm(), ux = across.settle(l, false).u.row(site).norm();
  RecordProperty("drag_along_only_mm", std::to_string(10 * ua));
  RecordProperty("drag_across_mm", std::to_string(10 * ux));
  EXPECT_GT(ux, 1.1 * ua);
  // The cut-back basis steps at the cost of the along-only one: d modes and one vector per load.
  EXPECT_LE(across.basis()->modeCount(), along.basis()->modeCount());
  EXPECT_LT(across.settle(l, false).u.norm(), 1e3);
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

// The mouth's ring released in halves (AnatomicalSettings::releaseRingHalves): a pull on one mouth
// corner no longer moves the other corner through the relaxed ring's one coordinate (on ICT the
// opposite corner moved 3.9 mm beside the pulled one's 5.4 mm; docs/anatomical_model.md, "A ring is
// released in halves"), and the reduced settle stays the full-space response of the released
// stiffness (the other half's columns are in the held basis).
TEST(RelaxedMuscles, AMouthRingReleasedInHalvesLetsOneCornerMoveWithoutTheOther) {
  const Head head = loadDefaultHead();
  std::vector<MuscleDef> defs;
  for (const MuscleDef& d : faceMuscleDefs())
    if (d.name == "zygomaticus_major_left" || d.name == "orbicularis_oris_upper" || d.name == "orbicularis_oris_lower")
      defs.push_back(d);
  ASSERT_EQ(defs.size(), 3u);
  AnatomicalSettings whole = withModulus(1.0e5), halves = withModulus(1.0e5);
  whole.releaseRingHalves = false;
  ASSERT_TRUE(halves.releaseRingHalves);  // the default
  const AnatomicalSkin tied(head, defs, whole), split(head, defs, halves);
  const int left = head.landmarks.vertex("mouth_corner_left"), right = head.landmarks.vertex("mouth_corner_right");
  const SkinLoads l = activate(split, {{"zygomaticus_major_left", 1.0}});
  const MatX3 ut = tied.settle(l, false).u, us = split.settle(l, false).u;
  const double tiedRatio = ut.row(right).norm() / ut.row(left).norm();
  const double splitRatio = us.row(right).norm() / us.row(left).norm();
  RecordProperty("opposite_over_pulled_corner_tied", std::to_string(tiedRatio));
  RecordProperty("opposite_over_pulled_corner_halves", std::to_string(splitRatio));
  EXPECT_LT(splitRatio, 0.5 * tiedRatio);
  EXPECT_GT(us.row(left).norm(), ut.row(left).norm());  // the pulled corner is held less
  // Exact in the basis: each half's release column's response is spanned.
  SkinLoads mixed = activate(split, {{"zygomaticus_major_left", 0.6}, {"orbicularis_oris_upper", 0.3}});
  mixed.gravity = Vec3(0.0, -981.0 * 0.8, 300.0);
  EXPECT_LT(relative(split.settle(mixed, false).u, split.linearFullResponse(mixed)), 1e-6);
  // The split is a different basis: its own cache keys.
  EXPECT_FALSE(tied.releasedBasisKey() == split.releasedBasisKey());
}

TEST(RelaxedMuscles, AStiffBellyIsTheHeldModelAndANegativeModulusIsRefused) {
  const Head head = loadDefaultHead();
  for (const bool across : {false, true}) {
    const AnatomicalSkin held(head, thesisMuscleDefs(), withModulus(0.0, across));
    const AnatomicalSkin stiff(head, thesisMuscleDefs(), withModulus(1.0e14, across));
    const SkinLoads l = activate(held, {{"zygomaticus_major_left", 1.0}, {"depressor_anguli_oris_right", 0.5}});
    EXPECT_LT(relative(stiff.settle(l, false).u, held.settle(l, false).u), 1e-5) << across;
  }
  EXPECT_THROW(AnatomicalSkin(head, thesisMuscleDefs(), withModulus(-1.0)), InputError);
}

}  // namespace
}  // namespace myo
