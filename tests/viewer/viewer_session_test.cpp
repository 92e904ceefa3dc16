// The viewer's logic without a window: sliders and their link, the fixed-dt accumulator, the
// timeline (play, seek), the mouse drag, authoring (keys, save, export), scripts.
#include <gtest/gtest.h>

#include <cmath>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/io/live_packets.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/scene_face.h"
#include "support/free_vertex.h"
#include "viewer_script.h"
#include "viewer_session.h"

namespace myo::viewer {
namespace {

namespace fs = std::filesystem;

SceneDesc smallScene() {
  SceneDesc scene = parseScene(R"({
    "name": "viewer_test",
    "model": "thesis",
    "muscles": {"use": ["zygomaticus_major_left", "zygomaticus_major_right", "depressor_anguli_oris_left"]},
    "numerics": {"skin_modes": 12},
    "duration": 0.5, "fps": 20,
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.25, "value": 1}]}}
  })");
  return scene;
}

ViewerSession& session() {  // built once: the eigen-solves are the slow part
  static ViewerSession s(smallScene(), nullptr);
  return s;
}

fs::path sessionScratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("myo_viewer_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

TEST(ViewerSession, TheLinkMovesTheMirrorMuscleAndSlidersClamp) {
  ViewerSession& s = session();
  s.resetSliders();
  const int left = s.model().muscleIndex("zygomaticus_major_left");
  const int right = s.model().muscleIndex("zygomaticus_major_right");
  const int dao = s.model().muscleIndex("depressor_anguli_oris_left");
  EXPECT_EQ(s.mirrorOf(left), right);
  EXPECT_EQ(s.mirrorOf(dao), -1);  // its right twin is not in this scene
  // The viewer skips the load-participation diagnostic (a factorization per channel at start-up).
  for (const SkinChannel& ch : s.thesisModel()->channels()) EXPECT_EQ(ch.loadParticipation, -1.0) << ch.name;
  EXPECT_EQ(s.thesisModel()->channels().back().name, "mouse");
  s.linked = true;
  s.setSlider(left, 0.7);
  EXPECT_DOUBLE_EQ(s.slider(right), 0.7);
  s.linked = false;
  s.setSlider(right, -0.2);
  EXPECT_DOUBLE_EQ(s.slider(left), 0.7);
  s.takeWarnings();
  s.setSlider(left, 4.0);
  EXPECT_EQ(s.slider(left), 1.0);
  const std::vector<std::string> warnings = s.takeWarnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "activation 4 of muscle 'zygomaticus_major_left' clamped to 1");
  EXPECT_THROW(s.setSlider(left, std::nan("")), InputError);
  try {
    s.setSlider("buccinator", 0.5);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("buccinator"), std::string::npos) << e.what();
  }
  s.linked = true;
  s.resetSliders();
}

TEST(ViewerSession, SimulationTimeIsIndependentOfTheFrameRate) {
  // 0.3 s in one frame or in 36 uneven frames: the same steps at the fixed dt, the same face.
  SceneDesc scene = smallScene();
  ViewerSession a(scene, nullptr), b(scene, nullptr);
  for (ViewerSession* s : {&a, &b}) s->setSlider("zygomaticus_major_left", 1.0);
  a.advance(0.3);
  for (int f = 0; f < 36; ++f) b.advance(f % 2 ? 0.3 / 36 * 1.5 : 0.3 / 36 * 0.5);  // 18 short, 18 long
  EXPECT_EQ(a.simulator().stepCount(), b.simulator().stepCount());
  EXPECT_EQ(a.simulator().stepCount(), static_cast<long long>(std::llround(0.3 / a.model().dt())));
  EXPECT_EQ((a.simulator().skinDisplacement() - b.simulator().skinDisplacement()).norm(), 0.0);
  EXPECT_GT(a.simulator().skinDisplacement().norm(), 1e-3);
}

