// Muscle–skin coupling of the anatomical model (muscles/muscle_coupling.h) on the built-in head:
// the skin over a muscle is tied to the muscle's surface point below it.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace myo
