#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "myoshell/anim/scene_parser.h"
#include "myoshell/core/errors.h"

namespace myo {
namespace {

std::string sceneErrorOf(const std::string& text) {
  try {
    parseScene(text, "scene.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The same scene under "model": "thesis", added last so every line and column stays where it was.
std::string thesisErrorOf(std::string text) {
  text.insert(text.rfind('}'), ", \"model\": \"thesis\"");
  return sceneErrorOf(text);
}

TEST(SceneParser, DefaultsFillAnEmptyScene) {
  const SceneDesc s = parseScene("{}", "dir/empty.json");
  EXPECT_EQ(s.name, "empty");
  EXPECT_EQ(s.head.builtin, "default");
  EXPECT_EQ(s.muscleLibrary, "face");  // the whole face under the anatomical model
  EXPECT_TRUE(s.muscles.empty());
  EXPECT_EQ(parseScene(R"({"model": "thesis"})", "t.json").muscleLibrary, "builtin");  // the thesis's eight
  EXPECT_EQ(s.model.skinModes, FaceModelSettings{}.skinModes);
  EXPECT_DOUBLE_EQ(s.duration, 1.0);
}

TEST(SceneParser, ReadsEveryPart) {
  const SceneDesc s = parseScene(R"({
    "name": "fig26",
    "model": "thesis",
    "muscles": {"use": ["zygomaticus_major_right"]},
    "skin": {"k_a": 1500, "damping_mass": 4},
    "springs": {"model": "displacement", "stiffness": 250},
    "roi_alpha": 5,
    "gravity": {"enabled": false},
    "drags": [{"name": "cheek", "landmark": "mouth_corner_right", "radius": 0.8, "pin_landmarks": false}],
    "numerics": {"dt": 0.002, "skin_modes": 12, "stepper": "semi-implicit", "precision": "double"},
    "duration": 3, "fps": 24,
    "timeline": {
      "activations": {"zygomaticus_major_right": [{"t": 0, "value": 0, "interp": "smooth"}, {"t": 1, "value": 1}]},
      "drags": {"cheek": [{"t": 0, "value": [0, 0, 0]}, {"t": 2, "value": [100, 0, 0]}]}
    }})", "s.json");
  EXPECT_EQ(s.name, "fig26");
  EXPECT_EQ(s.muscles.size(), 1u);
  EXPECT_DOUBLE_EQ(s.model.skin.kA, 1500);
  EXPECT_DOUBLE_EQ(s.model.skinDampingMass, 4);
  EXPECT_EQ(s.model.springModel, SpringModel::Displacement);
  EXPECT_DOUBLE_EQ(s.model.springStiffness, 250);
  EXPECT_DOUBLE_EQ(s.model.roiAlpha, 5);
  EXPECT_FALSE(s.model.gravity);
  ASSERT_EQ(s.drags.size(), 1u);
  EXPECT_EQ(s.drags[0].landmark, "mouth_corner_right");
  EXPECT_FALSE(s.drags[0].pinLandmarks);
  EXPECT_DOUBLE_EQ(s.model.dt, 0.002);
  EXPECT_EQ(s.model.stepper, ModalStepper::SemiImplicit);
  EXPECT_EQ(s.model.precision, ModalPrecision::Double);
  EXPECT_DOUBLE_EQ(s.activations.at("zygomaticus_major_right").at(0.5), 0.5);
  EXPECT_TRUE(s.dragForces.at("cheek").at(1.0).isApprox(Vec3(50, 0, 0)));
}

TEST(SceneParser, ErrorsNameFileLineColumnAndKeyPath) {
  EXPECT_EQ(sceneErrorOf("{\n  \"numerics\": {\"dt\": -1}\n}"), "scene.json:2:22: key 'numerics.dt': must be > 0 (got -1)");
  EXPECT_EQ(sceneErrorOf("{\n  \"numerics\": {\"dtt\": 0.1}\n}"),
            "scene.json:2:16: key 'numerics.dtt': unknown key (did you mean 'numerics.dt'?)");
  // A misspelt key is suggested its spelling among the keys of its own mapping, present or not.
  EXPECT_EQ(sceneErrorOf("{\"gravty\": {\"enabled\": false}}"),
            "scene.json:1:2: key 'gravty': unknown key (did you mean 'gravity'?)");
  EXPECT_EQ(sceneErrorOf("{\"skin\": {\"youngs_modulus\": 2e6}}"),
            "scene.json:1:11: key 'skin.youngs_modulus': unknown key (did you mean 'skin.young_modulus'?)");
  EXPECT_EQ(sceneErrorOf("{\"wobble\": 1}"), "scene.json:1:2: key 'wobble': unknown key");  // nothing close
  EXPECT_EQ(sceneErrorOf("{\"duration\": \"2\"}"), "scene.json:1:14: key 'duration': must be a number");
  EXPECT_EQ(thesisErrorOf("{\"roi_alpha\": 0.9}"), "scene.json:1:15: key 'roi_alpha': must be > 1 (got 0.9)");
  EXPECT_EQ(thesisErrorOf("{\"timeline\": {\"activations\": {\"m\": [{\"t\": 0, \"value\": 1.5}]}}}"),
            "scene.json:1:55: key 'timeline.activations.m[0].value': must lie in [-1, 1] (got 1.5)");
  EXPECT_EQ(thesisErrorOf("{\"springs\": {\"model\": \"hooke\"}}"),
            "scene.json:1:23: key 'springs.model': must be \"thesis\" or \"displacement\" (got \"hooke\")");
  EXPECT_EQ(sceneErrorOf("{\"drags\": [{\"name\": \"d\"}]}"),
            "scene.json:1:12: key 'drags[0].landmark': give exactly one of 'landmark' and 'vertex'");
  EXPECT_EQ(thesisErrorOf("{\"drags\": [{\"name\": \"d\", \"vertex\": 3, \"pin_landmarks\": 1}]}"),
            "scene.json:1:56: key 'drags[0].pin_landmarks': must be true or false");
  EXPECT_EQ(sceneErrorOf("{\"timeline\": {\"drags\": {\"nope\": []}}}"),
            "scene.json:1:25: key 'timeline.drags.nope': no drag of that name in 'drags'");
  const std::string syntax = sceneErrorOf("{\n  \"duration\": 1,,\n}");
  EXPECT_EQ(syntax.rfind("scene.json:2:", 0), 0u) << syntax;
  EXPECT_NE(syntax.find("syntax error"), std::string::npos) << syntax;
}

TEST(SceneParser, RoundTripsThroughJson) {
  const SceneDesc a = parseScene(R"({"name": "rt", "model": "thesis", "numerics": {"skin_modes": 7},
    "muscles": {"extra": [{"name": "frontalis_right", "origin": {"landmark": "right_brow_inner", "offset": [0, 0.5, 0]},
                           "insertion": {"landmark": "right_brow_inner"}}]},
    "drags": [{"name": "d", "vertex": 12, "pin_landmarks": false}],
    "timeline": {"activations": {"frontalis_right": [{"t": 0, "value": 0, "interp": "step"}, {"t": 1, "value": -0.5}]},
                 "gravity": [{"t": 0, "value": 1}, {"t": 2, "value": 0}]}})",
                                 "rt.json");
  const std::string once = sceneToJson(a);
  const SceneDesc b = parseScene(once, "rt.json");
  EXPECT_EQ(sceneToJson(b), once);
  EXPECT_EQ(b.model.skinModes, 7);
  ASSERT_EQ(b.extraMuscles.size(), 1u);
  EXPECT_TRUE(b.extraMuscles[0].origin.offset.isApprox(Vec3(0, 0.5, 0)));
  EXPECT_DOUBLE_EQ(b.activations.at("frontalis_right").at(2.0), -0.5);
  EXPECT_DOUBLE_EQ(b.gravity.at(1.0), 0.5);
  ASSERT_EQ(b.drags.size(), 1u);
  EXPECT_FALSE(b.drags[0].pinLandmarks);
}

TEST(SceneParser, InterpOnATracksLastKeyIsAnErrorAtItsPlace) {
  // interp shapes the segment from its key to the next; the last key starts none.
  EXPECT_EQ(sceneErrorOf("{\"timeline\": {\"gravity\": [{\"t\": 0, \"value\": 0}, {\"t\": 1, \"value\": 1, \"interp\": \"smooth\"}]}}"),
            "scene.json:1:80: key 'timeline.gravity[1].interp': a track's last key starts no segment ('interp' says how "
            "the value goes from its key to the next; put it on the key that starts the eased segment)");
  EXPECT_NE(sceneErrorOf("{\"timeline\": {\"drags\": {\"d\": [{\"t\": 0, \"value\": [0, 0, 0], \"interp\": \"linear\"}]}}, "
                    "\"drags\": [{\"name\": \"d\", \"vertex\": 1}]}")
                .find("key 'timeline.drags.d[0].interp': a track's last key starts no segment"),
            std::string::npos);
  // On the key that starts the segment it eases that segment: halfway along, smoothstep(0.5) = 0.5,
  // at a quarter 0.15625 (linear would give 0.25).
  const SceneDesc s = parseScene(R"({"timeline": {"gravity": [{"t": 0, "value": 0, "interp": "smooth"}, {"t": 1, "value": 1}]}})");
  EXPECT_DOUBLE_EQ(s.gravity.at(0.25), 0.15625);
}

TEST(SceneParser, PrintsWhatIsMeant) {
  // No interp on a last key, "all" for every muscle, a pin file only when there is one.
  SceneDesc s = parseScene(R"({"timeline": {"gravity": [{"t": 0, "value": 0, "interp": "smooth"}, {"t": 1, "value": 1}]}})");
  nlohmann::json j = nlohmann::json::parse(sceneToJson(s));
  EXPECT_EQ(j["timeline"]["gravity"][0]["interp"], "smooth");
  EXPECT_FALSE(j["timeline"]["gravity"][1].contains("interp"));
  EXPECT_EQ(j["muscles"]["use"], "all");
  EXPECT_EQ(j["head"], nlohmann::json({{"builtin", "default"}}));
  s.modelKind = FaceModelKind::Thesis;  // the pin file is the thesis model's
  s.head.obj = "h.obj";
  s.head.landmarks = "l.json";
  EXPECT_FALSE(nlohmann::json::parse(sceneToJson(s))["head"].contains("gravity_pins"));
  s.head.gravityPins = "pins.json";
  EXPECT_EQ(nlohmann::json::parse(sceneToJson(s))["head"]["gravity_pins"], "pins.json");
  // "use": "all" and the old empty list both read as every muscle.
  EXPECT_TRUE(parseScene(R"({"muscles": {"use": "all"}})").muscles.empty());
  EXPECT_TRUE(parseScene(R"({"muscles": {"use": []}})").muscles.empty());
  EXPECT_EQ(thesisErrorOf(R"({"head": {"gravity_pins": "p.json"}})"),
            "scene.json:1:27: key 'head.gravity_pins': only a head OBJ takes a pin file (the built-in head has its own pins)");
}

TEST(SceneParser, FramesCloserThanOneStepOrAShorterSceneAreErrorsNamingBothValues) {
  EXPECT_EQ(sceneErrorOf("{\"numerics\": {\"dt\": 0.01},\n \"fps\": 200}"),
            "scene.json:2:9: key 'fps': fps = 200 is above 1/dt = 100 (numerics.dt = 0.01 s): frames closer than one "
            "step would repeat; lower fps or dt");
  // Only dt written (fps 30 by default): the error sits at dt.
  EXPECT_EQ(sceneErrorOf("{\"numerics\": {\"dt\": 0.05}}"),
            "scene.json:1:21: key 'numerics.dt': fps = 30 is above 1/dt = 20 (numerics.dt = 0.05 s): frames closer than "
            "one step would repeat; lower fps or dt");
  EXPECT_EQ(sceneErrorOf("{\"duration\": 0.001}"),
            "scene.json:1:14: key 'duration': duration = 0.001 s is shorter than one step (numerics.dt = 0.00416667 s): "
            "the face would not move; lengthen duration or lower dt");
  // fps = 1/dt and duration = dt are the limits, and pass.
  EXPECT_NO_THROW(parseScene(R"({"numerics": {"dt": 0.01}, "fps": 100, "duration": 0.01})"));
  EXPECT_NO_THROW(parseScene(R"({"fps": 240})"));
}

std::string parseError(const std::string& text, const std::string& name) {
  try {
    parseScene(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneParser, RejectsUnknownMusclesOfTheBuiltInLibraryAtTheirPlace) {
  EXPECT_EQ(parseError(R"({"muscles": {"use": ["zygomaticus_major_right", "buccinator"], "library": "builtin"}})", "b.json"),
            "b.json:1:49: key 'muscles.use': unknown muscle 'buccinator' (the library has: zygomaticus_major_right, "
            "zygomaticus_major_left, corrugator_supercilii_right, corrugator_supercilii_left, "
            "depressor_labii_inferioris_right, depressor_labii_inferioris_left, depressor_anguli_oris_right, "
            "depressor_anguli_oris_left, orbicularis_oris_upper, orbicularis_oris_lower)");
  // A timeline muscle the library lacks, and one the selection leaves out.
  EXPECT_EQ(parseError("timeline:\n  activations:\n    buccinator: [{t: 0, value: 1}]\n", "u.yaml"),
            "u.yaml:3:5: key 'timeline.activations.buccinator': the scene has no muscle 'buccinator'");
  EXPECT_EQ(
      parseError(
          R"({"muscles": {"use": ["zygomaticus_major_right"]}, "timeline": {"activations": {"corrugator_supercilii_left": [{"t": 0, "value": 1}]}}})",
          "t.json"),
      "t.json:1:80: key 'timeline.activations.corrugator_supercilii_left': the scene has no muscle "
      "'corrugator_supercilii_left' (it is not in 'muscles.use' nor in 'muscles.extra')");
  // With a library file the selection is still checked against the timeline at parse time.
  EXPECT_EQ(
      parseError(R"({"muscles": {"library": "lib.json", "use": ["a"]}, "timeline": {"activations": {"b": [{"t": 0, "value": 1}]}}})",
                 "l.json"),
      "l.json:1:81: key 'timeline.activations.b': the scene has no muscle 'b' (it is not in 'muscles.use' nor in "
      "'muscles.extra')");
}

TEST(SceneParser, SceneMusclesSelectsInUseOrderThenExtras) {
  const SceneDesc s = parseScene(
      R"({"muscles": {"use": ["corrugator_supercilii_left", "zygomaticus_major_right"], "extra": [{"name": "x", "origin": {"landmark": "nose_tip"}, "insertion": {"landmark": "chin_menton"}}]}})",
      "s.json");
  const std::vector<MuscleDef> m = sceneMuscles(s, thesisMuscleDefs());
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].name, "corrugator_supercilii_left");
  EXPECT_EQ(m[1].name, "zygomaticus_major_right");
  EXPECT_EQ(m[2].name, "x");
  EXPECT_EQ(sceneMuscles(parseScene("{}", "e.json"), thesisMuscleDefs()).size(), thesisMuscleDefs().size());
}

}  // namespace
}  // namespace myo

