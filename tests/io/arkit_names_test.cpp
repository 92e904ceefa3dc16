// The ARKit/ICT alias table (fit/arkit_names.h), checked against ICT's rig where it is present.
#include "myoshell/fit/arkit_names.h"

#include <gtest/gtest.h>

#include <set>

#include "myoshell/core/errors.h"
#include "myoshell/io/rig_file.h"
#include "support/test_data.h"

namespace myo {
namespace {

std::string errorOf(const std::string& name) {
  try {
    canonicalArkitName(name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ArkitNames, FiftyTwoDistinctNamesInArkitsOrder) {
  const std::vector<std::string>& names = arkitNames();
  ASSERT_EQ(names.size(), 52u);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), 52u);
  EXPECT_EQ(names.front(), "eyeBlinkLeft");
  EXPECT_EQ(names[17], "jawOpen");
  EXPECT_EQ(names.back(), "tongueOut");
}

TEST(ArkitNames, BothSpellingsRoundTrip) {
  EXPECT_EQ(canonicalArkitName("mouthSmile_L"), "mouthSmileLeft");
  EXPECT_EQ(canonicalArkitName("eyeBlink_R"), "eyeBlinkRight");
  EXPECT_EQ(canonicalArkitName("jawLeft"), "jawLeft");  // not a sided shape: one spelling
  EXPECT_EQ(ictNamesOf("mouthSmileLeft"), (std::vector<std::string>{"mouthSmile_L"}));
  EXPECT_EQ(ictNamesOf("browInnerUp"), (std::vector<std::string>{"browInnerUp_L", "browInnerUp_R"}));
  EXPECT_EQ(ictNamesOf("cheekPuff_R"), (std::vector<std::string>{"cheekPuff_L", "cheekPuff_R"}));
  for (const std::string& a : arkitNames()) {
    EXPECT_EQ(canonicalArkitName(a), a);
    for (const std::string& i : ictNamesOf(a)) EXPECT_EQ(canonicalArkitName(i), a) << i;
  }
}

// Twenty left/right pairs, each the other's mirror (fit-rig fits a pair together): the sided shapes,
// and mouthLeft/mouthRight and jawLeft/jawRight, which move the whole mouth or jaw to one side.
TEST(ArkitNames, TwentyMirrorPairsEachTheOthersTwin) {
  int pairs = 0;
  for (const std::string& a : arkitNames()) {
    const std::optional<std::string> twin = mirroredArkitName(a);
    if (!twin) {
      EXPECT_TRUE(arkitFacs(a).side.empty()) << a;
      continue;
    }
    EXPECT_NE(*twin, a);
    EXPECT_EQ(mirroredArkitName(*twin), a);
    if (!arkitFacs(a).side.empty()) EXPECT_NE(arkitFacs(a).side, arkitFacs(*twin).side) << a;
    pairs += a.ends_with("Left") ? 1 : 0;
  }
  EXPECT_EQ(pairs, 20);
  EXPECT_EQ(mirroredArkitName("mouthLeft"), "mouthRight");
  EXPECT_EQ(mirroredArkitName("jawRight"), "jawLeft");
  EXPECT_EQ(mirroredArkitName("eyeBlink_L"), "eyeBlinkRight");  // ICT's spelling
  EXPECT_FALSE(mirroredArkitName("jawOpen").has_value());
  EXPECT_FALSE(mirroredArkitName("cheekPuff_L").has_value());  // an ICT half of a midline shape
  EXPECT_THROW(mirroredArkitName("mouthSmileleft"), InputError);
}

TEST(ArkitNames, UnknownNamesListCloseMatchesOrTheValidNames) {
  EXPECT_EQ(errorOf("mouthSmileleft"), "unknown blendshape name 'mouthSmileleft' (did you mean mouthSmileLeft?)");
  EXPECT_EQ(errorOf("mouthSmile_l"), "unknown blendshape name 'mouthSmile_l' (did you mean mouthSmile_L, mouthSmile_R?)");
  const std::string far = errorOf("frown");
  EXPECT_EQ(far.rfind("unknown blendshape name 'frown' (use one of the 52 ARKit names: eyeBlinkLeft, ", 0), 0u) << far;
  EXPECT_NE(far.find(", tongueOut)"), std::string::npos) << far;
  EXPECT_FALSE(findArkitName("frown").has_value());
}

TEST(ArkitNames, EveryShapeOfIctsRigResolves) {
  MYO_REQUIRE_SHARED_DATA();
  const RigFile rig = readRig((test::sharedDataDir() / "ict" / "ict_arkit_rig.glb").string());
  ASSERT_EQ(rig.names.size(), 37u);
  std::set<std::string> arkit;
  for (const std::string& n : rig.names) arkit.insert(canonicalArkitName(n));
  EXPECT_EQ(arkit.size(), 35u);  // browInnerUp and cheekPuff are two ICT shapes each
  EXPECT_TRUE(arkit.count("browInnerUp") && arkit.count("cheekPuff") && arkit.count("mouthSmileLeft"));
}

}  // namespace
}  // namespace myo