TEST(ViewerSession, PlayingFollowsTheTimelineAndSeekReplaysIt) {
  ViewerSession& s = session();
  s.resetSliders();
  s.seek(0.0);
  s.playing = true;
  s.advance(0.2);
  EXPECT_NEAR(s.playhead(), 0.2, 1e-9);
  const int left = s.model().muscleIndex("zygomaticus_major_left");
  EXPECT_NEAR(s.slider(left), s.scene().activations.at("zygomaticus_major_left").at(s.playhead() - s.model().dt()), 1e-9);
  s.advance(1.0);  // past the end: stops there
  EXPECT_FALSE(s.playing);
  EXPECT_DOUBLE_EQ(s.playhead(), s.duration());
  // Seek = a fresh simulator played to t.
  s.seek(0.3);
  ScenePlayer fresh(s.scene(), std::shared_ptr<const FaceSystem>(&s.model(), [](const FaceSystem*) {}));
  fresh.playTo(0.3);
  EXPECT_LE((fresh.simulator().skinDisplacement() - s.simulator().skinDisplacement()).norm(), 1e-12);
  EXPECT_NEAR(s.slider(left), 1.0, 1e-12);
  s.seek(0.0);
}

TEST(ViewerSession, TheMouseDragPullsTheGrabbedSpotAndReleaseLetsGo) {
  ViewerSession& s = session();
  s.setGravity(false);  // only the drag moves the face
  s.resetSliders();
  const int cheek = test::freeLeftCheekVertex(s.model().head(), s.model().pinnedVertices());
  s.grab(cheek);
  EXPECT_TRUE(s.grabbing());
  EXPECT_EQ(s.grabbedVertex(), cheek);
  const Vec3 out = s.model().head().frame().axes.col(2);
  s.pull(2000.0 * out);
  s.advance(0.25);
  const Vec3 moved = s.simulator().skinDisplacement().row(cheek);
  EXPECT_GT(moved.dot(out), 0.05);
  EXPECT_GT(moved.dot(out), 0.5 * s.simulator().skinDisplacement().rowwise().norm().maxCoeff());
  s.release();
  s.advance(2.0);
  EXPECT_LT(s.simulator().skinDisplacement().norm(), 0.05 * moved.norm());
  EXPECT_THROW(s.grab(-1), InputError);
  // The mouse's channel pins the rim only, not the landmarks: a grip on the mouth corner moves it.
  const int corner = s.model().head().landmarks.vertex("mouth_corner_left");
  s.grab(corner);
  s.pull(2000.0 * out);
  s.advance(0.25);
  EXPECT_GT(s.simulator().skinDisplacement().row(corner).dot(out), 0.05);
  s.release();
  s.setGravity(true);
}

// The anatomical model grips the mouse drag wherever the user picks (AnatomicalStepper::grab): the
// grabbed spot moves along the pull, as with the thesis's model above; a vertex outside the skin
// is refused naming the drag and the vertex.
TEST(ViewerSession, TheAnatomicalMouseDragPullsANewlyGrabbedSpot) {
  ViewerSession s(parseScene(R"({
    "name": "viewer_anatomical_grab",
    "muscles": {"use": ["zygomaticus_major_left"]},
    "numerics": {"skin_modes": 8},
    "duration": 0.2, "fps": 20
  })"),
                  nullptr);
  ASSERT_EQ(s.model().kind(), FaceModelKind::Anatomical);  // upright: gravity is no load, only the drag moves the face
  // The contact penalty is on: a grab rebuilds it on the grabbed basis.
  EXPECT_NE(dynamic_cast<const AnatomicalFace&>(s.model()).skin().contactPenalty(), nullptr);
  const Head& head = s.model().head();
  const Vec3 out = head.frame().axes.col(2);
  for (const char* landmark : {"mouth_corner_left", "nose_tip"}) {  // a new spot, then the drag's own
    const int v = head.landmarks.vertex(landmark);
    s.grab(v);
    EXPECT_EQ(s.grabbedVertex(), v);
    s.pull(20000.0 * out);  // the skin held by the skull is stiffer than the thesis's pinned channel
    s.advance(0.25);
    const Vec3 moved = s.simulator().skinDisplacement().row(v);
    EXPECT_GT(moved.dot(out), 0.03) << landmark;  // cm (0.16 at the corner, 0.055 at the nose tip)
    EXPECT_GT(moved.normalized().dot(out), 0.8) << landmark;
    EXPECT_GT(moved.norm(), 0.5 * s.simulator().skinDisplacement().rowwise().norm().maxCoeff()) << landmark;
    s.release();
    s.advance(2.0);
    // Let go, the face falls still (the contact's constraints lie clear of the rest:
    // kRestContactClearance; at the rest they made a few µm buzz here for ever).
    EXPECT_LT(s.simulator().skinDisplacement().rowwise().norm().maxCoeff(), 1e-3 * moved.norm()) << landmark;
  }
  const int n = head.mesh.vertexCount();
  try {
    s.grab(n);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "drag 'mouse': vertex " + std::to_string(n) + " is outside [0, " + std::to_string(n) + ")");
  }
}

