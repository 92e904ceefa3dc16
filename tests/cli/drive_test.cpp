// `myoshell drive` on a real performance (../shared/data/openface/facsvatar_demo.csv, OpenFace
// action units of a person's face, 490 frames at 25 fps): the output has the performance's frames,
// and over time the face moves as the action units say — the mouth corners rise with AU12 (lip
// corner puller) and the inner brows with AU1 (inner brow raiser) less AU4 (brow lowerer).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anim/performance.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/performance_file.h"
#include "myoshell/io/retarget_map_file.h"
#include "myoshell/io/rig_file.h"
#include "support/cli_runner.h"
#include "support/csv_columns.h"
#include "support/test_data.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = a.size();
  double ma = 0, mb = 0;
  for (size_t i = 0; i < n; ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

struct DriveCorrelations {
  double mouthCornersWithAu12 = 0.0;
  double innerBrowsWithAu1MinusAu4 = 0.0;
  // The eyes (a head with open eyes): the lid gap (both eyes' mean) against AU45 (blink); the mean
  // gap over the blink frames (AU45 ≥ 0.5) over the mean gap where AU45 ≤ 0.1; the gap at the frame
  // where AU45 peaks over the gap at rest.
  double lidGapWithAu45 = 0.0;
  double lidGapBlinkingOverNot = 1.0;
  double lidGapAtBlinkPeakOverRest = 1.0;
};

// The demo performance without its jaw's action units (AU25 lips part, AU26 jaw drop), written
// beside `dir`: what the muscles alone make of it.
fs::path demoWithoutJaw(const fs::path& dir) {
  test::copyCsvWithoutColumns(test::sharedDataDir() / "openface" / "facsvatar_demo.csv", dir / "demo_no_jaw.csv",
                              [](const std::string& c) { return c == "AU25_r" || c == "AU26_r"; });
  return dir / "demo_no_jaw.csv";
}

// Drives `csv` on `headArgument` and correlates the landmarks' heights (along the face frame's y)
// with the demo's action units, frame by frame.
DriveCorrelations drive(const fs::path& csv, const std::string& headArgument, const Head& head, const fs::path& out) {
  const auto r = test::runCli("drive '" + csv.string() + "' --head " + headArgument + " --format pc2 --out '" +
                              out.string() + "' --json");
  EXPECT_EQ(r.exitCode, 0) << r.merged;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("input"), "openface");
  EXPECT_EQ(j.at("au_scale"), 1.0);
  EXPECT_EQ(j.at("frames"), 490);
  EXPECT_NEAR(j.at("fps").get<double>(), 25.0, 1e-9);
  EXPECT_NEAR(j.at("duration").get<double>(), 19.56, 1e-9);
  EXPECT_EQ(j.at("dropped_frames"), 0);
  EXPECT_TRUE(j.at("warnings").is_array());

  const PointCache pc = readPc2(out / (csv.stem().string() + ".pc2"));
  EXPECT_EQ(pc.samples.size(), 490u);
  const Performance perf = readPerformanceFile((test::sharedDataDir() / "openface" / "facsvatar_demo.csv").string());
  const std::vector<double>& au12 = perf.find("AU12")->values;
  const std::vector<double>& au1 = perf.find("AU1")->values;
  const std::vector<double>& au4 = perf.find("AU4")->values;
  const Vec3 up = head.frame().axes.col(1);
  const int cornerL = head.landmarks.vertex("mouth_corner_left"), cornerR = head.landmarks.vertex("mouth_corner_right");
  const int browL = head.landmarks.vertex("left_brow_inner"), browR = head.landmarks.vertex("right_brow_inner");
  std::vector<double> corners, brows, au14;
  for (size_t f = 0; f < pc.samples.size() && f < au12.size(); ++f) {
    const MatX3& p = pc.samples[f];
    corners.push_back(up.dot(p.row(cornerL).transpose() + p.row(cornerR).transpose()));
    brows.push_back(up.dot(p.row(browL).transpose() + p.row(browR).transpose()));
    au14.push_back(au1[f] - au4[f]);
  }
  DriveCorrelations c;
  c.mouthCornersWithAu12 = pearson(corners, std::vector<double>(au12.begin(), au12.begin() + corners.size()));
  c.innerBrowsWithAu1MinusAu4 = pearson(brows, au14);
  if (hasOpenEyes(head.mesh, head.landmarks)) {
    const LidRig lids = lidRig(head.mesh, head.landmarks);
    const std::vector<double>& au45 = perf.find("AU45")->values;
    std::vector<double> gaps;
    for (size_t f = 0; f < corners.size(); ++f)
      gaps.push_back(0.5 * (lidGap(lids, 0, pc.samples[f]) + lidGap(lids, 1, pc.samples[f])));
    const size_t peak = std::max_element(au45.begin(), au45.begin() + gaps.size()) - au45.begin();
    const double restGap = 0.5 * (lidGap(lids, 0, head.mesh.V) + lidGap(lids, 1, head.mesh.V));
    c.lidGapWithAu45 = pearson(gaps, std::vector<double>(au45.begin(), au45.begin() + gaps.size()));
    c.lidGapAtBlinkPeakOverRest = gaps[peak] / restGap;
    double blinking = 0, open = 0;
    int nBlinking = 0, nOpen = 0;
    for (size_t f = 0; f < gaps.size(); ++f) {
      if (au45[f] >= 0.5) blinking += gaps[f], ++nBlinking;
      if (au45[f] <= 0.1) open += gaps[f], ++nOpen;
    }
    EXPECT_GT(nBlinking, 0);
    EXPECT_GT(nOpen, 0);
    c.lidGapBlinkingOverNot = (blinking / std::max(nBlinking, 1)) / (open / std::max(nOpen, 1));
  }
  return c;
}