namespace myo {
namespace {

// "model": anatomical (the default) or thesis; keys of one model are errors under the other, naming
// the model, at their place.
TEST(SceneParser, TheModelKeyAndKeysOfOneModelOnly) {
  EXPECT_EQ(parseScene("{}").modelKind, FaceModelKind::Anatomical);
  EXPECT_EQ(parseScene("{\"model\": \"thesis\"}").modelKind, FaceModelKind::Thesis);
  EXPECT_EQ(sceneErrorOf("{\"model\": \"bone\"}"),
            "scene.json:1:11: key 'model': must be \"anatomical\" or \"thesis\" (got \"bone\")");
  const std::string tail = ": only \"model\": \"thesis\" uses it (this scene's model is anatomical, the default)";
  EXPECT_EQ(sceneErrorOf("{\n  \"roi_alpha\": 5\n}"), "scene.json:2:16: key 'roi_alpha'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"springs\": {\"stiffness\": 3}}"), "scene.json:1:13: key 'springs'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"head\": {\"obj\": \"h.obj\", \"landmarks\": \"l.json\", \"gravity_pins\": \"p.json\"}}"),
            "scene.json:1:66: key 'head.gravity_pins'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"drags\": [{\"name\": \"d\", \"vertex\": 3, \"pins\": \"p.json\"}]}"),
            "scene.json:1:47: key 'drags[0].pins'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"drags\": [{\"name\": \"d\", \"vertex\": 3, \"pin_landmarks\": false}]}"),
            "scene.json:1:56: key 'drags[0].pin_landmarks'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"skin\": {\"k_a\": 100}}"), "scene.json:1:18: key 'skin.k_a'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"numerics\": {\"stepper\": \"exact\"}}"), "scene.json:1:26: key 'numerics.stepper'" + tail);
  EXPECT_EQ(sceneErrorOf("{\"muscle_material\": {\"damping_ratio\": 1}}"),
            "scene.json:1:39: key 'muscle_material.damping_ratio'" + tail);
  // Relaxing is the thesis's.
  EXPECT_EQ(sceneErrorOf("{\"timeline\": {\"activations\": {\"m\": [{\"t\": 0, \"value\": -0.5}]}}}"),
            "scene.json:1:55: key 'timeline.activations.m[0].value': must lie in [0, 1] under the anatomical model "
            "(relaxing, a < 0, needs \"model\": \"thesis\") (got -0.5)");
  // The anatomical model's own keys are errors under the thesis.
  const std::string anatomical = ": only \"model\": \"anatomical\" uses it (this scene's model is thesis)";
  EXPECT_EQ(thesisErrorOf("{\"skin\": {\"young_modulus\": 1e5}}"), "scene.json:1:28: key 'skin.young_modulus'" + anatomical);
  EXPECT_EQ(thesisErrorOf("{\"timeline\": {\"head_pose\": [{\"t\": 0, \"value\": [90, 0, 0]}]}}"),
            "scene.json:1:28: key 'timeline.head_pose'" + anatomical);
  EXPECT_EQ(thesisErrorOf("{\"skin\": {\"attachment\": \"a.json\"}}"), "scene.json:1:25: key 'skin.attachment'" + anatomical);
  EXPECT_EQ(thesisErrorOf("{\"numerics\": {\"response\": \"follow\"}}"),
            "scene.json:1:27: key 'numerics.response'" + anatomical);
}