// Let go, a face with the contact's penalties in the step falls still as one without them: the rest
// lies strictly clear of every constraint (contact_report.h, kRestContactClearance). With an orbit
// vertex exactly on the eyeball's contact sphere at rest, the built-in head kept moving by 1–3 µm
// after a pull on the nose, however long it was stepped.
TEST(ViewerSession, LetGoTheFaceFallsStillWithTheContactOnAsWithItOff) {
  double still[2] = {0.0, 0.0};
  for (int on = 0; on < 2; ++on) {
    ViewerSession s(parseScene(std::string(R"({"name": "viewer_let_go", "muscles": {"use": ["zygomaticus_major_left"]},
      "numerics": {"skin_modes": 8}, "duration": 0.2, "fps": 20, "contact": ")") + (on ? "on" : "off") + "\"}"),
                    nullptr);
    const Head& head = s.model().head();
    s.grab(head.landmarks.vertex("nose_tip"));
    s.pull(20000.0 * head.frame().axes.col(2));
    s.advance(0.25);
    const double pulled = s.simulator().skinDisplacement().rowwise().norm().maxCoeff();
    s.release();
    s.advance(3.0);
    still[on] = s.simulator().skinDisplacement().rowwise().norm().maxCoeff();
    RecordProperty(std::string(on ? "on" : "off") + "_left_after_3s_cm", std::to_string(still[on]));
    EXPECT_GT(pulled, 0.05);
    EXPECT_LT(still[on], 1e-6) << (on ? "contact on" : "contact off");  // 3 s: the slowest mode decays
  }
}

