// The performance readers (anim/performance.h): OpenFace 2 CSV, Live Link Face CSV and MediaPipe
// JSON Lines from inline texts and small sample takes (tests/anim/performances/), the FACSvatar demo
// performance of ../shared/data/openface (skipped when absent), and every error's exact text.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/performance.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/performance_file.h"
#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

std::string errorOf(const std::string& text, const PerformanceOptions& options = {}, const std::string& name = "p.csv") {
  try {
    parsePerformance(text, name, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::vector<double> valuesOf(const Performance& p, const std::string& channel) {
  const PerformanceChannel* c = p.find(channel);
  return c ? c->values : std::vector<double>{};
}

fs::path samples() { return test::sourceDir() / "tests" / "anim" / "performances"; }

// ---- names and detection ----------------------------------------------------------------------

TEST(PerformanceInput, NamesRoundTripAndUnknownOnesAreRefused) {
  for (const PerformanceInput in : {PerformanceInput::OpenFace, PerformanceInput::LiveLink, PerformanceInput::MediaPipe})
    EXPECT_EQ(performanceInputFromString(toString(in)), in);
  EXPECT_STREQ(toString(PerformanceInput::LiveLink), "livelink");
  try {
    performanceInputFromString("faceshift");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown performance input 'faceshift' (use openface, livelink or mediapipe)");
  }
}

TEST(PerformanceInput, DetectedFromTheFirstLine) {
  EXPECT_EQ(detectPerformanceInput("frame,timestamp,AU12_r\n0,0,1\n"), PerformanceInput::OpenFace);
  EXPECT_EQ(detectPerformanceInput("frame, face_id, timestamp, confidence, success, AU45_c\n"), PerformanceInput::OpenFace);
  EXPECT_EQ(detectPerformanceInput("Timecode,BlendShapeCount,EyeBlinkLeft\n"), PerformanceInput::LiveLink);
  EXPECT_EQ(detectPerformanceInput("Timecode,BlendshapeCount,EyeBlinkLeft\n"), PerformanceInput::LiveLink);
  EXPECT_EQ(detectPerformanceInput("\n  {\"timestamp_ms\": 0, \"blendshapes\": []}\n"), PerformanceInput::MediaPipe);
  EXPECT_EQ(detectPerformanceInput("\xEF\xBB\xBF" "frame,timestamp,AU12_r\n"), PerformanceInput::OpenFace);  // Excel's BOM
  try {
    detectPerformanceInput("\ntime,smile\n0,1\n", "take.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "take.csv:2: cannot tell the performance's layout from 'time,smile': expected an OpenFace CSV header "
                 "(timestamp and AUxx_r columns), a Live Link Face header (Timecode,BlendShapeCount,…) or MediaPipe "
                 "JSON Lines ({\"timestamp_ms\": …})");
  }
  // A layout's own columns tell it even without its time column, whose reader then names it (this
  // said "cannot tell the performance's layout" for an OpenFace CSV without its timestamp).
  EXPECT_EQ(errorOf("frame,confidence,success,AU01_r,AU12_r\n0,0.98,1,0.1,0.2\n"),
            "p.csv:1: missing required column 'timestamp'");
  EXPECT_EQ(errorOf("frame,Timestamp,AU12_r\n0,0,1\n"),
            "p.csv:1: missing required column 'timestamp' (is 'Timestamp' it? OpenFace writes 'timestamp')");
  EXPECT_EQ(errorOf("BlendShapeCount,EyeBlinkLeft\n52,0.1\n"),
            "p.csv:1: missing required column 'Timecode' (a Live Link Face CSV starts Timecode,BlendShapeCount,…)");
  // A timestamp without action units is not OpenFace's.
  EXPECT_NE(errorOf("frame,timestamp,confidence\n").find("p.csv:1: cannot tell"), std::string::npos);
  EXPECT_EQ(errorOf("\n \n"), "p.csv: the performance file is empty");
}

// ---- OpenFace ---------------------------------------------------------------------------------

// FACSvatar's cleaned layout: no face_id, no AUxx_c, intensities 0–1; AU columns out of order.
const char* kCleanOpenFace =
    "frame,timestamp,confidence,success,gaze_angle_x,gaze_angle_y,pose_Rx,pose_Ry,pose_Rz,AU12_r,AU01_r\n"
    "0,0.0,0.98,1,0.07,0.34,0,0,0,0.2,0.5\n"
    "1,0.04,0.98,1,0.07,0.34,0,0,0,0.4,0.25\n"
    "2,0.08,0.98,1,0.07,0.34,0,0,0,0.6,0.0\n";

TEST(PerformanceOpenFace, ReadsACleanedSubsetOnItsOwnScale) {
  const Performance p = parsePerformance(kCleanOpenFace, "clean.csv");
  EXPECT_EQ(p.input, PerformanceInput::OpenFace);
  EXPECT_DOUBLE_EQ(p.auScale, 1.0);
  ASSERT_EQ(p.channels.size(), 2u);
  EXPECT_EQ(p.channels[0].name, "AU1");  // ascending by AU, no leading zero
  EXPECT_EQ(p.channels[1].name, "AU12");
  EXPECT_EQ(valuesOf(p, "AU12"), (std::vector<double>{0.2, 0.4, 0.6}));
  EXPECT_EQ(valuesOf(p, "AU1"), (std::vector<double>{0.5, 0.25, 0.0}));
  EXPECT_EQ(p.find("AU01"), nullptr);
  ASSERT_EQ(p.times.size(), 3u);
  EXPECT_DOUBLE_EQ(p.times[2], 0.08);
  EXPECT_NEAR(p.fps, 25.0, 1e-9);
  EXPECT_NEAR(p.duration(), 0.08, 1e-12);
  ASSERT_EQ(p.headPose.size(), 3u);
  EXPECT_TRUE(p.headPose[1].isZero());
  EXPECT_EQ(p.droppedFrames, 0);
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();  // gaze_angle_* is OpenFace's: not unknown
}

// Raw OpenFace output, a few of its 714 columns, as its Windows build writes the header (", ").
const char* kRawOpenFace =
    "frame, face_id, timestamp, confidence, success, gaze_0_x, eye_lmk_x_0, pose_Tx, pose_Rx, pose_Ry, pose_Rz, "
    "x_0, y_0, X_0, Y_0, Z_0, p_scale, p_rx, p_0, AU01_r, AU12_r, AU01_c, AU12_c, AU28_c\n"
    "1, 0, 0.000, 0.98, 1, 0.1, 300.5, 10.2, 0, 0, 0, 300, 200, -30, 10, 400, 1.1, 0.01, 0.5, 1.00, 2.50, 1, 1, 0\n"
    "2, 0, 0.033, 0.97, 1, 0.1, 300.5, 10.2, 0, 0, 0, 300, 200, -30, 10, 400, 1.1, 0.01, 0.5, 0.00, 5.00, 0, 1, 0\n";

TEST(PerformanceOpenFace, RawOutputIsOnTheZeroToFiveScale) {
  const Performance p = parsePerformance(kRawOpenFace, "raw.csv");
  EXPECT_DOUBLE_EQ(p.auScale, 5.0);
  ASSERT_EQ(p.channels.size(), 2u);  // the AUxx_c presence columns are no channels (AU28 has only _c)
  EXPECT_EQ(valuesOf(p, "AU1"), (std::vector<double>{0.2, 0.0}));
  EXPECT_EQ(valuesOf(p, "AU12"), (std::vector<double>{0.5, 1.0}));
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();  // every column is OpenFace's own
  // A header with only AUxx_c columns (no face_id) is raw too; an explicit scale wins.
  const Performance given = parsePerformance(kRawOpenFace, "raw.csv", {.auScale = 10.0});
  EXPECT_DOUBLE_EQ(given.auScale, 10.0);
  EXPECT_EQ(valuesOf(given, "AU12"), (std::vector<double>{0.25, 0.5}));
  const Performance presence =
      parsePerformance("timestamp,AU12_r,AU12_c\n0,5,1\n0.1,2.5,1\n", "c.csv");
  EXPECT_DOUBLE_EQ(presence.auScale, 5.0);
}

TEST(PerformanceOpenFace, CommaSpaceHeaderReadsAsCommas) {
  std::string commas = kRawOpenFace;
  for (size_t at = commas.find(", "); at != std::string::npos; at = commas.find(", ", at)) commas.erase(at + 1, 1);
  ASSERT_EQ(commas.find(", "), std::string::npos);
  const Performance a = parsePerformance(kRawOpenFace), b = parsePerformance(commas);
  EXPECT_EQ(a.times, b.times);
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (size_t c = 0; c < a.channels.size(); ++c) {
    EXPECT_EQ(a.channels[c].name, b.channels[c].name);
    EXPECT_EQ(a.channels[c].values, b.channels[c].values);
  }
  EXPECT_DOUBLE_EQ(a.auScale, b.auScale);
}

TEST(PerformanceOpenFace, DroppedFramesAreBridgedByInterpolationInTime) {
  // Frames at 0.1 (success 0), 0.2 (confidence 0.5) and 0.25 (an empty cell) lie between valid
  // frames at 0 (AU12 0.0) and 0.4 (AU12 0.8): they get 0.2, 0.4 and 0.5 whatever they hold.
  const Performance p = parsePerformance(
      "timestamp,confidence,success,AU12_r\n"
      "0.0,0.9,1,0.0\n"
      "0.1,0.9,0,0.9\n"
      "0.2,0.5,1,0.9\n"
      "0.25,0.9,1,\n"
      "0.4,0.9,1,0.8\n",
      "gaps.csv");
  ASSERT_EQ(p.times.size(), 5u);
  const std::vector<double> v = valuesOf(p, "AU12");
  EXPECT_NEAR(v[1], 0.2, 1e-12);
  EXPECT_NEAR(v[2], 0.4, 1e-12);
  EXPECT_NEAR(v[3], 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(v[4], 0.8);
  EXPECT_EQ(p.droppedFrames, 3);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_EQ(p.warnings[0],
            "dropped 3 of 5 frames (3 bridged by interpolation, 0 trimmed at the ends): 1 with success 0, 1 with "
            "confidence below 0.7, 1 with empty cells; the first at line 3");
  // A lower threshold keeps the 0.5-confidence frame.
  EXPECT_EQ(parsePerformance("timestamp,confidence,AU12_r\n0,0.9,0\n0.1,0.5,0.3\n0.2,0.9,0\n", "c.csv",
                             {.minConfidence = 0.4})
                .droppedFrames,
            0);
}

TEST(PerformanceOpenFace, DroppedFramesAtTheEndsAreTrimmed) {
  const Performance p = parsePerformance(
      "timestamp,success,AU12_r\n"
      "0.0,0,0\n"
      "0.1,1,0.3\n"
      "0.2,1,0.4\n"
      "0.3,1,0.5\n"
      "0.4,0,0\n"
      "0.5,0,0\n",
      "ends.csv");
  EXPECT_EQ(valuesOf(p, "AU12"), (std::vector<double>{0.3, 0.4, 0.5}));
  ASSERT_EQ(p.times.size(), 3u);
  EXPECT_DOUBLE_EQ(p.times[0], 0.0);  // the first kept frame's time is subtracted
  EXPECT_NEAR(p.times[2], 0.2, 1e-12);
  EXPECT_NEAR(p.fps, 10.0, 1e-9);
  EXPECT_EQ(p.droppedFrames, 3);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_EQ(p.warnings[0],
            "dropped 3 of 6 frames (0 bridged by interpolation, 3 trimmed at the ends): 3 with success 0; the first "
            "at line 2");
}

const char* kTwoFaces =
    "frame,face_id,timestamp,confidence,success,AU12_r\n"
    "1,0,0.0,0.9,1,1\n"
    "1,1,0.0,0.9,1,4\n"
    "2,0,0.1,0.9,1,2\n"
    "2,1,0.1,0.9,1,5\n";

TEST(PerformanceOpenFace, SeveralFacesNeedAChoice) {
  EXPECT_EQ(errorOf(kTwoFaces, {}, "two.csv"), "two.csv: the file holds 2 faces (face_id 0, 1): choose one (--face N)");
  const Performance one = parsePerformance(kTwoFaces, "two.csv", {.face = 1});
  EXPECT_EQ(valuesOf(one, "AU12"), (std::vector<double>{0.8, 1.0}));
  EXPECT_EQ(one.droppedFrames, 0);  // the other face's rows are not this face's dropped frames
  EXPECT_EQ(valuesOf(parsePerformance(kTwoFaces, "two.csv", {.face = 0}), "AU12"), (std::vector<double>{0.2, 0.4}));
  EXPECT_EQ(errorOf(kTwoFaces, {.face = 7}, "two.csv"), "two.csv: face_id 7 is not in the file (its faces: 0, 1)");
  EXPECT_EQ(errorOf(kCleanOpenFace, {.face = 2}, "c.csv"),
            "c.csv: face_id 2 is not in the file (it has no face_id column: one face, 0)");
  EXPECT_EQ(parsePerformance(kCleanOpenFace, "c.csv", {.face = 0}).times.size(), 3u);
}

// The rotation a [pitch, yaw, roll] reading stands for, against OpenFace's own matrix
// (RotationHelpers.h, Euler2RotationMatrix: R = Rx·Ry·Rz), brought into face-frame axes by hand.
TEST(PerformanceOpenFace, HeadPoseIsConvertedIntoTheFaceFrame) {
  const auto poseOf = [](double rx, double ry, double rz) {
    const std::string row = "0.1," + std::to_string(rx) + "," + std::to_string(ry) + "," + std::to_string(rz) + ",0\n";
    const Performance p = parsePerformance("timestamp,pose_Rx,pose_Ry,pose_Rz,AU12_r\n0,0,0,0,0\n" + row, "pose.csv");
    return p.headPose.back();
  };
  const double deg = 180.0 / M_PI;
  // One axis at a time: chin down is +pitch (as timeline.head_pose: face-down is +90°); OpenFace's
  // +Ry turns the face to the subject's right (our −yaw); its +Rz drops the subject's left ear
  // towards the left shoulder in the image's right-down frame (our −roll: +roll lifts the left side).
  EXPECT_TRUE(poseOf(0.2, 0, 0).isApprox(Vec3(0.2 * deg, 0, 0), 1e-12));
  EXPECT_TRUE(poseOf(0, 0.3, 0).isApprox(Vec3(0, -0.3 * deg, 0), 1e-12));
  EXPECT_TRUE(poseOf(0, 0, 0.1).isApprox(Vec3(0, 0, -0.1 * deg), 1e-12));
  // Chin down really moves the face's normal (+z, towards the viewer) down (−y) in the face frame.
  const Vec3 normal = headPoseRotation(poseOf(0.2, 0, 0)) * Vec3::UnitZ();
  EXPECT_LT(normal.y(), -0.19);
  // A hand-made row turned about all three axes: the same rotation as OpenFace's matrix, seen from
  // the face frame (x the image's right = subject's left, y up = −image y, z towards the camera).
  const double a = 0.25, b = -0.4, c = 0.15;
  const double s1 = std::sin(a), s2 = std::sin(b), s3 = std::sin(c), c1 = std::cos(a), c2 = std::cos(b), c3 = std::cos(c);
  Mat3 openFace;
  openFace << c2 * c3, -c2 * s3, s2,                                  //
      c1 * s3 + c3 * s1 * s2, c1 * c3 - s1 * s2 * s3, -c2 * s1,        //
      s1 * s3 - c1 * c3 * s2, c3 * s1 + c1 * s2 * s3, c1 * c2;
  const Mat3 C = Vec3(1, -1, -1).asDiagonal();
  const Mat3 expected = C * openFace * C;
  const Mat3 got = headPoseRotation(poseOf(a, b, c)).toRotationMatrix();
  EXPECT_TRUE(got.isApprox(expected, 1e-6)) << got << "\nexpected\n" << expected;
}

TEST(PerformanceOpenFace, UnknownColumnsWarnOnceByName) {
  const Performance p = parsePerformance(
      "timestamp,AU12_r,mood,x_0,gaze_0_x,note\n0,1,a,3,0,x\n0.1,1,b,3,0,y\n0.2,1,c,3,0,z\n", "u.csv");
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_EQ(p.warnings[0], "ignored 2 unknown columns: mood, note");
}

TEST(PerformanceOpenFace, ErrorsNameTheFileLineAndFault) {
  EXPECT_EQ(errorOf("frame,AU12_r\n", {.input = PerformanceInput::OpenFace}), "p.csv:1: missing required column 'timestamp'");
  EXPECT_EQ(errorOf("timestamp,AU12_c\n0,1\n"), "p.csv:1: no action-unit intensity column (AUxx_r): OpenFace writes them with -aus");
  EXPECT_EQ(errorOf("timestamp,pose_Rx,pose_Rz,AU12_r\n"),
            "p.csv:1: missing required column 'pose_Ry' (the head's rotation needs pose_Rx, pose_Ry and pose_Rz)");
  EXPECT_EQ(errorOf("timestamp,AU12_r,AU12_r\n"), "p.csv:1: column 'AU12_r' appears twice (columns 2 and 3)");
  EXPECT_EQ(errorOf("timestamp,AU12_r,AU012_r\n"), "p.csv:1: columns 'AU12_r' and 'AU012_r' are both AU12");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,0.5\n0.1\n"), "p.csv:3: row has 1 fields, the header has 2");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,0.5,1\n"), "p.csv:2: row has 3 fields, the header has 2");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,abc\n"), "p.csv:2: unreadable number 'abc' in column 'AU12_r'");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,+-1\n"), "p.csv:2: unreadable number '+-1' in column 'AU12_r'");
  EXPECT_EQ(valuesOf(parsePerformance("timestamp,AU12_r\n+0,+0.5\n0.1,1\n"), "AU12"), (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,nan\n"), "p.csv:2: non-finite number 'nan' in column 'AU12_r'");
  EXPECT_EQ(errorOf("timestamp,AU12_r\ninf,0\n"), "p.csv:2: non-finite number 'inf' in column 'timestamp'");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,1e400\n"), "p.csv:2: non-finite number '1e400' in column 'AU12_r'");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n-0.04,0\n0,0\n"), "p.csv:2: negative time -0.04 s");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,0\n0.08,0\n\n0.04,0\n"),
            "p.csv:5: time 0.04 s is not after the previous frame's 0.08 s (line 3)");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,0\n0,0\n"), "p.csv:3: time 0 s is not after the previous frame's 0 s (line 2)");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n0,0\n0.1,1.2\n"),
            "p.csv:3: AU12_r is 1.2, outside [0, 1] (scale 1: the header has no face_id or AUxx_c column; raw "
            "OpenFace intensities 0–5 need --au-scale 5)");
  EXPECT_EQ(errorOf("face_id,timestamp,AU12_r\n0,0,0\n0,0.1,-0.5\n"),
            "p.csv:3: AU12_r is -0.5, outside [0, 5] (scale 5: the header has face_id or AUxx_c columns, as raw "
            "OpenFace output)");
  EXPECT_EQ(errorOf("face_id,timestamp,AU12_r\n0.5,0,0\n"), "p.csv:2: face_id '0.5' is not an integer");
  EXPECT_EQ(errorOf("timestamp,success,AU12_r\n0,1,0\n0.1,0,0\n0.2,,0\n,1,0\n"),
            "p.csv: fewer than two valid frames (4 rows, 1 with success 0, 1 with empty cells, 1 with no timestamp)");
  EXPECT_EQ(errorOf("timestamp,AU12_r\n"), "p.csv: fewer than two valid frames (0 rows)");
  EXPECT_EQ(errorOf(kCleanOpenFace, {.auScale = 0.0}), "the AU scale must be a positive number (got 0)");
  // A tiny excursion past the scale is round-off: clamped, not refused.
  EXPECT_EQ(valuesOf(parsePerformance("timestamp,AU12_r\n0,1.0000001\n0.1,-0.0000001\n"), "AU12"),
            (std::vector<double>{1.0, 0.0}));
}

