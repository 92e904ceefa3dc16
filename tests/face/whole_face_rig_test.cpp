// The whole face against ICT's artist shapes (`myoshell fit-rig ../shared/data/ict/ict_arkit_rig.glb
// --head ../shared/data/ict --library face`, docs/fitting.md): the whole-face issue's measure, kept
// from falling back.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "myoshell/anatomy/mouth_pressure.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/fit/rig_fit.h"
#include "myoshell/fit/shape_metric.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/rig_fitting.h"
#include "myoshell/io/rig_making.h"
#include "support/basis_cache.h"
#include "support/ict.h"

namespace myo {
namespace {

// The median cosine over the reachable shapes, and over the mouth and brow shapes (the names not
// starting with jaw, eye or mouthClose), is at least 0.88 (measured 0.864 and 0.863 on 2026-11-26,
// 0.888 and 0.882 on 2026-11-29);
// the six named shapes the model makes reach 0.8, eyeSquint and mouthShrugUpper 0.75. The two it does
// not make yet (browInnerUp, mouthRollLower: docs/muscles.md) are recorded, browInnerUp kept from
// falling back.
TEST(WholeFaceIct, TheRigFitReachesTheArtistsMouthAndBrowShapes) {
  MYO_REQUIRE_SHARED_DATA();
  FitHeadOptions head;
  head.head = (test::sharedDataDir() / "ict").string();
  head.headGiven = true;
  head.library = "face";
  const RigFile& rig = test::ictRig();
  FitSettings settings;
  settings.lambda = 0.02;  // fit-rig's default
  const FittedRig fitted = fitRigShapes(rig, rigFitInputs(rig, head), head.library, settings, test::sharedBasisCache());
  std::vector<double> all, mouthAndBrow;
  std::map<std::string, double> cosine;
  for (const RigShapeFit& s : fitted.fit.shapes) {
    if (!s.reachable || !s.fit) continue;
    const double c = s.fit->metric.cosine;
    cosine[s.name] = c;
    RecordProperty(s.name + "_cosine", std::to_string(c));
    all.push_back(c);
    if (s.name.rfind("jaw", 0) != 0 && s.name.rfind("eye", 0) != 0 && s.name.rfind("mouthClose", 0) != 0)
      mouthAndBrow.push_back(c);
  }
  RecordProperty("median_reachable", std::to_string(median(all)));
  RecordProperty("median_mouth_and_brow", std::to_string(median(mouthAndBrow)));
  EXPECT_EQ(all.size(), 26u);
  EXPECT_EQ(mouthAndBrow.size(), 15u);
  EXPECT_GE(median(all), 0.88);  // the whole-face issue's bar
  EXPECT_GE(median(mouthAndBrow), 0.88);
  for (const std::string name : {"mouthSmileLeft", "mouthFrownLeft", "mouthStretchLeft", "mouthUpperUpLeft", "mouthPucker",
                                 "mouthFunnel"}) {
    ASSERT_TRUE(cosine.count(name)) << name;
    EXPECT_GE(cosine[name], 0.8) << name;
  }
  // The cheek raiser (AU6: the orbital arc fixed medially, sliding along the skin; docs/muscles.md):
  // 0.771 on 2026-11-28, 0.538 as the whole loop in the face's plane. The issue asks 0.75.
  for (const std::string name : {"eyeSquintLeft", "eyeSquintRight"}) {
    ASSERT_TRUE(cosine.count(name)) << name;
    EXPECT_GE(cosine[name], 0.75) << name;
  }
  // The upper lip raised (the lip's body growing in height about its own axis; docs/muscles.md,
  // "The lip's body"): 0.771 on 2026-11-29, 0.718 with the ring squeezing the lip across. The
  // issue asks 0.75.
  ASSERT_TRUE(cosine.count("mouthShrugUpper"));
  EXPECT_GE(cosine["mouthShrugUpper"], 0.75);
  // The lower lip rolled in: the mentalis's pad pushing the lower lip (docs/muscles.md, "The chin's
  // pad pushes the lower lip") gives the skin under it and the chin their rise, the lower lip's
  // marginal part presses its margin back onto the arch ("The marginal part rolls the lower lip
  // in"): 0.568 on 2026-12-07, 0.468 before the marginal part, 0.307 before the pad. The lip turning
  // over the incisors' edge is still missing (the issue asks 0.75).
  ASSERT_TRUE(cosine.count("mouthRollLower"));
  EXPECT_GE(cosine["mouthRollLower"], 0.56);
  // The inner brows raised (the forehead's column keeping its volume: the brow no longer sinks into
  // the head; docs/muscles.md) and the medial frontalis drawing the nose's root (its continuation
  // into the procerus): 0.716 on 2026-12-07 (fit-rig), 0.690 before, 0.672 before that. The issue
  // asks 0.75: not reached.
  ASSERT_TRUE(cosine.count("browInnerUp"));
  EXPECT_GE(cosine["browInnerUp"], 0.71);
}

// The eyes' turns are derived, never fitted (the lids follow the gaze: docs/eyelids.md): ICT's artist
// eyeLook shapes only measure them. The rig `myoshell rig --head ICT` makes with the shipped map,
// each of the eight against ICT's own by the shape metric: cosine at least 0.7 (the bar).
TEST(WholeFaceIct, TheDerivedEyeTurnsAndCheekPuffFollowTheArtists) {
  MYO_REQUIRE_SHARED_DATA();
  FitHeadOptions head;
  head.head = (test::sharedDataDir() / "ict").string();
  head.headGiven = true;
  const RigFile& artist = test::ictRig();
  const SceneInputs inputs = fitHeadInputs(head, nullptr, "rig");
  const MadeRig made = makeArkitRig(inputs, readRigMap("", inputs.muscles, "face"), test::sharedBasisCache());
  const MatX3& rest = inputs.head.mesh.V;
  for (const std::string side : {"Left", "Right"})
    for (const std::string turn : {"Up", "Down", "In", "Out"}) {
      const std::string name = "eyeLook" + turn + side;
      const auto it = std::find_if(made.settled.shapes.begin(), made.settled.shapes.end(),
                                   [&](const ArkitRigShape& s) { return s.name == name; });
      ASSERT_NE(it, made.settled.shapes.end()) << name;
      const ShapeComparison c = compareShapes(it->delta, artist.delta("eyeLook" + turn + "_" + side.substr(0, 1)), rest);  // ICT's spelling
      RecordProperty(name + "_cosine", std::to_string(c.cosine));
      RecordProperty(name + "_ratio", std::to_string(c.magnitudeRatio));
      EXPECT_GE(c.cosine, 0.7) << name;
    }
  // cheekPuff is derived too: 2 kPa of air (anatomy/mouth_pressure.h), against ICT's two halves
  // together; the cheeks move out by the 5–15 mm a cheek puff shows (measured 6.3 mm on 2026-11-28).
  const auto puff = std::find_if(made.settled.shapes.begin(), made.settled.shapes.end(),
                                 [](const ArkitRigShape& s) { return s.name == "cheekPuff"; });
  ASSERT_NE(puff, made.settled.shapes.end());
  const ShapeComparison c = compareShapes(puff->delta, artist.delta("cheekPuff_L") + artist.delta("cheekPuff_R"), rest);
  RecordProperty("cheekPuff_cosine", std::to_string(c.cosine));
  RecordProperty("cheekPuff_ratio", std::to_string(c.magnitudeRatio));
  RecordProperty("cheekPuff_peak_mm", std::to_string(10 * puff->maxDisplacementCm));
  EXPECT_GE(c.cosine, 0.7);
  const double cheeks = cheekOutwardMoveCm(inputs.head, puff->delta);
  RecordProperty("cheekPuff_cheeks_out_mm", std::to_string(10 * cheeks));
  EXPECT_GE(cheeks, 0.5);
  EXPECT_LE(cheeks, 1.5);
  // The derived lip presser (AU24) and lip suck (AU28) drive both rings of the mouth: with the lip's
  // body (docs/muscles.md, "The lip's body") the lips' inner margins at the midline stay together,
  // no farther apart than at rest (0.76 mm); a ring pushing each lip away from the mouth's line
  // parted them by 3.8 and 6.9 mm.
  const FaceFrame frame = inputs.head.frame();
  const int upper = inputs.head.landmarks.vertex("upper_lip_inner"), lower = inputs.head.landmarks.vertex("lower_lip_inner");
  auto gap = [&](const MatX3& d) { return frame.directionToFrame(Vec3((rest + d).row(upper) - (rest + d).row(lower))).y(); };
  const double restGap = gap(MatX3::Zero(rest.rows(), 3));
  for (const std::string name : {"mouthPressLeft", "mouthPressRight", "mouthRollUpper"}) {
    const auto it = std::find_if(made.settled.shapes.begin(), made.settled.shapes.end(),
                                 [&](const ArkitRigShape& s) { return s.name == name; });
    ASSERT_NE(it, made.settled.shapes.end()) << name;
    RecordProperty(name + "_lip_gap_mm", std::to_string(10 * gap(it->delta)));
    EXPECT_LE(gap(it->delta), restGap) << name;
  }
  // The derived chin raiser (AU17, both mentalis at 1): the chin's pad pushes the lower lip up
  // against the upper, which it lifts (measured 2026-11-29: the lower margin 1.5 mm up along the
  // mesh's y, 0.3 mm before; the upper 0.9 mm; the margins' gap along the face's y 0.76 mm at rest,
  // −0.01 mm after). The lips meet and the contact holds them: their margins' heights cross by no
  // more than a fraction of a millimetre, as where the derived press holds them (above: −0.17 mm).
  const auto shrug = std::find_if(made.settled.shapes.begin(), made.settled.shapes.end(),
                                  [](const ArkitRigShape& s) { return s.name == "mouthShrugLower"; });
  ASSERT_NE(shrug, made.settled.shapes.end());
  const double lowerUp = frame.directionToFrame(Vec3(shrug->delta.row(lower))).y();
  RecordProperty("mouthShrugLower_lower_lip_up_mm", std::to_string(10 * lowerUp));
  RecordProperty("mouthShrugLower_lip_gap_mm", std::to_string(10 * gap(shrug->delta)));
  EXPECT_GE(lowerUp, 0.1);
  EXPECT_LE(gap(shrug->delta), restGap);
  EXPECT_GE(gap(shrug->delta), -0.05);
}

}  // namespace
}  // namespace myo
