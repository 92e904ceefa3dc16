// The skin's response setting (AnatomicalSettings::response, the scene's numerics.response;
// docs/live.md, "Lag") on the built-in head's whole face: `follow` settles exactly where `dynamic`
// does (rings, the jaw, contact, a turned head, warped modes too), keeps the secondary motion of a
// head turn, and has the skin at its settled shape after the first step where `dynamic` trails it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/io/scene_face.h"
#include "support/basis_cache.h"

namespace myo {
namespace {

// The scene `text` with every "RESPONSE" replaced by `response`, built and ready to play.
std::unique_ptr<ScenePlayer> player(std::string text, const std::string& response) {
  for (size_t at; (at = text.find("RESPONSE")) != std::string::npos;) text.replace(at, 8, response);
  SceneDesc scene = parseScene(text, "follow.json");
  std::shared_ptr<const FaceSystem> face = buildSceneFace(scene, test::sharedBasisCache());
  return std::make_unique<ScenePlayer>(scene, face);
}

const AnatomicalSimulator& anatomical(ScenePlayer& p) { return dynamic_cast<const AnatomicalSimulator&>(p.simulator()); }

std::string sci(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}

// How far u has come towards `settled`: its component along it, ⟨u, s⟩/⟨s, s⟩ (1 = there).
double fraction(const MatX3& u, const MatX3& settled) {
  return (u.array() * settled.array()).sum() / settled.squaredNorm();
}

// Several muscles of the whole face at once, two of them rings (the lower lip's, the right
// palpebral), the jaw open 10° (the lips on the teeth: contact acts), the head pitched 30° (a
// gravity load): 1.2 s from rest end at the same shape to 1e-6 cm whichever the response (5× the
// skin's mass damping, on which the fixed point does not depend, settles them in that time).
TEST(FollowResponse, SettlesWhereDynamicDoes) {
  const std::string text = R"({"model": "anatomical", "duration": 1.2, "fps": 30, "numerics": {"response": "RESPONSE"},
    "skin": {"damping_mass": 40},
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 1}],
      "orbicularis_oris_lower": [{"t": 0, "value": 0.6}], "orbicularis_oculi_palpebral_right": [{"t": 0, "value": 0.5}],
      "depressor_anguli_oris_right": [{"t": 0, "value": 0.7}], "frontalis_medial_left": [{"t": 0, "value": 0.4}]},
    "jaw": {"open": [{"t": 0, "value": 10}]}, "head_pose": [{"t": 0, "value": [30, 0, 0]}]}})";
  MatX3 u[2], placed[2];
  double early[2];
  int i = 0;
  for (const char* response : {"dynamic", "follow"}) {
    auto p = player(text, response);
    ASSERT_EQ(anatomical(*p).stepper().response(), i ? SkinResponse::Follow : SkinResponse::Dynamic);
    ASSERT_TRUE(p->playTo(0.05));
    const MatX3 at50ms = p->simulator().skinDisplacement();
    ASSERT_TRUE(p->playTo(1.2));
    u[i] = p->simulator().skinDisplacement();
    p->simulator().skinPositions(placed[i]);
    early[i] = fraction(at50ms, u[i]);
    ++i;
  }
  const double diff = (u[1] - u[0]).cwiseAbs().maxCoeff(), placedDiff = (placed[1] - placed[0]).cwiseAbs().maxCoeff();
  RecordProperty("settled_difference_cm", sci(diff));
  RecordProperty("fraction_at_50ms_dynamic_follow", sci(early[0]) + " / " + sci(early[1]));
  EXPECT_GT(u[0].cwiseAbs().maxCoeff(), 0.1);  // the face moved (> 1 mm)
  EXPECT_LT(diff, 1e-6);
  EXPECT_LT(placedDiff, 1e-6);
  // And the two got there differently: at 50 ms follow is nearer the settled shape.
  EXPECT_GT(early[1], early[0] + 0.1);
}

// The same with modal warping: the centre is the linear activation response, the warp's correction
// steps dynamically (Φᵀ R(Ψq)ᵀ F − Λc), so the fixed point is the warped dynamic one. (A warped step
// reads the whole basis: 10 modes and 5× the damping keep the test short; the fixed point does not
// depend on either.)
TEST(FollowResponse, SettlesWhereDynamicDoesWithWarping) {
  const std::string text = R"({"model": "anatomical", "duration": 1, "fps": 30, "contact": "off", "muscles": {"library": "builtin"},
    "skin": {"damping_mass": 40},
    "numerics": {"response": "RESPONSE", "warping": true, "skin_modes": 10},
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0.5}],
      "orbicularis_oris_upper": [{"t": 0, "value": 0.3}]}, "head_pose": [{"t": 0, "value": [0, 0, 10]}]}})";
  MatX3 u[2];
  int i = 0;
  for (const char* response : {"dynamic", "follow"}) {
    auto p = player(text, response);
    ASSERT_TRUE(p->playTo(1.0));
    u[i++] = p->simulator().skinDisplacement();
  }
  EXPECT_GT(u[0].cwiseAbs().maxCoeff(), 0.1);
  EXPECT_LT((u[1] - u[0]).cwiseAbs().maxCoeff(), 1e-6);
}