// numerics.response (docs/live.md, "Lag"): dynamic by default, follow when asked, printed by check
// and read back; any other value an error at its place.
TEST(SceneParser, TheResponseKey) {
  EXPECT_EQ(parseScene("{}").anatomical.response, SkinResponse::Dynamic);
  const SceneDesc f = parseScene("{\"numerics\": {\"response\": \"follow\"}}");
  EXPECT_EQ(f.anatomical.response, SkinResponse::Follow);
  EXPECT_EQ(parseScene(sceneToJson(f)).anatomical.response, SkinResponse::Follow);
  EXPECT_NE(sceneToJson(parseScene("{}")).find("\"response\": \"dynamic\""), std::string::npos);
  EXPECT_EQ(sceneErrorOf("{\"numerics\": {\"response\": \"instant\"}}"),
            "scene.json:1:27: key 'numerics.response': must be \"dynamic\" or \"follow\" (got \"instant\")");
}

// A muscle written in the scene (muscles.extra) follows the scene's model: the keys only the
// thesis's calibration reads (contraction, spring_stiffness, roi_alpha) are errors under the
// anatomical model, a coupling profile under the thesis's.
TEST(SceneParser, ExtraMusclesKeysOfOneModelOnly) {
  const std::string muscle = R"({"muscles": {"extra": [{"name": "m", "origin": {"landmark": "nose_tip"}, )"
                             R"("insertion": {"landmark": "chin_menton"}, )";
  const std::string thesisOnly = ": only \"model\": \"thesis\" uses it (this scene's model is anatomical, the default)";
  EXPECT_EQ(sceneErrorOf(muscle + R"("roi_alpha": 4}]}})"), "scene.json:1:129: key 'muscles.extra[0].roi_alpha'" + thesisOnly);
  EXPECT_EQ(sceneErrorOf(muscle + R"("spring_stiffness": 40}]}})"),
            "scene.json:1:136: key 'muscles.extra[0].spring_stiffness'" + thesisOnly);
  EXPECT_EQ(sceneErrorOf(muscle + R"("contraction": 0.2}]}})"), "scene.json:1:131: key 'muscles.extra[0].contraction'" + thesisOnly);
  EXPECT_EQ(thesisErrorOf(muscle + R"("coupling": {"belly_modulus": 0}}]}})"),
            "scene.json:1:128: key 'muscles.extra[0].coupling': only \"model\": \"anatomical\" uses it (this scene's "
            "model is thesis)");
  // Each model reads its own.
  EXPECT_DOUBLE_EQ(parseScene(muscle + R"("coupling": {"insertion_modulus": 6e5}}]}})").extraMuscles[0].coupling->insertionModulus,
                   6e5);
  EXPECT_DOUBLE_EQ(parseScene(muscle + R"("roi_alpha": 4}]}, "model": "thesis"})").extraMuscles[0].roiAlpha, 4.0);
  // A profile out of order names the muscle and the field.
  EXPECT_EQ(sceneErrorOf(muscle + R"("coupling": {"origin_end": 0.4, "belly_start": 0.3}}]}})"),
            "scene.json:1:143: key 'muscles.extra[0].coupling.origin_end': origin_end (0.4) must be < belly_start (0.3) "
            "in muscle 'm'");
}

