// The FACS map (fit/facs_map.h, assets/facs/au_map.json, docs/facs.md): the shipped map reads
// against the face's muscles, holds every OpenFace AU, drives every muscle of the face exactly by the
// AUs its definition names, and leaves only the jaw's and the lids' AUs unplayed; a map reads back to
// itself; every fault is refused with file:line:col; intensities become activations by weighted sums
// clamped to 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "myoshell/anatomy/mouth_pressure.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/facs_map.h"
#include "myoshell/io/facs_map_file.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/test_data.h"

namespace myo {
namespace {

std::vector<std::string> faceMuscleNames() {
  std::vector<std::string> names;
  for (const MuscleDef& def : faceMuscleDefs()) names.push_back(def.name);
  return names;
}

// The AU numbers of a muscle definition's `facs` field ("AU4 AU9" → {4, 9}).
std::set<int> ausOfFacsField(const std::string& facs) {
  std::set<int> aus;
  std::istringstream in(facs);
  std::string token;
  while (in >> token) {
    EXPECT_EQ(token.rfind("AU", 0), 0u) << facs;
    aus.insert(std::stoi(token.substr(2)));
  }
  return aus;
}

TEST(FacsMap, TheShippedMapReadsAgainstTheFaceLibraryAndIsTheFileOnDisk) {
  const FacsMap& map = builtinFacsMap();
  // OpenFace's 17, the eight more the muscles make, the jaw's AU27, 29, 30, the cheeks' air AU34
  // and the eyes' AU61–64.
  ASSERT_EQ(map.entries.size(), 33u);
  const FacsMap fromFile = readFacsMapFile((test::sourceDir() / "assets/facs/au_map.json").string(), faceMuscleNames());
  EXPECT_EQ(serialiseFacsMap(fromFile), serialiseFacsMap(map));
  std::vector<int> order;
  for (const FacsEntry& e : map.entries) order.push_back(e.au);
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));
  ASSERT_NE(map.find(12), nullptr);
  EXPECT_EQ(map.find(12)->name, "lip corner puller");
  EXPECT_EQ(map.find(3), nullptr);  // FACS has no AU3
}

TEST(FacsMap, EveryOpenFaceIntensityAuIsThereAndFlagged) {
  const FacsMap& map = builtinFacsMap();
  std::vector<int> flagged;
  for (const FacsEntry& e : map.entries)
    if (e.openface) flagged.push_back(e.au);
  EXPECT_EQ(flagged, (std::vector<int>{1, 2, 4, 5, 6, 7, 9, 10, 12, 14, 15, 17, 20, 23, 25, 26, 45}));
  EXPECT_EQ(flagged, openFaceIntensityAus());
}

TEST(FacsMap, EveryFaceMuscleIsDrivenByExactlyTheAusItsDefinitionNames) {
  std::map<std::string, std::set<int>> drivenBy;
  for (const FacsEntry& e : builtinFacsMap().entries)
    for (const auto& [muscle, weight] : e.muscles) {
      drivenBy[muscle].insert(e.au);
      EXPECT_GT(weight, 0.0) << "AU" << e.au << " " << muscle;
    }
  ASSERT_EQ(faceMuscleDefs().size(), 40u);
  for (const MuscleDef& def : faceMuscleDefs()) EXPECT_EQ(drivenBy[def.name], ausOfFacsField(def.facs)) << def.name;
  EXPECT_EQ(drivenBy.size(), 40u);  // and no other muscle
}

TEST(FacsMap, EveryAuDrivesMusclesOrTheJawAndTheLidsAusDriveTheLids) {
  std::map<int, std::string> needs;
  for (const FacsEntry& e : builtinFacsMap().entries) {
    EXPECT_EQ(e.muscles.empty() && !e.movesJaw() && !e.turnsEyes() && e.mouthPressureKpa == 0.0, !e.needs.empty()) << "AU" << e.au;
    if (!e.needs.empty()) needs[e.au] = e.needs;
  }
  EXPECT_TRUE(needs.empty());
  // The lids (docs/eyelids.md): a blink closes them, AU5 raises the upper lid, AU7 narrows them by
  // half a blink.
  auto weight = [](int au, const std::string& muscle) {
    for (const auto& [name, w] : builtinFacsMap().find(au)->muscles)
      if (name == muscle) return w;
    return 0.0;
  };
  for (const std::string side : {"left", "right"}) {
    EXPECT_DOUBLE_EQ(weight(45, "orbicularis_oculi_palpebral_" + side), 1.0);
    EXPECT_DOUBLE_EQ(weight(5, "levator_palpebrae_superioris_" + side), 1.0);
    EXPECT_DOUBLE_EQ(weight(7, "orbicularis_oculi_palpebral_" + side), 0.5);
  }
  // The jaw's AUs open, thrust and shift it (docs/facs.md).
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(25)->jawOpenDeg, 2.0);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(26)->jawOpenDeg, 12.0);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(27)->jawOpenDeg, 35.0);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(29)->jawForwardCm, 0.8);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(30)->jawLateralCm, 1.0);
  // The eyes' AUs turn them 25° (pitch + up, yaw + the subject's left), muscles none: the lids follow.
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(61)->gazeYawDeg, 25.0);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(62)->gazeYawDeg, -25.0);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(63)->gazePitchDeg, 25.0);
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(64)->gazePitchDeg, -25.0);
  for (int au : {61, 62, 63, 64}) EXPECT_TRUE(builtinFacsMap().find(au)->muscles.empty()) << "AU" << au;
  // The puff holds 2 kPa of air and drives no muscle (docs/anatomical_model.md, "Air in the mouth").
  EXPECT_DOUBLE_EQ(builtinFacsMap().find(34)->mouthPressureKpa, kCheekPuffPressureKpa);
  EXPECT_TRUE(builtinFacsMap().find(34)->muscles.empty());
}