TEST(PerformanceOpenFace, TheFacsvatarDemo) {
  const fs::path demo = test::sharedDataDir() / "openface" / "facsvatar_demo.csv";
  if (!fs::exists(demo))
    GTEST_SKIP() << "the OpenFace demo performance is not at " << demo
                 << " (set MYOSHELL_SHARED_DATA or place ../shared beside the project)";
  const Performance p = readPerformanceFile(demo.string());
  EXPECT_EQ(p.input, PerformanceInput::OpenFace);
  EXPECT_EQ(p.times.size(), 490u);
  EXPECT_NEAR(p.fps, 25.0, 1e-9);
  EXPECT_NEAR(p.duration(), 19.56, 1e-9);
  EXPECT_DOUBLE_EQ(p.auScale, 1.0);
  ASSERT_EQ(p.channels.size(), 17u);
  const std::vector<std::string> aus = {"AU1",  "AU2",  "AU4",  "AU5",  "AU6",  "AU7",  "AU9",  "AU10", "AU12",
                                        "AU14", "AU15", "AU17", "AU20", "AU23", "AU25", "AU26", "AU45"};
  for (size_t c = 0; c < aus.size(); ++c) EXPECT_EQ(p.channels[c].name, aus[c]);
  EXPECT_DOUBLE_EQ(p.find("AU1")->values[0], 0.176);  // the first row as written
  EXPECT_DOUBLE_EQ(p.find("AU45")->values[0], 0.316);
  EXPECT_EQ(p.headPose.size(), 490u);
  EXPECT_EQ(p.droppedFrames, 0);
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();
  for (const PerformanceChannel& c : p.channels)
    for (const double v : c.values) ASSERT_TRUE(v >= 0 && v <= 1) << c.name << " " << v;
}