TEST(SceneParser, AttachmentAndCouplingRoundTrip) {
  const SceneDesc a = parseScene(R"({"skin": {"attachment": "lips.json"},
    "muscles": {"extra": [{"name": "m", "origin": {"landmark": "nose_tip"}, "insertion": {"landmark": "chin_menton"},
                           "coupling": {"insertion_modulus": 6e5, "origin_end": 0.1}}]}})",
                                 "an.json");
  EXPECT_EQ(a.skinAttachment, "lips.json");
  ASSERT_TRUE(a.extraMuscles[0].coupling.has_value());
  CouplingProfile expected;
  expected.insertionModulus = 6e5;
  expected.originEnd = 0.1;
  EXPECT_EQ(*a.extraMuscles[0].coupling, expected);
  const std::string once = sceneToJson(a);
  const SceneDesc b = parseScene(once, "an.json");
  EXPECT_EQ(sceneToJson(b), once);
  EXPECT_EQ(b.skinAttachment, "lips.json");
  EXPECT_EQ(*b.extraMuscles[0].coupling, expected);
  EXPECT_EQ(sceneErrorOf(R"({"skin": {"attachment": ""}})"),
            "scene.json:1:25: key 'skin.attachment': must name a file of attachment overrides");
}

TEST(SceneParser, AnatomicalKeysMapOntoItsSettingsAndRoundTrip) {
  const SceneDesc a = parseScene(R"({"name": "an",
    "skin": {"young_modulus": 5e5, "thickness": 0.2, "damping_mass": 3},
    "muscles": {"use": ["zygomaticus_major_left"], "shortening": 0.25},
    "muscle_material": {"k_b": 5e4},
    "gravity": {"acceleration": 900},
    "drags": [{"name": "d", "landmark": "nose_tip", "radius": 0.5}],
    "numerics": {"dt": 0.002, "skin_modes": 12, "warping": false},
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 1, "value": 1}]},
                 "head_pose": [{"t": 0, "value": [0, 0, 0], "interp": "smooth"}, {"t": 1, "value": [90, 0, 0]}]}})",
                                 "an.json");
  const AnatomicalSettings& s = a.anatomical;
  EXPECT_EQ(a.modelKind, FaceModelKind::Anatomical);
  EXPECT_DOUBLE_EQ(s.skinYoungModulus, 5e5);
  EXPECT_DOUBLE_EQ(s.skinThickness, 0.2);
  EXPECT_DOUBLE_EQ(s.dampingMass, 3.0);
  EXPECT_DOUBLE_EQ(s.coupling.shortening, 0.25);
  EXPECT_DOUBLE_EQ(s.coupling.muscle.kB, 5e4);
  EXPECT_DOUBLE_EQ(s.gravity, 900.0);
  EXPECT_DOUBLE_EQ(s.dt, 0.002);
  EXPECT_EQ(s.skinModes, 12);
  EXPECT_FALSE(s.warping);
  ASSERT_EQ(a.headPose.keys().size(), 2u);
  const std::string once = sceneToJson(a);
  const SceneDesc b = parseScene(once, "an.json");
  EXPECT_EQ(sceneToJson(b), once);
  EXPECT_DOUBLE_EQ(b.anatomical.skinYoungModulus, 5e5);
  EXPECT_LT(b.headPose.at(0.5).angularDistance(a.headPose.at(0.5)), 1e-15);
}

}  // namespace
}  // namespace myo