TEST(FacsMap, ReadsBackToItselfWithEveryNumberExact) {
  FacsMap map;
  map.note = "by hand";
  map.entries.push_back({12, "lip corner puller", true, {{"b", 0.1 + 0.2}, {"a", 1.0}}, "", "first b, then a"});
  map.entries.push_back({26, "jaw drop", true, {}, "jaw", ""});
  map.entries.push_back({11, "nasolabial deepener", false, {{"c", 0.0}}, "", ""});
  FacsEntry eyes{63, "eyes up", false, {}, "", ""};
  eyes.gazePitchDeg = 0.1 + 24.8;
  eyes.gazeYawDeg = -3.0;
  map.entries.push_back(eyes);
  const std::string text = serialiseFacsMap(map);
  const FacsMap back = parseFacsMap(text, "map.json");
  EXPECT_EQ(serialiseFacsMap(back), text);
  ASSERT_EQ(back.entries.size(), 4u);
  EXPECT_EQ(back.entries[3].gazePitchDeg, 0.1 + 24.8);
  EXPECT_EQ(back.entries[3].gazeYawDeg, -3.0);
  EXPECT_EQ(back.note, "by hand");
  EXPECT_EQ(back.entries[0].muscles, (std::vector<std::pair<std::string, double>>{{"b", 0.1 + 0.2}, {"a", 1.0}}));
  EXPECT_EQ(back.entries[0].note, "first b, then a");
  EXPECT_EQ(back.entries[1].needs, "jaw");
  EXPECT_FALSE(back.entries[2].openface);
}

TEST(FacsMap, YamlReadsAndOpenfaceDefaultsToOpenFacesList) {
  const FacsMap map = parseFacsMap("aus:\n  - {au: 12, name: smile, muscles: {z: 1}}\n  - {au: 13, name: sharp, muscles: {l: 0.5}}\n",
                                   "map.yaml");
  EXPECT_TRUE(map.entries[0].openface);
  EXPECT_FALSE(map.entries[1].openface);
  EXPECT_EQ(map.entries[1].muscles[0].second, 0.5);
}