TEST(ViewerSession, KeysFromSlidersSaveAndReloadAndExportAGlb) {
  ViewerSession s(smallScene(), nullptr);
  const fs::path dir = sessionScratch("authoring");
  s.seek(0.4);
  s.setSlider("depressor_anguli_oris_left", 0.6);
  EXPECT_EQ(s.setKeysAtPlayhead(), 3);
  s.setSlider("depressor_anguli_oris_left", 0.8);
  s.setKeysAtPlayhead();  // the key at 0.4 s is replaced, not doubled
  s.saveScene((dir / "authored.json").string());
  const SceneDesc back = readScene((dir / "authored.json").string());
  const ScalarTrack& dao = back.activations.at("depressor_anguli_oris_left");
  ASSERT_EQ(dao.keys().size(), 1u);
  EXPECT_DOUBLE_EQ(dao.keys()[0].time, 0.4);
  EXPECT_DOUBLE_EQ(dao.keys()[0].value, 0.8);
  const ScalarTrack& zyg = back.activations.at("zygomaticus_major_left");
  ASSERT_EQ(zyg.keys().size(), 3u);  // 0, 0.25 and the new 0.4
  EXPECT_DOUBLE_EQ(zyg.keys()[2].time, 0.4);
  EXPECT_FALSE(fs::exists(dir / "authored.json.tmp"));
  // It read back (so no interp on a last key, which readScene refuses), and it is what `check`
  // prints for it: a fixed point.
  EXPECT_EQ(sceneToJson(back), readWholeFile((dir / "authored.json").string()));

  const int frames = s.exportGlb((dir / "authored.glb").string());
  EXPECT_EQ(frames, 11);  // 0.5 s at 20 fps
  ASSERT_TRUE(fs::exists(dir / "authored.glb"));
  EXPECT_GT(fs::file_size(dir / "authored.glb"), 10000u);
  EXPECT_THROW(s.saveScene((dir / "missing" / "x.json").string()), InputError);
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

TEST(ViewerScript, ErrorsNameTheFileLineAndFault) {
  auto message = [](const std::string& text) {
    try {
      parseViewerScript(text, "s.txt");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("set zygomaticus_major_left 1\nfrobnicate\n"),
            "s.txt:2: unknown command 'frobnicate' (known: advance, blink, calibrate, export, grab, gravity, jaw, key, link, "
            "orbit, pause, play, probe, pull, release, reset, save, screenshot, seek, select, set, show, sliders, "
            "stiffness, view, zoom)");
  EXPECT_EQ(message("# a comment\n\nadvance\n"), "s.txt:3: 'advance' takes 1 argument, got 0");
  EXPECT_EQ(message("set zygomaticus_major_left lots\n"), "s.txt:1: 'set': 'lots' is not a finite number");
  EXPECT_EQ(message("stiffness nan\n"), "s.txt:1: 'stiffness': 'nan' is not a finite number");
  EXPECT_EQ(message("gravity maybe\n"), "s.txt:1: 'gravity': expected on or off, got 'maybe'");
  EXPECT_EQ(message("view top\n"), "s.txt:1: 'view': unknown view 'top' (use front, three-quarter or profile)");
  const auto ok = parseViewerScript("set a 0.5  # half\npull 1 2 -3e2\n", "s.txt");
  ASSERT_EQ(ok.size(), 2u);
  EXPECT_EQ(ok[0].line, 1);
  EXPECT_DOUBLE_EQ(ok[0].number(1), 0.5);
  EXPECT_DOUBLE_EQ(ok[1].number(2), -300.0);
  EXPECT_EQ(ok[1].line, 2);
  try {
    readViewerScript("/nonexistent/script.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/script.txt: cannot open the script");
  }
}

// The anatomical model in the viewer: sliders in [0, 1], the mouse grip moved anywhere, the timeline
// plays it.
TEST(ViewerSession, TheAnatomicalModelPlaysAndClampsItsSliders) {
  ViewerSession s(parseScene(R"({
    "name": "viewer_anatomical",
    "muscles": {"use": ["zygomaticus_major_left"]},
    "numerics": {"skin_modes": 4},
    "duration": 0.2, "fps": 20,
    "timeline": {"activations": {"zygomaticus_major_left": [{"t": 0, "value": 0}, {"t": 0.1, "value": 1}]}}
  })"),
                  nullptr);
  EXPECT_EQ(s.model().kind(), FaceModelKind::Anatomical);
  EXPECT_EQ(s.thesisModel(), nullptr);
  EXPECT_EQ(s.model().channelNames(), std::vector<std::string>{"skin"});
  s.setSlider(0, -0.5);
  EXPECT_EQ(s.slider(0), 0.0);
  const std::vector<std::string> warnings = s.takeWarnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "activation -0.5 of muscle 'zygomaticus_major_left' clamped to 0");
  const int nose = s.model().head().landmarks.vertex("nose_tip");
  EXPECT_NO_THROW(s.grab(nose));  // the mouse drag's own vertex
  s.release();
  const int other = nose == 0 ? 1 : 0;
  EXPECT_NO_THROW(s.grab(other));  // anywhere else: a Ritz vector computed at grab time
  EXPECT_EQ(s.grabbedVertex(), other);
  s.release();
  s.playing = true;
  s.advance(0.2);
  EXPECT_NEAR(s.slider(0), 1.0, 1e-9);  // the timeline drove the slider
  EXPECT_GT(s.simulator().skinDisplacement().rowwise().norm().maxCoeff(), 0.01);
}