namespace myo {
namespace {

TEST(SceneParser, PerformanceKeyReadsItsOptionsAndRoundTrips) {
  const SceneDesc s = parseScene(R"({"muscles": {"library": "face"},
    "performance": {"file": "take1.csv", "input": "openface", "au_scale": 5, "min_confidence": 0.8,
                    "start": 1.5, "end": 9, "map": "m.json",
                    "filter": {"min_cutoff": 2, "beta": 0.1, "d_cutoff": 1.5}}})",
                                 "dir/s.json");
  EXPECT_EQ(s.performance.file, "take1.csv");
  ASSERT_TRUE(s.performance.read.input.has_value());
  EXPECT_EQ(*s.performance.read.input, PerformanceInput::OpenFace);
  EXPECT_EQ(s.performance.read.auScale.value_or(0.0), 5.0);
  EXPECT_DOUBLE_EQ(s.performance.read.minConfidence, 0.8);
  EXPECT_DOUBLE_EQ(s.performance.start, 1.5);
  EXPECT_DOUBLE_EQ(s.performance.end, 9.0);
  EXPECT_DOUBLE_EQ(s.performance.filter.minCutoff, 2.0);
  EXPECT_DOUBLE_EQ(s.performance.filter.beta, 0.1);
  EXPECT_DOUBLE_EQ(s.performance.filter.derivativeCutoff, 1.5);
  const SceneDesc back = parseScene(sceneToJson(s), "dir/s.json");
  EXPECT_EQ(sceneToJson(back), sceneToJson(s));
}

