// Muscle–skin coupling of the anatomical model (muscles/muscle_coupling.h) on the built-in head:
// the skin over a muscle is tied to the muscle's surface point below it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "myoshell/muscles/muscle_coupling.h"
#include "myoshell/muscles/muscle_def.h"
#include "myoshell/muscles/tissue_attachment.h"

namespace myo {
namespace {

const MuscleDef& thesisMuscle(const std::string& name) {
  static const std::vector<MuscleDef> defs = thesisMuscleDefs();
  for (const MuscleDef& d : defs)
    if (d.name == name) return d;
  throw std::runtime_error("no muscle " + name);
}

const Head& builtInHead() {
  static const Head head = loadDefaultHead();
  return head;
}

// Each skin vertex is tied at most once per muscle (no two springs pull it towards different
// places), only where the muscle lies beneath it, never at the origin, and the stiffness grows
// towards the insertion as the profile says.
TEST(MuscleCoupling, EachSkinVertexOverTheMuscleIsTiedOnceToThePointBelowIt) {
  const CoupledMuscle m = coupleMuscle(thesisMuscle("zygomaticus_major_left"), builtInHead());
  ASSERT_FALSE(m.springs.empty());
  std::map<int, int> tied;
  const VecX area = lumpedVertexAreas(builtInHead().mesh.V, builtInHead().mesh.F);
  double nearInsertion = 0.0, inBelly = 0.0;
  int nInsertion = 0, nBelly = 0;
  for (const auto& s : m.springs) {
    ++tied[s.skin];
    EXPECT_GT(s.t, CouplingProfile{}.originEnd);
    EXPECT_GT(s.stiffness, 0.0);
    ASSERT_EQ(s.nodes.size(), 3u);
    double sum = 0.0;
    for (double w : s.weights) {
      EXPECT_GE(w, -1e-12);
      sum += w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    const double perArea = s.stiffness * s.depth / area(s.skin);  // G(t)·fade: the profile's G
    if (s.t > 0.9) nearInsertion += perArea, ++nInsertion;
    if (s.t > 0.35 && s.t < 0.6) inBelly += perArea, ++nBelly;
  }
  for (const auto& [vertex, count] : tied) EXPECT_EQ(count, 1) << "skin vertex " << vertex;
  ASSERT_GT(nInsertion, 0);
  ASSERT_GT(nBelly, 0);
  EXPECT_GT(nearInsertion / nInsertion, 10.0 * inBelly / nBelly) << "the insertion holds the skin far more than the belly";
}

// The load is the coupling stiffness times the muscle's displacement below the vertex: linear in
// the muscle's shape, and K_c is diagonal.
TEST(MuscleCoupling, LoadIsStiffnessTimesTheMuscleDisplacementBelow) {
  const Head& head = builtInHead();
  const CoupledMuscle m = coupleMuscle(thesisMuscle("depressor_anguli_oris_right"), head);
  const MatX3 f = couplingLoad(m, head.mesh.vertexCount());
  std::vector<Triplet> triplets;
  addCouplingStiffness(m, triplets);
  for (const Triplet& t : triplets) EXPECT_EQ(t.row(), t.col());
  for (const auto& s : m.springs) {
    const Vec3 expected = s.stiffness * s.muscleDisplacement(m.fullShape);
    EXPECT_LE((Vec3(f.row(s.skin)) - expected).norm(), 1e-12 * (1.0 + expected.norm())) << "vertex " << s.skin;
  }
  // The insertion moves towards the origin, so the load on the skin over it does too.
  const Vec3 towardsOrigin = (m.muscle.originPoint - m.muscle.insertionPoint).normalized();
  Vec3 total = Vec3::Zero();
  for (const auto& s : m.springs)
    if (s.t > 0.8) total += f.row(s.skin).transpose();
  EXPECT_GT(total.normalized().dot(towardsOrigin), 0.8);
}

// The lip's body keeps its volume (docs/muscles.md, "The lip's body"): the mouth's ring shortens its
// fibres by σ along the lip and draws the lip's axis in, while each lip's cross-section, not squeezed
// across by fibres that pull along themselves, grows in height by 1/√(1 − σ) about its own axis
// (the lip's area grown by 1/(1 − σ) alike in height and thickness: length × area kept). Without
// the lip's body the ring draws every node in by σ: the height shrinks to 1 − σ.
TEST(MuscleCoupling, TheLipsBodyGrowsInHeightAboutItsOwnAxisAsTheRingShortens) {
  const Head& head = builtInHead();
  const Vec3 y = head.frame().axes.col(1);
  for (const char* name : {"orbicularis_oris_upper", "orbicularis_oris_lower"}) {
    MuscleDef def;
    for (const MuscleDef& d : faceMuscleDefs())
      if (d.name == name) def = d;
    ASSERT_TRUE(def.isRing() && def.ring.lipBody) << name;
    const double sigma = def.ring.shortening;
    for (const bool body : {true, false}) {
      def.ring.lipBody = body;
      const CoupledMuscle m = coupleMuscle(def, head);
      const MatX3& V = m.muscle.mesh.V;
      const int k = def.ringNodes, stations = static_cast<int>(V.rows()) / k;
      double worst = 0.0, heightRatio = 0.0;
      for (int s = 0; s < stations; ++s) {
        Vec3 axis = Vec3::Zero(), moved = Vec3::Zero();
        for (int j = 0; j < k; ++j) axis += Vec3(V.row(s * k + j)) / k, moved += Vec3((V + m.fullShape).row(s * k + j)) / k;
        double before = 0.0, after = 0.0;  // the station's height: its nodes' vertical spread about the axis
        for (int j = 0; j < k; ++j) {
          before = std::max(before, std::abs((Vec3(V.row(s * k + j)) - axis).dot(y)));
          after = std::max(after, std::abs((Vec3((V + m.fullShape).row(s * k + j)) - moved).dot(y)));
        }
        heightRatio = after / before;
        worst = std::max(worst, std::abs(heightRatio - (body ? 1.0 / std::sqrt(1.0 - sigma) : 1.0 - sigma)));
      }
      RecordProperty(std::string(name) + (body ? "_height_ratio" : "_height_ratio_without_body"), std::to_string(heightRatio));
      EXPECT_LT(worst, 1e-9) << name << (body ? " with" : " without") << " the lip's body";
      // The axis still moves as the ring: in and forward, the mouth's corners towards each other.
      const Vec3 c = m.muscle.ringCentre;
      const Vec3 end = V.row(0), endMoved = (V + m.fullShape).row(0);
      EXPECT_LT((endMoved - c).norm(), (end - c).norm()) << name;
    }
  }
}

// The column's volume (tissue_attachment.h, columnVolumeStiffness) on a flat sheet in the x–y plane
// (normal +z), h = 0.4 cm: a uniform compression ε along x that lifts the skin by h ε keeps the
// column's volume and costs nothing; the same compression without the lift costs Σ κ (h ε)², a
// push along the normal alone Σ κ δ², a slide along the sheet nothing (exact: the energy is
// quadratic, ½uᵀKu).
TEST(ColumnVolume, AUniformCompressionCostsNothingOnlyWhenTheSkinRisesByTheColumnsThickening) {
  const int m = 7;  // m × m vertices, 0.3 cm apart
  MatX3 V(m * m, 3);
  for (int r = 0; r < m; ++r)
    for (int c = 0; c < m; ++c) V.row(r * m + c) << 0.3 * c, 0.3 * r, 0.0;
  MatX3i F(2 * (m - 1) * (m - 1), 3);
  int t = 0;
  for (int r = 0; r + 1 < m; ++r)
    for (int c = 0; c + 1 < m; ++c) {
      const int a = r * m + c;
      F.row(t++) << a, a + 1, a + m + 1;
      F.row(t++) << a, a + m + 1, a + m;
    }
  const VecX area = lumpedVertexAreas(V, F);
  const VecX depth = VecX::Constant(m * m, 0.4);
  VecX kappa = 3e6 * area;
  kappa(0) = 0.0;  // a vertex outside the region has no row
  const SparseMat K = columnVolumeStiffness(V, F, depth, area, kappa);
  ASSERT_EQ(K.rows(), 3 * m * m);
  EXPECT_LT((SparseMat(K.transpose()) - K).norm(), 1e-9 * K.norm());
  const double eps = 0.1, delta = 0.05;
  auto energy = [&](auto field) {
    VecX u(3 * m * m);
    for (int v = 0; v < m * m; ++v) u.segment<3>(3 * v) = field(Vec3(V.row(v)));
    return 0.5 * u.dot(K * u);
  };
  const double sumKappa = kappa.sum();
  EXPECT_NEAR(energy([&](const Vec3& p) { return Vec3(-eps * p.x(), 0.0, 0.4 * eps); }), 0.0, 1e-9 * sumKappa);
  EXPECT_NEAR(energy([&](const Vec3& p) { return Vec3(-eps * p.x(), 0.0, 0.0); }), 0.5 * sumKappa * std::pow(0.4 * eps, 2),
              1e-9 * sumKappa);
  EXPECT_NEAR(energy([&](const Vec3&) { return Vec3(0.0, 0.0, delta); }), 0.5 * sumKappa * delta * delta, 1e-9 * sumKappa);
  EXPECT_NEAR(energy([&](const Vec3&) { return Vec3(0.2, -0.1, 0.0); }), 0.0, 1e-9 * sumKappa);
}

// A relaxed muscle follows the skin along its shape by a small motion about the rest (the release,
// docs/anatomical_model.md, "Relaxed muscles follow the skin"), so a lip's ring is released along the
// tangent of the lip body's law at rest: per unit of the ring's shortening ε the lip's height grows by
// ε/2 (1/√(1 − ε) − 1 → ε/2), where the active shape at a = 1 carries the finite 1/√(1 − σ) − 1 of
// σ = 0.45 (0.35, 1.55 times the tangent's 0.225). The in-plane part is the active shape's. A hoop's
// squeeze ε varies along its band, and its release follows the same tangent with the local ε.
TEST(MuscleCoupling, ARelaxedLipIsReleasedAlongTheTangentOfItsBodysLaw) {
  const Head& head = builtInHead();
  const Vec3 y = head.frame().axes.col(1);
  for (const MuscleDef& def : faceMuscleDefs()) {
    if (!def.isRing() || !def.ring.lipBody) continue;
    const double sigma = def.ring.shortening;
    const CoupledMuscle m = coupleMuscle(def, head);
    ASSERT_EQ(m.releaseShape.rows(), m.fullShape.rows()) << def.name;
    const MatX3& V = m.muscle.mesh.V;
    const int k = def.ringNodes, stations = static_cast<int>(V.rows()) / k;
    double worst = 0.0;
    for (int s = 0; s < stations; ++s) {
      Vec3 axis = Vec3::Zero(), moved = Vec3::Zero();
      for (int j = 0; j < k; ++j) axis += Vec3(V.row(s * k + j)) / k, moved += Vec3((V + m.releaseShape).row(s * k + j)) / k;
      double before = 0.0, after = 0.0;
      for (int j = 0; j < k; ++j) {
        before = std::max(before, std::abs((Vec3(V.row(s * k + j)) - axis).dot(y)));
        after = std::max(after, std::abs((Vec3((V + m.releaseShape).row(s * k + j)) - moved).dot(y)));
      }
      // A hoop (the lower lip's marginal part) squeezes the lip by ε = σ·4ξ(1 − ξ) at its place ξ
      // along the band, nothing at the held ends; every other lip ring by σ all along.
      const double xi = static_cast<double>(s) / static_cast<double>(stations - 1);
      const double eps = def.ring.hoop ? sigma * 4.0 * xi * (1.0 - xi) : sigma;
      worst = std::max(worst, std::abs(after / before - (1.0 + 0.5 * eps)));
      // The axis moves as the active shape's: the release differs only in the lip's height.
      for (int j = 0; j < k; ++j) {
        const Vec3 d = (m.releaseShape - m.fullShape).row(s * k + j);
        EXPECT_LT((d - d.dot(y) * y).norm(), 1e-12) << def.name;
      }
    }
    EXPECT_LT(worst, 1e-9) << def.name;
  }
  // A ring without a lip's body and a linear muscle are released along their shape itself.
  for (const MuscleDef& def : faceMuscleDefs())
    if (def.name == "orbicularis_oculi_orbital_left" || def.name == "zygomaticus_major_left")
      EXPECT_EQ(coupleMuscle(def, head).releaseShape.rows(), 0) << def.name;
}

}  // namespace
}  // namespace myo
