// A muscle's own coupling profile (MuscleDef::coupling, the library key `coupling`): it sets the
// springs' G(t) of that muscle alone; without one the model's profile applies.
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/head/head.h"
#include "myoshell/muscles/muscle_coupling.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace {

MuscleDef zygomaticus() {
  for (const MuscleDef& d : thesisMuscleDefs())
    if (d.name == "zygomaticus_major_left") return d;
  throw std::logic_error("no zygomaticus_major_left in the built-in library");
}

TEST(MuscleCouplingProfile, AStifferInsertionModulusGivesProportionallyStifferInsertionSprings) {
  const Head head = loadDefaultHead();
  MuscleDef def = zygomaticus();
  ASSERT_FALSE(def.coupling.has_value());  // the shipped library keeps the model's profile
  const CoupledMuscle base = coupleMuscle(def, head);

  // The default profile written out gives the same springs, bit for bit.
  def.coupling = CouplingProfile{};
  const CoupledMuscle same = coupleMuscle(def, head);
  ASSERT_EQ(same.springs.size(), base.springs.size());
  for (size_t k = 0; k < base.springs.size(); ++k) EXPECT_EQ(same.springs[k].stiffness, base.springs[k].stiffness);

  // Twice the insertion modulus: every spring scales by G'(t)/G(t), the skin over the insertion by nearly 2
  // (exactly 2 at t = 1), the belly's not at all.
  def.coupling->insertionModulus = 2.0 * CouplingProfile{}.insertionModulus;
  const CoupledMuscle stiff = coupleMuscle(def, head);
  ASSERT_EQ(stiff.springs.size(), base.springs.size());
  int atInsertion = 0, unchanged = 0;
  for (size_t k = 0; k < base.springs.size(); ++k) {
    const auto& a = base.springs[k];
    const auto& b = stiff.springs[k];
    ASSERT_EQ(a.skin, b.skin);
    ASSERT_EQ(a.t, b.t);
    const double ratio = def.coupling->modulus(a.t) / CouplingProfile{}.modulus(a.t);
    EXPECT_NEAR(b.stiffness / a.stiffness, ratio, 1e-12 * ratio) << "skin vertex " << a.skin << " t " << a.t;
    if (a.t >= 0.95) {  // over the insertion
      ++atInsertion;
      EXPECT_GT(b.stiffness / a.stiffness, 1.9) << "skin vertex " << a.skin << " t " << a.t;
    }
    if (a.t <= CouplingProfile{}.insertionStart) {
      ++unchanged;
      EXPECT_EQ(b.stiffness, a.stiffness);  // the belly keeps its modulus
    }
  }
  EXPECT_GT(atInsertion, 0);
  EXPECT_GT(unchanged, 0);
  // The muscle's own shape does not depend on how it is tied to the skin.
  EXPECT_EQ(stiff.fullShape, base.fullShape);
}

TEST(MuscleCouplingProfile, TheLibraryReadsItAndRefusesABadOneNamingTheMuscle) {
  const std::string head = R"({"muscles": [{"name": "zyg", "origin": {"landmark": "right_eye_outer"},
  "insertion": {"landmark": "mouth_corner_right"}, "coupling": )";
  const std::vector<MuscleDef> defs =
      parseMuscleDefs(head + R"({"insertion_modulus": 6e5, "belly_start": 0.4}}]})", "lib.json");
  ASSERT_TRUE(defs[0].coupling.has_value());
  EXPECT_DOUBLE_EQ(defs[0].coupling->insertionModulus, 6e5);
  EXPECT_DOUBLE_EQ(defs[0].coupling->bellyStart, 0.4);
  EXPECT_DOUBLE_EQ(defs[0].coupling->bellyModulus, CouplingProfile{}.bellyModulus);  // unwritten: the default
  auto errorOf = [&](const std::string& coupling) {
    try {
      parseMuscleDefs(head + coupling + "}]}", "lib.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(errorOf(R"({"origin_end": 0.4, "belly_start": 0.3})"),
            "lib.json:2:79: key 'muscles[0].coupling.origin_end': origin_end (0.4) must be < belly_start (0.3) in muscle 'zyg'");
  EXPECT_EQ(errorOf(R"({"origin_end": 0.35})"),
            "lib.json:2:79: key 'muscles[0].coupling.origin_end': origin_end (0.35) must be < belly_start (0.3) in muscle 'zyg'");
  EXPECT_EQ(errorOf(R"({"insertion_start": 0.2})"),
            "lib.json:2:84: key 'muscles[0].coupling.insertion_start': belly_start (0.3) must be ≤ insertion_start (0.2) in "
            "muscle 'zyg'");
  EXPECT_EQ(errorOf(R"({"insertion_start": 1})"),
            "lib.json:2:84: key 'muscles[0].coupling.insertion_start': must be < 1 (got 1) in muscle 'zyg'");
  EXPECT_EQ(errorOf(R"({"insertion_modulus": -3})"),
            "lib.json:2:86: key 'muscles[0].coupling.insertion_modulus': must be > 0 dyn/cm² (got -3) in muscle 'zyg'");
  EXPECT_EQ(errorOf(R"({"belly_modulus": -1})"),
            "lib.json:2:82: key 'muscles[0].coupling.belly_modulus': must be ≥ 0 dyn/cm² (got -1) in muscle 'zyg'");
  EXPECT_EQ(errorOf(R"({"belly": 1})"), "lib.json:2:65: key 'muscles[0].coupling.belly': unknown key");
  EXPECT_EQ(errorOf(R"(3)"), "lib.json:2:64: key 'muscles[0].coupling': must be an object");

  // A definition built in code is checked where it is used, naming the muscle.
  MuscleDef def = zygomaticus();
  def.coupling = CouplingProfile{};
  def.coupling->originEnd = 0.5;
  try {
    coupleMuscle(def, loadDefaultHead());
    FAIL() << "a bad profile was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "muscle 'zygomaticus_major_left': coupling: profile positions must satisfy 0 ≤ origin_end < belly_start ≤ "
              "insertion_start < 1");
  }
}

}  // namespace
}  // namespace myo