// The whole performance: the inner brows follow AU1 − AU4 and the mouth corners' height follows AU12
// (the issue asks ≥ 0.6 and ≥ 0.7 on this take), although the jaw, driven by AU25/AU26 (which rise
// with AU12 in this take: the person smiles with parted lips), lowers the corners while the
// zygomatici raise them (docs/performance_input.md, "Measured"). Without the jaw's units the corners
// follow AU12 at ≥ 0.7 too. On a head with open eyes the lids close where AU45 (blink) peaks.
void checkDemo(const std::string& headArgument, const Head& head, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("myo_drive_" + tag + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const DriveCorrelations full = drive(test::sharedDataDir() / "openface" / "facsvatar_demo.csv", headArgument, head, dir / "full");
  ::testing::Test::RecordProperty("full_mouth_corners_au12", std::to_string(full.mouthCornersWithAu12));
  ::testing::Test::RecordProperty("full_inner_brows_au1_au4", std::to_string(full.innerBrowsWithAu1MinusAu4));
  EXPECT_GE(full.innerBrowsWithAu1MinusAu4, 0.6);
  EXPECT_GE(full.mouthCornersWithAu12, 0.7);
  if (hasOpenEyes(head.mesh, head.landmarks)) {
    ::testing::Test::RecordProperty("lid_gap_au45", std::to_string(full.lidGapWithAu45));
    ::testing::Test::RecordProperty("lid_gap_at_blink_peak_over_rest", std::to_string(full.lidGapAtBlinkPeakOverRest));
    ::testing::Test::RecordProperty("lid_gap_blinking_over_not", std::to_string(full.lidGapBlinkingOverNot));
    // The gap also follows AU7 (lid tightener, at half weight on the same palpebral part; its mean
    // in this take is 0.48) and AU5, so its correlation with AU45 alone is moderate (−0.5 to −0.65).
    EXPECT_LE(full.lidGapWithAu45, -0.4);
    EXPECT_LE(full.lidGapBlinkingOverNot, 0.5);
    EXPECT_LE(full.lidGapAtBlinkPeakOverRest, 0.4);
  } else {
    ADD_FAILURE() << tag << ": the head should have open eyes";
  }
  const DriveCorrelations muscles = drive(demoWithoutJaw(dir), headArgument, head, dir / "no_jaw");
  ::testing::Test::RecordProperty("no_jaw_mouth_corners_au12", std::to_string(muscles.mouthCornersWithAu12));
  ::testing::Test::RecordProperty("no_jaw_inner_brows_au1_au4", std::to_string(muscles.innerBrowsWithAu1MinusAu4));
  EXPECT_GE(muscles.mouthCornersWithAu12, 0.7);
  EXPECT_GE(muscles.innerBrowsWithAu1MinusAu4, 0.6);
  fs::remove_all(dir);
}

TEST(DriveCli, DemoPerformanceOnTheBuiltInHead) {
  MYO_REQUIRE_SHARED_DATA();
  checkDemo("default", loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical)), "default");
}

TEST(DriveCli, DemoPerformanceOnTheIctHead) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path ict = test::sharedDataDir() / "ict";
  const Head head = loadHead((ict / "head_skin.obj").string(), (ict / "landmarks_multipie68.json").string());
  checkDemo("'" + ict.string() + "'", head, "ict");
}

