#include <gtest/gtest.h>

#include <fstream>

#include "myoshell/core/errors.h"
#include "myoshell/head/head.h"
#include "myoshell/head/landmarks.h"
#include "myoshell/io/head_files.h"
#include "support/test_data.h"

namespace myo {
namespace {

std::string landmarkErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

std::string plainMapAll() {
  std::string s = "{";
  int id = 0;
  for (const RequiredLandmark& r : kRequiredLandmarks) {
    s += std::string(id ? ", " : "") + "\"" + r.name + "\": " + std::to_string(id);
    ++id;
  }
  return s + "}";
}

TEST(Landmarks, AcceptsTheIctLayoutAndAPlainMap) {
  const std::string layout = R"({"source": "x", "multipie68": [)" + [] {
    std::string s;
    for (int i = 0; i < 68; ++i) s += (i ? "," : "") + std::to_string(100 + i);
    return s;
  }() + R"(], "groups": {"jaw": [1]}, "named": {"nose_tip": {"multipie_index": 30, "vertex": 7}, "extra": 9}})";
  const Landmarks a = parseLandmarks(layout, 200);
  EXPECT_EQ(a.vertex("nose_tip"), 7);          // named wins
  EXPECT_EQ(a.vertex("chin_menton"), 108);     // Multi-PIE point 8
  EXPECT_EQ(a.vertex("extra"), 9);
  a.requireAll();
  const Landmarks b = parseLandmarks(plainMapAll(), 200);
  EXPECT_TRUE(b.multipie68.empty());
  EXPECT_EQ(b.vertex("right_eye_outer"), 0);
  b.requireAll();
  // Round trip through the writer.
  const Landmarks c = parseLandmarks(landmarksToJson(a), 200);
  EXPECT_EQ(c.multipie68, a.multipie68);
  EXPECT_EQ(c.named, a.named);
}

TEST(Landmarks, MissingFileIsNamed) {
  const std::string msg = landmarkErrorOf([] { readLandmarks("/nonexistent/lm.json", 10); });
  EXPECT_EQ(msg, "/nonexistent/lm.json: cannot open landmark file");
}

TEST(Landmarks, VertexIdOutOfRangeNamesTheLandmark) {
  EXPECT_EQ(landmarkErrorOf([] { parseLandmarks(R"({"nose_tip": 12})", 10, "lm.json"); }),
            "lm.json: landmark 'nose_tip': vertex id 12 out of range [0, 10)");
  EXPECT_EQ(landmarkErrorOf([] { parseLandmarks(R"({"named": {"chin_menton": {"vertex": -1}}})", 10, "lm.json"); }),
            "lm.json: landmark 'chin_menton': vertex id -1 out of range [0, 10)");
  EXPECT_EQ(landmarkErrorOf([] { parseLandmarks(R"({"multipie68": [1, 2]})", 10, "lm.json"); }),
            "lm.json: multipie68 must hold 68 vertex ids, got 2");
}

TEST(Landmarks, MissingRequiredNameIsNamed) {
  std::string text = plainMapAll();
  text.replace(text.find("\"nose_tip\""), 10, "\"nose_tipp\"");
  const Landmarks lm = parseLandmarks(text, 100, "mine.json");
  EXPECT_EQ(landmarkErrorOf([&] { lm.requireAll(); }),
            "mine.json: missing landmark 'nose_tip' (give it under \"named\" or as Multi-PIE point "
            "30 in \"multipie68\")");
}

TEST(Landmarks, BadJsonNamesTheLine) {
  const std::string text = "{\n  \"nose_tip\": 3,\n  \"chin_menton\" 4\n}\n";
  const std::string msg = landmarkErrorOf([&] { parseLandmarks(text, 10, "bad.json"); });
  EXPECT_EQ(msg.rfind("bad.json:3:", 0), 0u) << msg;
  EXPECT_NE(msg.find("bad JSON in landmark file: syntax error"), std::string::npos) << msg;
}

TEST(Landmarks, LoadHeadReportsLandmarkErrorsWithTheFile) {
  MYO_REQUIRE_SHARED_DATA();
  const auto obj = (test::sharedDataDir() / "ict" / "head_skin.obj").string();
  const std::string path = testing::TempDir() + "/partial_landmarks.json";
  std::ofstream(path) << R"({"named": {"nose_tip": {"vertex": 4857}}})";
  EXPECT_EQ(landmarkErrorOf([&] { loadHead(obj, path); }),
            path + ": missing landmark 'right_eye_outer' (give it under \"named\" or as Multi-PIE "
                   "point 36 in \"multipie68\")");
  std::ofstream(path) << R"({"nose_tip": 11248})";
  EXPECT_EQ(landmarkErrorOf([&] { loadHead(obj, path); }),
            path + ": landmark 'nose_tip': vertex id 11248 out of range [0, 11248)");
}

}  // namespace
}  // namespace myo