// ---- Live Link Face ---------------------------------------------------------------------------

TEST(PerformanceLiveLink, ReadsATakeWithAllSixtyOneValues) {
  const Performance p = readPerformanceFile((samples() / "livelink_take.csv").string());
  EXPECT_EQ(p.input, PerformanceInput::LiveLink);
  EXPECT_EQ(p.channels.size(), 52u);  // the 52 ARKit weights; the eyes' rotations are the gaze, not channels
  EXPECT_EQ(p.channels[0].name, "eyeBlinkLeft");  // PascalCase lowered, in the file's order
  EXPECT_EQ(p.channels.back().name, "tongueOut");
  EXPECT_EQ(p.find("EyeBlinkLeft"), nullptr);
  EXPECT_NEAR(p.fps, 60.0, 1e-12);  // frame numbers reach 59
  ASSERT_EQ(p.times.size(), 3u);
  // 20:14:39:58.412, 20:14:39:59.412, 20:14:40:00.412 at 60 fps: one frame apart.
  EXPECT_NEAR(p.times[1], 1.0 / 60, 1e-9);
  EXPECT_NEAR(p.times[2], 2.0 / 60, 1e-9);
  const std::vector<double> jaw = valuesOf(p, "jawOpen");
  ASSERT_EQ(jaw.size(), 3u);
  EXPECT_NEAR(jaw[0], 0.21, 1e-8);
  EXPECT_NEAR(jaw[2], 0.25, 1e-8);
  EXPECT_NEAR(valuesOf(p, "mouthSmileLeft")[1], 0.36, 1e-8);
  // HeadPitch −0.0342, HeadYaw 0.0521, HeadRoll 0.0105 are degrees / 180.
  ASSERT_EQ(p.headPose.size(), 3u);
  EXPECT_TRUE(p.headPose[0].isApprox(Vec3(-0.0342 * 180, 0.0521 * 180, 0.0105 * 180), 1e-9)) << p.headPose[0];
  EXPECT_EQ(p.droppedFrames, 0);
  EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();
}