// The stiffness slider on the anatomical model rebuilds the skin at skin.young_modulus = s·E₀: the
// same pull moves the mouth corner less on a stiffer skin and more on a softer one; the sliders,
// gravity switch and playhead are kept, the grab let go, and the scene carries the new modulus.
TEST(ViewerSession, TheAnatomicalStiffnessSliderRebuildsTheSkinAtTheScaledModulus) {
  SceneDesc scene = parseScene(R"({
    "name": "viewer_anatomical_stiffness",
    "muscles": {"use": ["zygomaticus_major_left"]},
    "numerics": {"skin_modes": 8},
    "duration": 0.5, "fps": 20
  })");
  const double e0 = scene.anatomical.skinYoungModulus;
  ViewerSession s(scene, nullptr);
  ASSERT_TRUE(s.stiffnessRebuilds());
  EXPECT_EQ(s.stiffnessScale(), 1.0);
  const int corner = s.model().head().landmarks.vertex("mouth_corner_left");
  const Vec3 out = s.model().head().frame().axes.col(2);
  auto pulled = [&] {  // the corner's displacement along a steady pull, once settled
    s.grab(corner);
    s.pull(20000.0 * out);
    s.advance(1.5);
    const double along = s.simulator().skinDisplacement().row(corner).dot(out);
    s.release();
    s.advance(3.0);
    return along;
  };
  const double base = pulled();
  s.setSlider(0, 0.3);
  s.seek(0.25);
  s.grab(corner);
  EXPECT_GT(s.setStiffnessScale(4.0), 0.0);  // the rebuild's wall time
  EXPECT_FALSE(s.grabbing());
  EXPECT_DOUBLE_EQ(s.stiffnessScale(), 4.0);
  EXPECT_DOUBLE_EQ(s.scene().anatomical.skinYoungModulus, 4.0 * e0);
  EXPECT_DOUBLE_EQ(s.slider(0), 0.3);
  EXPECT_DOUBLE_EQ(s.playhead(), 0.25);
  s.setSlider(0, 0.0);
  const double stiff = pulled();
  s.setStiffnessScale(0.5);
  EXPECT_DOUBLE_EQ(s.scene().anatomical.skinYoungModulus, 0.5 * e0);  // of E₀, not of the last scale
  const double soft = pulled();
  RecordProperty("corner_cm_x1_x4_x0.5", std::to_string(base) + " " + std::to_string(stiff) + " " + std::to_string(soft));
  EXPECT_GT(base, 0.03);
  // Not 1/s: the skull's attachment and the muscles' couplings do not scale with the skin.
  EXPECT_LT(stiff, 0.75 * base);  // 0.60 of it (measured)
  EXPECT_GT(soft, 1.1 * base);    // 1.19 of it
  EXPECT_THROW(s.setStiffnessScale(0.0), InputError);
  EXPECT_THROW(s.setStiffnessScale(std::nan("")), InputError);
  EXPECT_DOUBLE_EQ(s.stiffnessScale(), 0.5);  // refused: nothing rebuilt
}

// The jaw's sliders (anatomical model): the chin follows the opening, values outside the jaw's
// ranges are clamped with a warning naming them, keys go on the jaw's tracks and a timeline that
// plays them moves the sliders; the thesis model refuses them, naming the model.
TEST(ViewerSession, ABlinkClosesAndReopensThePalpebralMusclesOverSliderAndTrack) {
  ViewerSession s(parseScene(R"({
    "name": "viewer_blink",
    "muscles": {"library": "face", "use": ["orbicularis_oculi_palpebral_left", "orbicularis_oculi_palpebral_right",
                                             "zygomaticus_major_left"]},
    "numerics": {"skin_modes": 4},
    "duration": 1.0, "fps": 20
  })"),
                  nullptr);
  const int left = s.model().muscleIndex("orbicularis_oculi_palpebral_left");
  const int right = s.model().muscleIndex("orbicularis_oculi_palpebral_right");
  s.linked = false;
  s.setSlider(right, 0.3);
  EXPECT_FALSE(s.blinking());
  s.blink();
  ASSERT_TRUE(s.blinking());
  s.advance(0.05);  // half way down
  EXPECT_NEAR(s.simulator().activation(left), 0.5, 0.05);
  EXPECT_NEAR(s.simulator().activation(right), 0.5, 0.05);  // the blink lifts a slider below it
  s.advance(0.075);  // closed
  EXPECT_DOUBLE_EQ(s.simulator().activation(left), 1.0);
  s.advance(0.5);  // over: back to the sliders
  EXPECT_FALSE(s.blinking());
  s.advance(0.01);
  EXPECT_EQ(s.simulator().activation(left), 0.0);
  EXPECT_EQ(s.simulator().activation(right), 0.3);
  EXPECT_EQ(s.slider(left), 0.0);  // the blink never moved a slider

  // A library without the palpebral part cannot blink, and says how to get it.
  ViewerSession thesis(parseScene(R"({"name": "no_lids", "muscles": {"use": ["zygomaticus_major_left"]},
                                      "numerics": {"skin_modes": 4}, "duration": 0.2, "fps": 20})"),
                       nullptr);
  try {
    thesis.blink();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "blink: the muscle library has no orbicularis_oculi_palpebral muscle (use \"muscles\": {\"library\": "
              "\"face\"})");
  }
}