std::string facsError(const std::string& text, const std::vector<std::string>& muscles = {}) {
  try {
    parseFacsMap(text, "map.json", muscles);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FacsMap, EveryFaultIsRefusedWithItsPlaceAndWhatIsWrong) {
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"a": 1}}], "version": 1})"),
            "map.json:1:57: key 'version': unknown key");
  EXPECT_EQ(facsError(R"({"note": "x"})"), "map.json:1:1: key 'aus': missing required key");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 63, "name": "x", "muscles": {}, "gaze": {"pitch": 50}}]})"),
            "map.json:1:67: key 'aus[0].gaze.pitch': must lie in [-45, 45] (got 50)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 63, "name": "x", "muscles": {}, "gaze": {"roll": 5}}]})"),
            "map.json:1:58: key 'aus[0].gaze.roll': unknown key");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 63, "name": "x", "muscles": {}, "gaze": {}}]})"),
            "map.json:1:57: key 'aus[0].gaze': turns nothing: give pitch or yaw, or leave the key out");
  EXPECT_EQ(facsError(R"({"aus": []})"), "map.json:1:9: key 'aus': must hold at least one action unit");
  EXPECT_EQ(facsError(R"({"aus": {"au": 1}})"), "map.json:1:9: key 'aus': must be a list of {au, name, muscles, …}");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 0, "name": "x", "muscles": {"a": 1}}]})"),
            "map.json:1:17: key 'aus[0].au': must be a positive integer up to 999 (got 0)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 1.5, "name": "x", "muscles": {"a": 1}}]})"),
            "map.json:1:17: key 'aus[0].au': must be a positive integer up to 999 (got 1.5)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": "12", "name": "x", "muscles": {"a": 1}}]})"),
            "map.json:1:17: key 'aus[0].au': must be a number");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "a", "muscles": {"a": 1}},)"
                  "\n"
                  R"(         {"au": 12.0, "name": "b", "muscles": {"b": 1}}]})"),
            "map.json:2:17: key 'aus[1].au': AU12 is already given by aus[0]");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "", "muscles": {"a": 1}}]})"),
            "map.json:1:29: key 'aus[0].name': must name the action unit (FACS's name, e.g. \"lip corner puller\")");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "openface": false, "muscles": {"a": 1}}]})"),
            "map.json:1:46: key 'aus[0].openface': AU12 is one of OpenFace 2.0's intensity AUs: write true");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 11, "name": "x", "openface": true, "muscles": {"a": 1}}]})"),
            "map.json:1:46: key 'aus[0].openface': OpenFace 2.0 estimates no intensity for AU11 (its AUs: AU1, AU2, "
            "AU4, AU5, AU6, AU7, AU9, AU10, AU12, AU14, AU15, AU17, AU20, AU23, AU25, AU26, AU45)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"a": 1.5}}]})"),
            "map.json:1:51: key 'aus[0].muscles.a': weight 1.5 is outside [0, 1]");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"a": -0.25}}]})"),
            "map.json:1:51: key 'aus[0].muscles.a': weight -0.25 is outside [0, 1]");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"": 0.5}}]})"),
            "map.json:1:46: key 'aus[0].muscles.': a muscle name cannot be empty");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"a": 0.5, "a": 0.5}}]})"),
            "map.json:1:56: key 'aus[0].muscles.a': is given twice");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"zygomaticus_major": 1}}]})",
                  {"zygomaticus_major_left", "zygomaticus_major_right", "procerus"}),
            "map.json:1:46: key 'aus[0].muscles.zygomaticus_major': unknown muscle 'zygomaticus_major' (did you mean "
            "zygomaticus_major_left, zygomaticus_major_right?)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"frontalis": 1}}]})", {"procerus", "mentalis_left"}),
            "map.json:1:46: key 'aus[0].muscles.frontalis': unknown muscle 'frontalis' (the muscles: procerus, "
            "mentalis_left)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 26, "name": "x", "muscles": {"a": 1}, "needs": "jaw"}]})"),
            "map.json:1:64: key 'aus[0].needs': an AU with muscles, a jaw or a gaze needs nothing more: give those, or needs, not "
            "both");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 26, "name": "x", "muscles": {}}]})"),
            "map.json:1:45: key 'aus[0].muscles': drives no muscle: list its muscles, give its jaw or gaze, or say in 'needs' "
            "what the model lacks");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 26, "name": "x", "muscles": {}, "jaw": {"open": 50}}]})"),
            "map.json:1:65: key 'aus[0].jaw.open': must lie in [0, 40] (got 50)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 26, "name": "x", "muscles": {}, "jaw": {}}]})"),
            "map.json:1:56: key 'aus[0].jaw': moves nothing: give open, forward or lateral, or leave the key out");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 26, "name": "x", "muscles": {}, "jaw": {"open": 5}, "needs": "lids"}]})"),
            "map.json:1:78: key 'aus[0].needs': an AU with muscles, a jaw or a gaze needs nothing more: give those, or needs, "
            "not both");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 26, "name": "x", "muscles": {}, "needs": ""}]})"),
            "map.json:1:58: key 'aus[0].needs': must say what the model lacks (e.g. \"lids\")");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": [1]}]})"),
            "map.json:1:45: key 'aus[0].muscles': must be an object of muscle: weight ({} when the AU drives none yet)");
  EXPECT_EQ(facsError(R"({"aus": [{"au": 12, "name": "x", "muscles": {"a": 1}, "weight": 1}]})"),
            "map.json:1:55: key 'aus[0].weight': unknown key");
}

TEST(FacsMap, AFileNamesItselfInItsErrors) {
  EXPECT_THROW(readFacsMapFile("/nonexistent/au_map.json"), InputError);
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "myoshell_facs_map_test.json";
  std::ofstream(path) << "{\"aus\": [{\"au\": 12, \"name\": \"x\", \"muscles\": {\"z\": 1}}]}\n";
  try {
    readFacsMapFile(path.string(), {"procerus"});
    ADD_FAILURE() << "an unknown muscle was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.line(), 1);
    EXPECT_EQ(e.column(), 46);  // the muscle's name
  }
  std::filesystem::remove(path);
}

// Two AUs sharing muscle b, and one the model cannot play yet.
const FacsMap& smallMap() {
  static const FacsMap map = parseFacsMap(R"({"aus": [
      {"au": 1, "name": "one", "muscles": {"a": 0.5, "b": 1.0}},
      {"au": 2, "name": "two", "muscles": {"b": 0.75, "c": 0.25}},
      {"au": 26, "name": "jaw drop", "muscles": {}, "needs": "jaw"}]})",
                                          "small.json");
  return map;
}