const char* kShortTake =
    "Timecode,BlendShapeCount,JawOpen,MouthSmileLeft\n"
    "00:00:01:10.500,2,0.1,0.2\n"
    "00:00:01:11.500,2,0.2,0.2\n"
    "00:00:01:14.000,2,,0.2\n"
    "00:00:01:17.000,2,0.5,0.2\n";

TEST(PerformanceLiveLink, TimecodesFrameRateAndGaps) {
  // Given the rate: time = (FF + fraction) / fps past the first kept frame.
  const Performance p = parsePerformance(kShortTake, "t.csv", {.inputFps = 30.0});
  ASSERT_EQ(p.times.size(), 4u);
  EXPECT_NEAR(p.times[1], 1.0 / 30, 1e-12);
  EXPECT_NEAR(p.times[2], 3.5 / 30, 1e-12);
  EXPECT_NEAR(p.times[3], 6.5 / 30, 1e-12);
  EXPECT_DOUBLE_EQ(p.fps, 30.0);
  EXPECT_NEAR(valuesOf(p, "jawOpen")[2], 0.2 + 0.3 * (2.5 / 5.5), 1e-12);  // bridged in time
  EXPECT_EQ(p.droppedFrames, 1);
  EXPECT_TRUE(p.headPose.empty());
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_EQ(p.warnings[0],
            "dropped 1 of 4 frames (1 bridged by interpolation, 0 trimmed at the ends): 1 with empty cells; the first "
            "at line 4");
  // Inferred from a take shorter than a second: a lower bound, said so.
  const Performance guessed = parsePerformance(kShortTake, "t.csv");
  EXPECT_DOUBLE_EQ(guessed.fps, 18.0);
  ASSERT_EQ(guessed.warnings.size(), 2u);
  EXPECT_EQ(guessed.warnings[0],
            "frame rate inferred as 18 fps from frame numbers up to 17, but the take spans no whole second: give the "
            "input frame rate (--input-fps)");
}