// Round trip: a MediaPipe track of known weights of ICT's rig shapes drives the ICT head to within
// Σ wᵢ·rmsᵢ + 0.5 mm (per frame, RMS over the vertices that move) of the blended artist shapes, rmsᵢ
// being each shape's fit error in the shipped map. The weights ramp for 1 s and hold for 2 s; the
// frames compared are the held ones after 1 s of settling.
TEST(DriveCli, KnownRigWeightsReproduceTheBlendedShapes) {
  MYO_REQUIRE_SHARED_DATA();
  const fs::path ict = test::sharedDataDir() / "ict";
  const fs::path dir = fs::temp_directory_path() / ("myo_drive_roundtrip_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<std::pair<std::string, double>> weights = {
      {"mouthSmileLeft", 0.7}, {"browInnerUp", 0.5}, {"mouthFunnel", 0.4}};
  {
    std::ofstream jsonl(dir / "take.jsonl");
    for (int f = 0; f <= 75; ++f) {  // 3 s at 25 fps
      const double ramp = std::min(1.0, f / 25.0);
      jsonl << "{\"timestamp_ms\": " << f * 40 << ", \"blendshapes\": [{\"categoryName\": \"_neutral\", \"score\": 0.1}";
      for (const auto& [name, w] : weights)
        jsonl << ", {\"categoryName\": \"" << name << "\", \"score\": " << ramp * w << "}";
      jsonl << "]}\n";
    }
  }
  const auto r = test::runCli("drive '" + (dir / "take.jsonl").string() + "' --head '" + ict.string() +
                              "' --filter off --format pc2 --out '" + (dir / "out").string() + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const PointCache pc = readPc2(dir / "out" / "take.pc2");
  ASSERT_EQ(pc.samples.size(), 76u);

  const RigFile rig = readRig((ict / "ict_arkit_rig.glb").string());
  const Head head = loadHead((ict / "head_skin.obj").string(), (ict / "landmarks_multipie68.json").string());
  ASSERT_EQ(rig.vertexCount(), head.mesh.vertexCount());
  const RetargetMap map = readRetargetMapFile((test::sourceDir() / "assets/retarget/arkit_ict_face.json").string());
  MatX3 blended = MatX3::Zero(head.mesh.vertexCount(), 3);
  double bound = 0.5;  // mm
  for (const auto& [name, w] : weights) {
    for (const std::string& ictName : ictNamesOf(name)) blended += w * rig.delta(ictName);
    const RetargetShape* shape = map.find(name);
    ASSERT_TRUE(shape && shape->fit) << name;
    bound += w * shape->fit->rmsMm;
  }
  for (int f = 50; f <= 75; f += 5) {
    const MatX3 u = pc.samples[f] - head.mesh.V;
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < u.rows(); ++i) {
      if (u.row(i).norm() <= 0.05 && blended.row(i).norm() <= 0.05) continue;
      sum += (u.row(i) - blended.row(i)).squaredNorm();
      ++count;
    }
    const double rmsMm = 10.0 * std::sqrt(sum / std::max(1, count));
    RecordProperty("rms_mm_frame_" + std::to_string(f), std::to_string(rmsMm));
    EXPECT_LE(rmsMm, bound) << "frame " << f;
  }
  fs::remove_all(dir);
}

TEST(DriveCli, BadArgumentsExitTwoBeforeAnyWork) {
  const fs::path out = fs::temp_directory_path() / ("myo_drive_bad_" + std::to_string(::getpid()));
  auto r = test::runCli("drive /no/such/file.csv --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("/no/such/file.csv: cannot open performance file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  MYO_REQUIRE_SHARED_DATA();
  const fs::path csv = test::sharedDataDir() / "openface" / "facsvatar_demo.csv";
  r = test::runCli("drive '" + csv.string() + "' --filter maybe --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--filter: expected on or off (got 'maybe')"), std::string::npos) << r.err;
  r = test::runCli("drive '" + csv.string() + "' --start 5 --end 2 --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--end 2 must lie after --start 5"), std::string::npos) << r.err;
  r = test::runCli("drive '" + csv.string() + "' --input livelink --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.merged;
  r = test::runCli("drive '" + csv.string() + "' --video --framing bust --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.merged;
  EXPECT_NE(r.err.find("unknown framing 'bust' (use face, head or all)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// A window that is empty or reversed is an error naming the options, before the take is read
// (a negative --end once meant "to the last frame" and played the whole take).
TEST(DriveCli, AnEmptyOrReversedWindowIsRefused) {
  const fs::path out = fs::temp_directory_path() / ("myo_drive_window_" + std::to_string(::getpid()));
  const std::string take = "'" + (test::sourceDir() / "tests" / "bad_inputs" / "performance_nan.csv").string() + "'";
  auto r = test::runCli("drive " + take + " --end -1 --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err, "myoshell: error: --end: must be > 0, got -1 (see myoshell drive --help)\n");
  r = test::runCli("drive " + take + " --start 2 --end 2 --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--end 2 must lie after --start 2"), std::string::npos) << r.err;
  r = test::runCli("drive " + take + " --start -0.5 --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--start: must be ≥ 0, got -0.5"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace myo