TEST(FacsActivations, WeightedIntensitiesAddAndTheSumIsClampedToOne) {
  const std::vector<std::string> muscles = {"d", "c", "b", "a"};
  VecX a = activationsForAus(smallMap(), {{1, 0.5}}, muscles);
  EXPECT_EQ(a, (VecX(4) << 0.0, 0.0, 0.5, 0.25).finished());
  a = activationsForAus(smallMap(), {{1, 0.25}, {2, 0.5}}, muscles);
  EXPECT_EQ(a, (VecX(4) << 0.0, 0.125, 0.25 + 0.375, 0.125).finished());
  a = activationsForAus(smallMap(), {{2, 1.0}, {1, 0.5}}, muscles);  // b: 0.5 + 0.75 = 1.25 → 1
  EXPECT_EQ(a, (VecX(4) << 0.0, 0.25, 1.0, 0.25).finished());
  a = activationsForAus(smallMap(), {{26, 1.0}, {1, 0.0}}, muscles);  // the jaw drop has nothing to drive yet
  EXPECT_EQ(a, VecX::Zero(4));
  EXPECT_EQ(activationsForAus(smallMap(), {}, muscles), VecX::Zero(4));
}

TEST(FacsActivations, OnlyTheGivenAusNeedTheirMuscles) {
  // Without c, AU2 cannot be played; AU1 alone can.
  EXPECT_EQ(activationsForAus(smallMap(), {{1, 1.0}}, {"a", "b"}), (VecX(2) << 0.5, 1.0).finished());
  try {
    activationsForAus(smallMap(), {{1, 1.0}, {2, 0.0}}, {"a", "b"});
    ADD_FAILURE() << "a muscle of a given AU was dropped";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "AU2 (two) drives c, which is not among the muscles played; leave AU2 out to play without it");
  }
}

std::string activationError(const AuIntensities& intensities) {
  try {
    activationsForAus(smallMap(), intensities, {"a", "b", "c"});
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FacsActivations, BadIntensitiesAreRefusedNamingTheAu) {
  EXPECT_EQ(activationError({{3, 0.5}}), "AU3 is not in the FACS map");
  EXPECT_EQ(activationError({{1, 0.5}, {1, 0.25}}), "AU1 is given twice");
  EXPECT_EQ(activationError({{2, 1.5}}), "AU2: intensity 1.5 is outside [0, 1]");
  EXPECT_EQ(activationError({{2, -0.25}}), "AU2: intensity -0.25 is outside [0, 1]");
  EXPECT_EQ(activationError({{2, std::numeric_limits<double>::quiet_NaN()}}), "AU2: intensity nan is outside [0, 1]");
  EXPECT_THROW(activationsForAus(smallMap(), {{1, 0.5}}, {"a", "b", "a"}), CheckError);
}

TEST(FacsActivations, TheShippedMapDrivesBothSidesAndClampsTheProcerus) {
  const std::vector<std::string> names = faceMuscleNames();
  std::map<std::string, double> byName;
  const VecX smile = activationsForAus(builtinFacsMap(), {{12, 0.6}}, names);
  for (size_t m = 0; m < names.size(); ++m) byName[names[m]] = smile(static_cast<Eigen::Index>(m));
  EXPECT_EQ(byName["zygomaticus_major_left"], 0.6);
  EXPECT_EQ(byName["zygomaticus_major_right"], 0.6);
  EXPECT_EQ(smile.sum(), 1.2);  // nothing else moves
  // AU4 (procerus 1) with AU9 (procerus 0.5), both at full intensity: the procerus is clamped to 1.
  const VecX frown = activationsForAus(builtinFacsMap(), {{4, 1.0}, {9, 1.0}}, names);
  for (size_t m = 0; m < names.size(); ++m) byName[names[m]] = frown(static_cast<Eigen::Index>(m));
  EXPECT_EQ(byName["procerus"], 1.0);
  EXPECT_EQ(byName["corrugator_supercilii_left"], 1.0);
  EXPECT_EQ(byName["levator_labii_superioris_alaeque_nasi_right"], 1.0);
  EXPECT_EQ(frown.maxCoeff(), 1.0);
  // Every AU of the map at full intensity at once: every muscle at most 1, none left at 0.
  AuIntensities all;
  for (const FacsEntry& e : builtinFacsMap().entries) all.emplace_back(e.au, 1.0);
  const VecX everything = activationsForAus(builtinFacsMap(), all, names);
  EXPECT_EQ(everything.maxCoeff(), 1.0);
  EXPECT_GT(everything.minCoeff(), 0.0);
}

}  // namespace
}  // namespace myo