TEST(PerformanceLiveLink, ErrorsNameTheFileLineAndFault) {
  const PerformanceOptions ll{.input = PerformanceInput::LiveLink};
  EXPECT_EQ(errorOf("frame,timestamp,AU12_r\n", ll),
            "p.csv:1: missing required column 'Timecode' (a Live Link Face CSV starts Timecode,BlendShapeCount,…)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,HeadYaw,HeadPitch,HeadRoll,LeftEyeYaw\n"), "p.csv:1: no ARKit blendshape column (EyeBlinkLeft … TongueOut)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen,HeadYaw,HeadPitch\n"),
            "p.csv:1: missing required column 'HeadRoll' (the head's rotation needs HeadPitch, HeadYaw and HeadRoll)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen,JawOpen\n"), "p.csv:1: column 'JawOpen' appears twice");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:00:01.5,1,0\n"),
            "p.csv:2: unreadable timecode '00:00:01.5' (expected HH:MM:SS:FF or HH:MM:SS:FF.fff)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:61:00:00,1,0\n"),
            "p.csv:2: unreadable timecode '00:61:00:00' (expected HH:MM:SS:FF or HH:MM:SS:FF.fff)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:00:00:30,1,0\n", {.inputFps = 30.0}),
            "p.csv:2: frame 30 of timecode '00:00:00:30' is not below the frame rate 30");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:00:00:00,1,1.5\n"), "p.csv:2: JawOpen is 1.5, outside [0, 1]");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen,HeadYaw,HeadPitch,HeadRoll\n00:00:00:00,1,0,0,-1.5,0\n"),
            "p.csv:2: HeadPitch is -1.5, outside [-1, 1] (degrees / 180)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:00:00:00,1,nan\n"),
            "p.csv:2: non-finite number 'nan' in column 'JawOpen'");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:00:00:01,1,0\n00:00:00:00,1,0\n"),
            "p.csv:3: time 0 s is not after the previous frame's 0.5 s (line 2)");
  EXPECT_EQ(errorOf("Timecode,BlendShapeCount,JawOpen\n00:00:00:01,1\n"), "p.csv:2: row has 2 fields, the header has 3");
  EXPECT_EQ(errorOf(kShortTake, {.inputFps = -1.0}), "the input frame rate must be a positive number (got -1)");
  // Names that are not ARKit's warn; ICT's spellings are not Live Link's.
  const Performance p = parsePerformance(
      "Timecode,BlendShapeCount,JawOpen,MouthSmile_L,Mood\n00:00:00:00,3,0,0,1\n00:00:00:01,3,0,0,1\n", "p.csv");
  ASSERT_EQ(p.warnings.size(), 2u);  // and the frame rate inferred from two frames
  EXPECT_EQ(p.warnings[0], "ignored 2 unknown columns: MouthSmile_L, Mood");
}