TEST(ViewerSession, TheJawSlidersOpenTheMouthKeyAndFollowTheTimeline) {
  ViewerSession s(parseScene(R"({
    "name": "viewer_jaw",
    "muscles": {"use": ["zygomaticus_major_left"]},
    "numerics": {"skin_modes": 4},
    "duration": 0.4, "fps": 20
  })"),
                  nullptr);
  ASSERT_TRUE(s.hasJaw());
  const int chin = s.model().head().landmarks.vertex("chin_menton");
  const Vec3 up = s.model().head().frame().axes.col(1);
  const double rest = up.dot(s.simulator().skinPositions().row(chin).transpose());
  s.setJawSlider({20.0, 0.0, 0.0});
  s.advance(0.1);
  const double open = up.dot(s.simulator().skinPositions().row(chin).transpose());
  RecordProperty("chin_down_cm_at_20_degrees", std::to_string(rest - open));
  EXPECT_GT(rest - open, 0.5);  // cm: the chin drops with the mandible

  s.setJawSlider({55.0, 2.0, -3.0});
  EXPECT_EQ(s.jawSlider().openDeg, kJawOpenMaxDeg);
  EXPECT_EQ(s.jawSlider().forwardCm, kJawForwardMaxCm);
  EXPECT_EQ(s.jawSlider().lateralCm, -kJawLateralMaxCm);
  const std::vector<std::string> warnings = s.takeWarnings();
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(warnings[0], "the jaw's opening 55 degrees clamped to 40");
  EXPECT_EQ(warnings[2], "the jaw's lateral shift -3 cm clamped to -1.5");
  EXPECT_THROW(s.setJawSlider({std::nan(""), 0.0, 0.0}), InputError);

  // Keys at 0 (closed) and at 0.4 s (open 10°): playing from the start, the sliders follow.
  s.setJawSlider({0.0, 0.0, 0.0});
  EXPECT_EQ(s.setKeysAtPlayhead(), s.muscleCount());  // at rest and no jaw track: no jaw keys
  s.setJawSlider({10.0, 0.0, 0.0});
  s.seek(0.4);
  EXPECT_EQ(s.setKeysAtPlayhead(), s.muscleCount() + 3);
  ASSERT_EQ(s.scene().jawOpen.keys().size(), 1u);
  s.setJawSlider({0.0, 0.0, 0.0});
  s.seek(0.0);
  s.playing = true;
  s.advance(0.4);
  EXPECT_NEAR(s.jawSlider().openDeg, 10.0, 1e-9);
  s.resetSliders();
  EXPECT_TRUE(s.jawSlider().isZero());

  ViewerSession thesis(parseScene(R"({"model": "thesis", "muscles": {"use": ["zygomaticus_major_left"]}, "duration": 0.1, "fps": 20})"),
                       nullptr);
  EXPECT_FALSE(thesis.hasJaw());
  try {
    thesis.setJawSlider({5.0, 0.0, 0.0});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "the jaw needs \"model\": \"anatomical\"; the thesis model has no jaw");
  }
}

