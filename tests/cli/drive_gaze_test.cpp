// `myoshell drive` turns the eyes from a tracker's gaze (docs/performance_input.md; docs/eyelids.md,
// "The lids follow the gaze"): OpenFace's gaze_angle_y looking up lifts the upper lids as the face's
// placement at that gaze does, in the rig's eyeLookUp direction; Live Link's eye angles turn each
// eye with the documented sign and win over its eyeLook* curves; zero gaze columns leave the output
// byte for byte as without them; the real demo take plays with its gaze.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anatomy/skin_placement.h"
#include "myoshell/anim/performance.h"
#include "myoshell/fit/arkit_rig.h"
#include "myoshell/fit/retarget_map.h"
#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/performance_file.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/cli_runner.h"
#include "support/csv_columns.h"
#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

struct GazeDir {
  fs::path path;
  explicit GazeDir(const std::string& tag)
      : path(fs::temp_directory_path() / ("myo_drive_gaze_" + tag + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~GazeDir() { fs::remove_all(path); }
};

const Head& builtInHead() {
  static const Head head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical));
  return head;
}

// The placement the playing face uses on the built-in head with the whole face's muscles.
const SkinPlacement& builtInPlacement() {
  static const SkinPlacement placement = [] {
    std::vector<std::string> names;
    for (const MuscleDef& d : faceMuscleDefs()) names.push_back(d.name);
    return SkinPlacement(builtInHead(), names);
  }();
  return placement;
}

// The built-in head's rest placed at `gaze` with no muscle acting.
MatX3 restAt(const EyeGaze& gaze) {
  const int n = builtInHead().mesh.vertexCount();
  MatX3 out;
  builtInPlacement().place(MatX3::Zero(n, 3), JawPose{}, VecX::Zero(static_cast<Eigen::Index>(faceMuscleDefs().size())),
                           out, builtInPlacement().contact(), gaze);
  return out;
}

PointCache driveGaze(const fs::path& take, const fs::path& out, const std::string& extra = "") {
  const auto r = test::runCli("drive '" + take.string() + "' --filter off --format pc2 " + extra + " --out '" +
                              out.string() + "'");
  EXPECT_EQ(r.exitCode, 0) << r.merged;
  return readPc2(out / (take.stem().string() + ".pc2"));
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The middle vertex of an eye's upper margin (eye 0 the subject's right).
int upperMid(int eye) {
  const EyeLids& lids = builtInPlacement().lids()->eyes[static_cast<size_t>(eye)];
  return lids.upperMargin[lids.upperMargin.size() / 2];
}

// OpenFace's gaze_angle_y < 0 looks up (its camera's y points down): 0.35 rad up for 0.4 s, no
// muscle acting. Every frame after the first is the rest placed at pitch 0.35 rad on both eyes; the
// upper lids rise, as the rig's eyeLookUpLeft lifts the left one.
TEST(DriveGaze, OpenFaceLookingUpLiftsTheUpperLids) {
  GazeDir dir("up");
  {
    std::ofstream csv(dir.path / "up.csv");
    csv << "timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n";
    for (int f = 0; f <= 10; ++f) csv << f * 0.04 << ",0,-0.35,0\n";
  }
  const PointCache pc = driveGaze(dir.path / "up.csv", dir.path / "out");
  ASSERT_EQ(pc.samples.size(), 11u);
  ASSERT_NE(builtInPlacement().lids(), nullptr);
  EyeGaze gaze;
  const double up = 0.35 * 180.0 / M_PI;
  gaze.pitchDeg = {up, up};
  const MatX3 expected = restAt(gaze);
  const MatX3& V = builtInHead().mesh.V;
  const Vec3 yAxis = builtInHead().frame().axes.col(1);
  const RetargetShape* look = builtinRetargetMap().find("eyeLookUpLeft");
  ASSERT_NE(look, nullptr);
  const MatX3 rig = restAt(gazeOf(*look));
  // Frame 0 is the face at rest, before the first step applies the timeline (as the jaw's).
  EXPECT_LT((pc.samples.front() - V).cwiseAbs().maxCoeff(), 1e-5);
  for (const MatX3& frame : {pc.samples[1], pc.samples.back()}) {
    EXPECT_LT((frame - expected).cwiseAbs().maxCoeff(), 1e-3);  // cm; the PC2 holds floats
    for (int eye = 0; eye < 2; ++eye) {
      const int mid = upperMid(eye);
      const Vec3 lift = (frame.row(mid) - V.row(mid)).transpose();
      RecordProperty("upper_lid_lift_mm_eye_" + std::to_string(eye), std::to_string(10.0 * lift.dot(yAxis)));
      EXPECT_GT(lift.dot(yAxis), 0.15);  // cm: 20° up lifts the upper margin by ~3 mm (docs/eyelids.md)
    }
    const int mid = upperMid(1);
    const Vec3 rigLift = (rig.row(mid) - V.row(mid)).transpose();
    const Vec3 lift = (frame.row(mid) - V.row(mid)).transpose();
    EXPECT_GT(lift.normalized().dot(rigLift.normalized()), 0.95);
  }
}