// ---- MediaPipe --------------------------------------------------------------------------------

TEST(PerformanceMediaPipe, ReadsATakeAndDropsTheFrameWithNoFace) {
  const Performance p = readPerformanceFile((samples() / "mediapipe_take.jsonl").string());
  EXPECT_EQ(p.input, PerformanceInput::MediaPipe);
  EXPECT_EQ(p.channels.size(), 51u);  // MediaPipe's 52 categories: _neutral and 51 ARKit names (no tongueOut)
  EXPECT_EQ(p.find("_neutral"), nullptr);
  EXPECT_EQ(p.find("tongueOut"), nullptr);
  EXPECT_EQ(p.channels[0].name, "browDownLeft");  // in the file's order
  ASSERT_EQ(p.times.size(), 4u);
  EXPECT_NEAR(p.times[3], 0.1, 1e-12);  // timestamp_ms 1000 … 1100
  EXPECT_NEAR(p.fps, 30.0, 1e-9);
  const std::vector<double> jaw = valuesOf(p, "jawOpen");
  EXPECT_NEAR(jaw[1], 0.15, 1e-12);
  EXPECT_NEAR(jaw[2], 0.15 + 0.10 * 34.0 / 67.0, 1e-9);  // the empty frame at 1067 ms, bridged
  EXPECT_NEAR(jaw[3], 0.25, 1e-12);
  EXPECT_EQ(p.droppedFrames, 1);
  EXPECT_TRUE(p.headPose.empty());
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_EQ(p.warnings[0],
            "dropped 1 of 4 frames (1 bridged by interpolation, 0 trimmed at the ends): 1 with no face (empty "
            "blendshapes); the first at line 3");
}