TEST(SceneParser, PerformanceKeyErrors) {
  EXPECT_EQ(sceneErrorOf(R"({"performance": {"input": "openface"}})"),
            "scene.json:1:17: key 'performance.file': missing required key");
  EXPECT_EQ(sceneErrorOf(R"({"performance": {"file": "a.csv", "input": "kinect"}})"),
            "scene.json:1:44: key 'performance.input': unknown performance input 'kinect' (use openface, livelink "
            "or mediapipe)");
  EXPECT_EQ(sceneErrorOf(R"({"performance": {"file": "a.csv"}, "duration": 3})"),
            "scene.json:1:48: key 'duration': comes from the performance (key 'performance'): its duration and frame "
            "rate are the scene's");
  EXPECT_EQ(sceneErrorOf(R"({"performance": {"file": "a.csv", "filter": {"beta": -1}}})"),
            "scene.json:1:54: key 'performance.filter.beta': must be ≥ 0 (got -1)");
  EXPECT_EQ(sceneErrorOf(R"({"performance": {"file": "a.csv", "start": 4, "end": 2}})"),
            "scene.json:1:54: key 'performance.end': must be > 4 (got 2)");
  EXPECT_EQ(thesisErrorOf(R"({"performance": {"file": "a.csv"}})"),
            "scene.json:1:17: key 'performance': only \"model\": \"anatomical\" uses it (this scene's model is thesis)");
}

}  // namespace
}  // namespace myo