// Zero gaze columns (and no head pose) play byte for byte as the same take without them.
TEST(DriveGaze, ZeroGazeColumnsLeaveTheOutputByteIdentical) {
  GazeDir dir("zero");
  {
    std::ofstream with(dir.path / "with.csv"), without(dir.path / "without.csv");
    with << "timestamp,confidence,success,gaze_angle_x,gaze_angle_y,AU12_r,AU45_r\n";
    without << "timestamp,confidence,success,AU12_r,AU45_r\n";
    for (int f = 0; f <= 12; ++f) {
      const double au12 = std::min(1.0, f / 6.0), au45 = f == 6 || f == 7 ? 0.9 : 0.0;
      const double confidence = f == 4 ? 0.3 : 0.98;  // one bridged frame
      with << f * 0.04 << "," << confidence << ",1,0,0," << au12 << "," << au45 << "\n";
      without << f * 0.04 << "," << confidence << ",1," << au12 << "," << au45 << "\n";
    }
  }
  const auto a = test::runCli("drive '" + (dir.path / "with.csv").string() + "' --format pc2 --out '" +
                              (dir.path / "a").string() + "'");
  ASSERT_EQ(a.exitCode, 0) << a.merged;
  const auto b = test::runCli("drive '" + (dir.path / "without.csv").string() + "' --format pc2 --out '" +
                              (dir.path / "b").string() + "'");
  ASSERT_EQ(b.exitCode, 0) << b.merged;
  const std::string pa = slurp(dir.path / "a" / "with.pc2"), pb = slurp(dir.path / "b" / "without.pc2");
  ASSERT_FALSE(pa.empty());
  EXPECT_TRUE(pa == pb);
  // The take moved the face (the smile, the blink): the identity is not of two rests.
  const PointCache pc = readPc2(dir.path / "a" / "with.pc2");
  EXPECT_GT((pc.samples.back() - builtInHead().mesh.V).cwiseAbs().maxCoeff(), 0.1);
}