// --live: a frame from the stream drives the muscles it maps (their sliders show it, the simulator
// holds it), the status counts it and times it (arrival → positions ready, on the injected clock),
// and a silent stream eases the face back to neutral.
TEST(ViewerSession, ALiveFrameDrivesTheSlidersAndTheStatusCountsIt) {
  ViewerSession s(smallScene(), nullptr);  // its own: listening is for good
  std::atomic<double> now{10.0};
  const LiveClock clock = [&] { return now.load(); };
  LiveSourceOptions options{LiveProtocol::LiveLink, "127.0.0.1", 0};
  options.clock = clock;
  auto source = std::make_unique<LiveSource>(options);
  LiveSource* const receiver = source.get();
  const int port = source->port();
  EXPECT_THROW(s.calibrateNeutral(), InputError);  // not live yet
  OneEuroSettings unfiltered;
  unfiltered.enabled = false;  // the values as mapped, not smoothed from the neutral start
  s.listen(std::move(source), clock, {}, unfiltered);
  ASSERT_TRUE(s.live());
  EXPECT_FALSE(s.playing);

  const int zygomaticus = s.model().muscleIndex("zygomaticus_major_left");
  LiveFrame smile;
  const auto& names = arkitNames();
  for (const char* name : {"mouthSmileLeft", "mouthSmileRight"})
    smile.weights[static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin())] = 0.8f;  // as sent
  LiveSender to("127.0.0.1", port);
  to.send(encodeLiveLinkPacket(smile, {1, 0.0f, 60, 1}));
  ASSERT_TRUE(receiver->waitForFrame(5.0));
  now = 10.004;  // the steps start 4 ms after the arrival (10.0)
  s.advance(0.1);
  // The stream's smile, mapped as `myoshell live` maps it (its LiveFaceMapper on the same scene).
  LiveFaceMapper reference(s.scene(), unfiltered);
  const MappedPerformance expected = reference.map(0.0, smile);
  const auto& mapped = reference.muscles();
  const size_t k = static_cast<size_t>(std::find(mapped.begin(), mapped.end(), "zygomaticus_major_left") - mapped.begin());
  ASSERT_LT(k, mapped.size());
  EXPECT_GT(expected.activations[k][0], 0.05);
  EXPECT_DOUBLE_EQ(s.slider(zygomaticus), expected.activations[k][0]);
  EXPECT_EQ(s.simulator().activation(zygomaticus), s.slider(zygomaticus));
  const LiveStatus st = s.liveStatus();
  EXPECT_EQ(st.protocol, LiveProtocol::LiveLink);
  EXPECT_EQ(st.port, port);
  EXPECT_EQ(st.counters.packets, 1);
  EXPECT_EQ(st.counters.taken, 1);
  EXPECT_EQ(st.counters.malformed, 0);
  ASSERT_EQ(st.latencySamples, 1);
  EXPECT_NEAR(st.latencyMs, 4.0, 1e-9);
  EXPECT_NEAR(st.packetsPerSecond, 1 / 0.004, 1e-6);  // one packet since listen() at 10.0
  EXPECT_GT(st.liveness, 0.99);
  // The smile moved the skin.
  EXPECT_GT(s.simulator().skinDisplacement().rowwise().norm().maxCoeff(), 0.01);

  const double smiled = s.slider(zygomaticus);
  now = 13.0;  // 3 s of silence: past the timeout and the ease
  s.advance(0.1);
  EXPECT_EQ(s.liveStatus().liveness, 0.0);
  EXPECT_GT(smiled, 0.0);
  EXPECT_EQ(s.slider(zygomaticus), 0.0);
  EXPECT_EQ(s.liveStatus().latencySamples, 0);  // nothing arrived in the last second
  s.calibrateNeutral(0.5);
  EXPECT_TRUE(s.liveStatus().calibrating);
  // A timeline does not play over the stream.
  s.playing = true;
  s.advance(0.05);
  EXPECT_FALSE(s.playing);
}

}  // namespace
}  // namespace myo::viewer