// A nod (pitch 0 → 40° over 0.15 s) with a smile held: the secondary motion, the skin's deviation
// from the static shape of the current loads, is follow's as dynamic's (within 10 % over the whole
// motion), not taken away: only the activations' response is taken at once.
TEST(FollowResponse, KeepsAHeadTurnsSecondaryMotion) {
  const std::string text = R"({"model": "anatomical", "duration": 2.6, "fps": 30, "contact": "off", "numerics": {"response": "RESPONSE"},
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0.6}], "zygomaticus_major_right": [{"t": 0, "value": 0.6}]},
    "head_pose": [{"t": 0, "value": [0, 0, 0]}, {"t": 2.0, "value": [0, 0, 0], "interp": "smooth"}, {"t": 2.1, "value": [60, 0, 0]}]}})";
  std::vector<MatX3> deviation[2];
  int i = 0;
  for (const char* response : {"dynamic", "follow"}) {
    auto p = player(text, response);
    const auto& face = dynamic_cast<const AnatomicalFace&>(p->model());
    ASSERT_TRUE(p->playTo(1.98));
    while (p->time() < 2.6 - 1e-9) {
      for (int k = 0; k < 3; ++k) p->step();
      const SettledSkin s = face.skin().settle(anatomical(*p).loads(), false);
      deviation[i].push_back(p->simulator().skinDisplacement() - s.u);
    }
    ++i;
  }
  ASSERT_EQ(deviation[0].size(), deviation[1].size());
  double largest = 0.0, apart = 0.0;
  for (size_t k = 0; k < deviation[0].size(); ++k) {
    largest = std::max(largest, deviation[0][k].cwiseAbs().maxCoeff());
    apart = std::max(apart, (deviation[1][k] - deviation[0][k]).cwiseAbs().maxCoeff());
  }
  RecordProperty("secondary_motion_cm_dynamic", sci(largest));
  RecordProperty("follow_minus_dynamic_cm", sci(apart));
  EXPECT_GT(largest, 0.01);  // the nod moves the skin by more than 0.1 mm beyond its static shape
  EXPECT_LT(apart, 0.1 * largest);
}

// A step of the zygomaticus 0 → 1 at t = 0 (contact on: the lips meet the teeth): with follow the
// skin has passed half its settled shape (the static solve's, with contact) after the first step;
// with dynamic it has not.
TEST(FollowResponse, TheSkinIsAtItsShapeAfterTheFirstStep) {
  const std::string text = R"({"model": "anatomical", "duration": 0.1, "fps": 30, "numerics": {"response": "RESPONSE"},
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 1}]}}})";
  double first[2];
  int i = 0;
  for (const char* response : {"dynamic", "follow"}) {
    auto p = player(text, response);
    p->step();
    const auto& skin = dynamic_cast<const AnatomicalFace&>(p->model()).skin();
    const SettledSkin settled = skin.settle(anatomical(*p).loads(), false);
    ASSERT_TRUE(settled.converged);
    first[i++] = fraction(p->simulator().skinDisplacement(), settled.u);
  }
  RecordProperty("fraction_after_one_step_dynamic_follow", sci(first[0]) + " / " + sci(first[1]));
  EXPECT_LT(first[0], 0.5);
  EXPECT_GT(first[1], 0.5);
}

// Switching at run time keeps the displacement (Follow takes the levels' response as its centre).
TEST(FollowResponse, ASwitchKeepsTheShape) {
  const std::string text = R"({"model": "anatomical", "duration": 1, "fps": 30, "contact": "off", "muscles": {"library": "builtin"},
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 1}]}}})";
  SceneDesc scene = parseScene(text, "switch.json");
  auto face = std::dynamic_pointer_cast<const AnatomicalFace>(buildSceneFace(scene, test::sharedBasisCache()));
  AnatomicalStepper stepper(face->skinPtr());
  SkinLoads loads;
  loads.activations = VecX::Zero(face->muscleCount());
  loads.activations(face->muscleIndex("zygomaticus_major_left")) = 1.0;
  loads.gravity = face->skin().restGravity();
  for (int k = 0; k < 5; ++k) stepper.step(loads);
  const MatX3 before = stepper.displacement();
  stepper.setResponse(SkinResponse::Follow);
  EXPECT_EQ((stepper.displacement() - before).cwiseAbs().maxCoeff(), 0.0);
  stepper.step(loads);  // the levels jump to the targets: the skin to their shape
  EXPECT_GT(fraction(stepper.displacement(), face->skin().settle(loads, false).u), 0.99);
}

}  // namespace
}  // namespace myo