// Live Link: LeftEyePitch −0.1 is 18° up for the left eye only (degrees / 180, a right-handed turn
// about the face's left looks down); the take's EyeLookUpLeft at 1 (25° through the map) is not
// added to it: the angles win. The right eye, at 0, does not move.
TEST(DriveGaze, LiveLinkEyeAnglesTurnTheLeftEyeUp) {
  GazeDir dir("livelink");
  {
    std::ofstream csv(dir.path / "take.csv");
    csv << "Timecode,BlendShapeCount,EyeLookUpLeft,JawOpen,LeftEyeYaw,LeftEyePitch,LeftEyeRoll,RightEyeYaw,"
           "RightEyePitch,RightEyeRoll\n";
    for (int f = 0; f <= 10; ++f) csv << "00:00:00:" << (f < 10 ? "0" : "") << f << ",8,1,0,0,-0.1,0,0,0,0\n";
  }
  const PointCache pc = driveGaze(dir.path / "take.csv", dir.path / "out", "--input-fps 30");
  ASSERT_EQ(pc.samples.size(), 11u);
  EyeGaze gaze;
  gaze.pitchDeg[1] = 18.0;
  const MatX3 expected = restAt(gaze);
  const MatX3& V = builtInHead().mesh.V;
  const Vec3 yAxis = builtInHead().frame().axes.col(1);
  const MatX3& last = pc.samples.back();
  EXPECT_LT((last - expected).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_GT((last.row(upperMid(1)) - V.row(upperMid(1))).dot(yAxis.transpose()), 0.15);
  EXPECT_LT((last.row(upperMid(0)) - V.row(upperMid(0))).norm(), 1e-4);
}

// On a head without eye openings (the thesis model's built-in head, its eyes closed) the gaze has
// no lids to turn: drive says so, and plays the rest of the take.
TEST(DriveGaze, AHeadWithoutEyeOpeningsIsToldTheGazeMovesNothing) {
  GazeDir dir("closed_eyes");
  const auto head = test::runCli("head --closed-eyes --levels 0 --write-obj '" + (dir.path / "h.obj").string() +
                                 "' --write-landmarks '" + (dir.path / "h.json").string() + "'");
  ASSERT_EQ(head.exitCode, 0) << head.merged;
  {
    std::ofstream csv(dir.path / "take.csv");
    csv << "Timecode,BlendShapeCount,JawOpen,LeftEyeYaw,LeftEyePitch,LeftEyeRoll,RightEyeYaw,RightEyePitch,RightEyeRoll\n";
    for (int f = 0; f <= 3; ++f) csv << "00:00:00:0" << f << ",7,0.2,0,-0.1,0,0,-0.1,0\n";
  }
  const std::string warning = "warning: the scene turns the eyes (its gaze), but this head has no eye openings";
  const auto r = test::runCli("drive '" + (dir.path / "take.csv").string() + "' --head '" + (dir.path / "h.obj").string() +
                              "' --landmarks '" + (dir.path / "h.json").string() + "' --input-fps 30 --format pc2 --out '" +
                              (dir.path / "out").string() + "'");
  EXPECT_EQ(r.exitCode, 0) << r.merged;
  EXPECT_NE(r.err.find(warning), std::string::npos) << r.err;
  // The built-in head (eyes open) plays the same take without it.
  const auto open = test::runCli("drive '" + (dir.path / "take.csv").string() + "' --input-fps 30 --format pc2 --out '" +
                                 (dir.path / "out_open").string() + "'");
  EXPECT_EQ(open.exitCode, 0) << open.merged;
  EXPECT_EQ(open.err.find(warning), std::string::npos) << open.err;
}

// A non-finite gaze is the reader's InputError naming the file, the line and the column.
TEST(DriveGaze, ANonFiniteGazeIsRefusedWithItsLineAndColumn) {
  GazeDir dir("nan");
  {
    std::ofstream csv(dir.path / "nan_gaze.csv");
    csv << "timestamp,gaze_angle_x,gaze_angle_y,AU12_r\n0,0,0,0\n0.04,0.1,-inf,0\n";
  }
  const auto r = test::runCli("drive '" + (dir.path / "nan_gaze.csv").string() + "' --out '" +
                              (dir.path / "out").string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("nan_gaze.csv:3: non-finite number '-inf' in column 'gaze_angle_y'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "out"));
}

// The FACSvatar demo take (OpenFace, 490 frames): its gaze, turned into the head by its pose, moves
// the lids against the same take without the gaze columns. The take looks down throughout
// (gaze_angle_y 0.17–0.45 rad), so the upper lids stand lower.
TEST(DriveGaze, TheDemoTakeDrivesTheLidsWithItsGaze) {
  MYO_REQUIRE_SHARED_DATA();
  GazeDir dir("demo");
  const fs::path demo = test::sharedDataDir() / "openface" / "facsvatar_demo.csv";
  const Performance perf = readPerformanceFile(demo.string());
  ASSERT_EQ(perf.gaze.size(), 490u);
  double pitchLo = 1e9, pitchHi = -1e9, yawLo = 1e9, yawHi = -1e9;
  for (const EyeGaze& g : perf.gaze) {
    pitchLo = std::min(pitchLo, g.pitchDeg[0]), pitchHi = std::max(pitchHi, g.pitchDeg[0]);
    yawLo = std::min(yawLo, g.yawDeg[0]), yawHi = std::max(yawHi, g.yawDeg[0]);
  }
  RecordProperty("gaze_pitch_deg_min", std::to_string(pitchLo));
  RecordProperty("gaze_pitch_deg_max", std::to_string(pitchHi));
  RecordProperty("gaze_yaw_deg_min", std::to_string(yawLo));
  RecordProperty("gaze_yaw_deg_max", std::to_string(yawHi));
  EXPECT_LT(pitchHi, 0.0);  // down throughout
  EXPECT_GT(pitchLo, -kGazeMaxDeg);

  // The same take without its gaze columns.
  test::copyCsvWithoutColumns(demo, dir.path / "no_gaze.csv", [](const std::string& c) { return c.rfind("gaze_", 0) == 0; });
  fs::copy_file(demo, dir.path / "gaze.csv");
  const auto a = test::runCli("drive '" + (dir.path / "gaze.csv").string() + "' --format pc2 --out '" +
                              (dir.path / "a").string() + "'");
  ASSERT_EQ(a.exitCode, 0) << a.merged;
  const auto b = test::runCli("drive '" + (dir.path / "no_gaze.csv").string() + "' --format pc2 --out '" +
                              (dir.path / "b").string() + "'");
  ASSERT_EQ(b.exitCode, 0) << b.merged;
  const PointCache with = readPc2(dir.path / "a" / "gaze.pc2"), without = readPc2(dir.path / "b" / "no_gaze.pc2");
  ASSERT_EQ(with.samples.size(), 490u);
  ASSERT_EQ(without.samples.size(), 490u);
  const LidRig& lids = *builtInPlacement().lids();
  const Vec3 yAxis = builtInHead().frame().axes.col(1);
  double largest = 0.0, upperDrop = 0.0;
  for (size_t f = 0; f < 490; ++f) {
    for (const EyeLids& eye : lids.eyes)
      for (const int v : eye.lidVertices)
        largest = std::max(largest, (with.samples[f].row(v) - without.samples[f].row(v)).norm());
    for (int eye = 0; eye < 2; ++eye) {
      const int v = upperMid(eye);
      upperDrop += (without.samples[f].row(v) - with.samples[f].row(v)).dot(yAxis.transpose()) / 980.0;
    }
  }
  RecordProperty("largest_lid_move_mm", std::to_string(10.0 * largest));
  RecordProperty("mean_upper_lid_drop_mm", std::to_string(10.0 * upperDrop));
  EXPECT_GT(largest, 0.1);      // cm
  EXPECT_LT(largest, 1.0);      // within the eyes' reach
  EXPECT_GT(upperDrop, 0.05);   // the upper lids stand lower, the take looking down
  // Nothing away from the eyes moves.
  double elsewhere = 0.0;
  std::vector<bool> nearEye(static_cast<size_t>(builtInHead().mesh.vertexCount()), false);
  for (const EyeLids& eye : lids.eyes)
    for (const int v : eye.orbitVertices) nearEye[static_cast<size_t>(v)] = true;
  for (size_t f = 0; f < 490; f += 7)
    for (int v = 0; v < builtInHead().mesh.vertexCount(); ++v)
      if (!nearEye[static_cast<size_t>(v)])
        elsewhere = std::max(elsewhere, (with.samples[f].row(v) - without.samples[f].row(v)).norm());
  RecordProperty("largest_move_away_from_the_eyes_mm", std::to_string(10.0 * elsewhere));
  EXPECT_LT(elsewhere, 0.05);

  // The blinks still close the eyes looking down (a closure closes the fissure the gaze leaves):
  // the mean lid gap over the frames with AU45 ≥ 0.5 over that where AU45 ≤ 0.1, with and without
  // the gaze, and the gap where AU45 peaks over the rest gap.
  const std::vector<double>& au45 = perf.find("AU45")->values;
  const double restGap = 0.5 * (lidGap(lids, 0, builtInHead().mesh.V) + lidGap(lids, 1, builtInHead().mesh.V));
  for (const auto& [tag, pc] : {std::pair<std::string, const PointCache*>{"gaze", &with}, {"no_gaze", &without}}) {
    double blinking = 0, open = 0;
    int nBlinking = 0, nOpen = 0;
    std::vector<double> gaps;
    for (size_t f = 0; f < 490; ++f) {
      gaps.push_back(0.5 * (lidGap(lids, 0, pc->samples[f]) + lidGap(lids, 1, pc->samples[f])));
      if (au45[f] >= 0.5) blinking += gaps.back(), ++nBlinking;
      if (au45[f] <= 0.1) open += gaps.back(), ++nOpen;
    }
    const size_t peak = std::max_element(au45.begin(), au45.end()) - au45.begin();
    const double ratio = (blinking / std::max(nBlinking, 1)) / (open / std::max(nOpen, 1));
    RecordProperty(tag + "_lid_gap_blinking_over_not", std::to_string(ratio));
    RecordProperty(tag + "_lid_gap_at_blink_peak_over_rest", std::to_string(gaps[peak] / restGap));
    RecordProperty(tag + "_lid_gap_open_mm", std::to_string(10.0 * open / std::max(nOpen, 1)));
    EXPECT_LE(ratio, 0.5) << tag;
    EXPECT_LE(gaps[peak] / restGap, 0.4) << tag;
  }
}

}  // namespace
}  // namespace myo