std::string mpFrame(double t, const std::string& shapes) {
  return "{\"timestamp_ms\": " + std::to_string(t) + ", \"blendshapes\": [" + shapes + "]}\n";
}

TEST(PerformanceMediaPipe, ErrorsNameTheFileLineAndFault) {
  const std::string good = mpFrame(0, "{\"categoryName\": \"jawOpen\", \"score\": 0.1}");
  EXPECT_EQ(errorOf(good + "{\"timestamp_ms\": 33, \"blendshapes\": [}\n", {}, "m.jsonl"),
            "m.jsonl:2:38: bad JSON: syntax error while parsing value - unexpected '}'; expected '[', '{', or a literal");
  EXPECT_EQ(errorOf(good + "[1, 2]\n", {}, "m.jsonl"),
            "m.jsonl:2: a frame must be a JSON object {\"timestamp_ms\": …, \"blendshapes\": […]}, got array");
  EXPECT_EQ(errorOf("{\"blendshapes\": []}\n", {}, "m.jsonl"), "m.jsonl:1: missing required key 'timestamp_ms'");
  EXPECT_EQ(errorOf("{\"timestamp_ms\": 0}\n", {}, "m.jsonl"), "m.jsonl:1: missing required key 'blendshapes'");
  EXPECT_EQ(errorOf("{\"timestamp_ms\": \"0\", \"blendshapes\": []}\n", {}, "m.jsonl"),
            "m.jsonl:1: timestamp_ms must be a number, got \"0\"");
  EXPECT_EQ(errorOf("{\"timestamp_ms\": 0, \"blendshapes\": 3}\n", {}, "m.jsonl"),
            "m.jsonl:1: blendshapes must be a list of {\"categoryName\": …, \"score\": …}, got 3");
  EXPECT_EQ(errorOf(mpFrame(0, "{\"categoryName\": \"jawOpen\"}"), {}, "m.jsonl"),
            "m.jsonl:1: blendshapes[0] must be an object {\"categoryName\": …, \"score\": …}");
  EXPECT_EQ(errorOf(mpFrame(0, "{\"categoryName\": \"jawOpen\", \"score\": \"high\"}"), {}, "m.jsonl"),
            "m.jsonl:1: blendshapes[0].score must be a number, got \"high\"");
  EXPECT_EQ(errorOf(mpFrame(0, "{\"categoryName\": \"jawOpen\", \"score\": 1.5}"), {}, "m.jsonl"),
            "m.jsonl:1: blendshapes[0].score of jawOpen is 1.5, outside [0, 1]");
  EXPECT_EQ(errorOf(mpFrame(0, "{\"categoryName\": \"jawOpen\", \"score\": 0.1}, {\"categoryName\": \"jawOpen\", \"score\": 0.2}"),
                    {}, "m.jsonl"),
            "m.jsonl:1: blendshapes[1]: jawOpen appears twice in the frame");
  EXPECT_EQ(errorOf(good + mpFrame(-5, "{\"categoryName\": \"jawOpen\", \"score\": 0.1}"), {}, "m.jsonl"),
            "m.jsonl:2: negative time -0.005 s");
  EXPECT_EQ(errorOf(good + "{\"timestamp_ms\": 1e400, \"blendshapes\": []}\n", {}, "m.jsonl"),
            "m.jsonl:2: bad JSON: number overflow parsing '1e400'");
  EXPECT_EQ(errorOf(good + mpFrame(33, ""), {}, "m.jsonl"),
            "m.jsonl: fewer than two valid frames (2 rows, 1 with no face (empty blendshapes))");
  // Unknown keys and names warn once each; blank lines are skipped.
  const Performance p = parsePerformance(
      "{\"timestamp_ms\": 0, \"frame\": 1, \"blendshapes\": [{\"categoryName\": \"jawOpen\", \"score\": 0.1}, "
      "{\"categoryName\": \"smile\", \"score\": 0.3}]}\n\n" +
          mpFrame(40, "{\"categoryName\": \"jawOpen\", \"score\": 0.3}, {\"categoryName\": \"_neutral\", \"score\": 0}"),
      "m.jsonl");
  ASSERT_EQ(p.warnings.size(), 2u);
  EXPECT_EQ(p.warnings[0], "ignored 1 unknown key: frame");
  EXPECT_EQ(p.warnings[1], "ignored 1 unknown blendshape name: smile");
  EXPECT_EQ(valuesOf(p, "jawOpen"), (std::vector<double>{0.1, 0.3}));
}

// ---- the file ----------------------------------------------------------------------------------

TEST(PerformanceFile, UnreadableFilesSayCannotOpen) {
  try {
    readPerformanceFile("/nonexistent/take.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/take.csv: cannot open performance file");
  }
}

}  // namespace
}  // namespace myo
