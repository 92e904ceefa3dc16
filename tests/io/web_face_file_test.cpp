// The web page's face data (io/web_face_file.h): the whole face's muscles and a basis round-trip
// (Φ to float32, the rest exactly); truncated, damaged and foreign files are refused with the
// reason; the page's cache serves only its key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "myoshell/core/errors.h"
#include "myoshell/io/web_face_file.h"
#include "web_face_seeds.h"

namespace myo {
namespace {

ModalBasis smallBasis() {
  ModalBasis b;
  b.fullVertexCount = 4;
  b.freeVertices = {0, 1, 2, 3};
  b.lambda = VecX::LinSpaced(3, 10.0, 30.0);
  b.freeMass = VecX::Constant(4, 0.25) + VecX::LinSpaced(4, 0.0, 1e-9);
  b.Phi = MatX::Random(12, 3);
  b.Psi = MatX::Random(12, 3);
  return b;
}

BasisKey someKey() {
  BasisKey k;
  k.words = {0x0123456789abcdefULL, 0xfedcba9876543210ULL};
  return k;
}

std::string messageOf(const std::string& bytes) {
  try {
    readWebFace(bytes, "face.myoweb");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(WebFaceFile, TheWholeFacesMusclesAndTheBasisRoundTrip) {
  const std::vector<MuscleDef>& muscles = faceMuscleDefs();
  const ModalBasis b = smallBasis();
  const WebFace w = readWebFace(webFaceBytes(muscles, someKey(), b), "face.myoweb");
  ASSERT_EQ(w.muscles.size(), muscles.size());
  for (size_t m = 0; m < muscles.size(); ++m) {
    const MuscleDef &a = muscles[m], &c = w.muscles[m];
    EXPECT_EQ(a.name, c.name);
    EXPECT_EQ(a.kind, c.kind);
    EXPECT_EQ(a.side, c.side);
    EXPECT_EQ(a.origin.landmark, c.origin.landmark);
    EXPECT_EQ(a.origin.offset, c.origin.offset);
    EXPECT_EQ(a.insertion.depth, c.insertion.depth);
    EXPECT_EQ(a.width, c.width);
    EXPECT_EQ(a.contraction, c.contraction);
    EXPECT_EQ(a.coupling.has_value(), c.coupling.has_value());
    if (a.coupling) EXPECT_EQ(*a.coupling, *c.coupling);
    ASSERT_EQ(a.ring.path.size(), c.ring.path.size());
    for (size_t k = 0; k < a.ring.path.size(); ++k) EXPECT_EQ(a.ring.path[k].offset, c.ring.path[k].offset);
    EXPECT_EQ(a.ring.anchors[1].landmark, c.ring.anchors[1].landmark);
    EXPECT_EQ(a.ring.shortening, c.ring.shortening);
    EXPECT_EQ(a.ring.alongSkin, c.ring.alongSkin);
    EXPECT_EQ(a.thickens, c.thickens);
    EXPECT_EQ(a.ring.lipBody, c.ring.lipBody);
    ASSERT_EQ(a.pushes.has_value(), c.pushes.has_value());
    if (a.pushes) EXPECT_EQ(a.pushes->offset, c.pushes->offset);
    if (a.pushes) EXPECT_EQ(a.pushes->landmark, c.pushes->landmark);
    ASSERT_EQ(a.continuesInto.has_value(), c.continuesInto.has_value());
    if (a.continuesInto) EXPECT_EQ(a.continuesInto->landmark, c.continuesInto->landmark);
  }
  EXPECT_EQ(w.basisKey, someKey());
  EXPECT_EQ(w.basis.fullVertexCount, 4);
  EXPECT_EQ(w.basis.freeVertices, b.freeVertices);
  EXPECT_EQ(w.basis.lambda, b.lambda);      // exact: a skin's fit compares the masses bit for bit
  EXPECT_EQ(w.basis.freeMass, b.freeMass);
  EXPECT_EQ(w.basis.Phi, b.Phi.cast<float>().cast<double>());  // float32
  EXPECT_GT((w.basis.Phi - b.Phi).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((w.basis.Phi - b.Phi).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(w.basis.Psi, MatX::Zero(12, 3));  // not stored: the page steps linear modes
}

TEST(WebFaceFile, TruncatedDamagedAndForeignFilesAreRefusedWithTheReason) {
  const std::string good = webFaceBytes(faceMuscleDefs(), someKey(), smallBasis());
  EXPECT_NE(messageOf("not a face at all"), "");
  EXPECT_NE(messageOf("not a face at all").find("no MYOWEBF1 magic"), std::string::npos);
  std::string damaged = good;
  damaged[damaged.size() / 2] ^= 0x40;
  EXPECT_NE(messageOf(damaged).find("checksum mismatch"), std::string::npos) << messageOf(damaged);
  const std::string cut = good.substr(0, good.size() - 100);
  EXPECT_NE(messageOf(cut).find("checksum mismatch"), std::string::npos) << messageOf(cut);
  EXPECT_EQ(messageOf(good), "");
}

// A take keeps its name, duration, fps and every key (time, value, interpolation) of its activation
// and jaw tracks; a scene with more on its timeline (a head pose) is refused by the writer, naming it.
TEST(WebFaceFile, TakesRoundTripAndATimelineBeyondActivationsAndJawIsRefused) {
  SceneDesc take;
  take.name = "smile";
  take.duration = 1.5;
  take.fps = 24.0;
  take.activations["zygomaticus_major_left"] =
      ScalarTrack({{0.0, 0.0, Interpolation::Smooth}, {0.5, 0.75, Interpolation::Step}, {1.0, 0.25}});
  take.jawOpen = ScalarTrack({{0.2, 0.0}, {0.9, 12.5, Interpolation::Smooth}});
  const WebFace w = readWebFace(webFaceBytes(faceMuscleDefs(), someKey(), smallBasis(), {take}), "face.myoweb");
  ASSERT_EQ(w.takes.size(), 1u);
  const SceneDesc& t = w.takes[0];
  EXPECT_EQ(t.name, "smile");
  EXPECT_EQ(t.duration, 1.5);
  EXPECT_EQ(t.fps, 24.0);
  ASSERT_EQ(t.activations.size(), 1u);
  const auto& keys = t.activations.at("zygomaticus_major_left").keys();
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_EQ(keys[1].time, 0.5);
  EXPECT_EQ(keys[1].value, 0.75);
  EXPECT_EQ(keys[1].interpolation, Interpolation::Step);
  EXPECT_EQ(keys[0].interpolation, Interpolation::Smooth);
  EXPECT_EQ(t.jawOpen.at(0.9), 12.5);
  EXPECT_TRUE(t.jawForward.empty());
  EXPECT_TRUE(t.jawLateral.empty());
  for (double time : {0.1, 0.3, 0.6, 1.2}) EXPECT_EQ(t.activations.at("zygomaticus_major_left").at(time),
                                                     take.activations.at("zygomaticus_major_left").at(time));
  take.headPose = HeadPoseTrack({{0.0, Vec3(10.0, 0.0, 0.0), Interpolation::Linear}});
  try {
    webFaceBytes(faceMuscleDefs(), someKey(), smallBasis(), {take});
    FAIL() << "a take with a head pose was written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("take 'smile' has a head pose"), std::string::npos) << e.what();
  }
}

// The shipped FACS map round-trips entry for entry (muscles and weights, jaw, gaze, air, needs), so
// the page's action units drive what drive's do.
TEST(WebFaceFile, TheFacsMapRoundTrips) {
  const FacsMap& map = builtinFacsMap();
  const WebFace w = readWebFace(webFaceBytes(faceMuscleDefs(), someKey(), smallBasis(), {}, map), "face.myoweb");
  ASSERT_EQ(w.facs.entries.size(), map.entries.size());
  for (size_t k = 0; k < map.entries.size(); ++k) {
    const FacsEntry &a = map.entries[k], &b = w.facs.entries[k];
    EXPECT_EQ(a.au, b.au);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.openface, b.openface);
    EXPECT_EQ(a.muscles, b.muscles);
    EXPECT_EQ(a.needs, b.needs);
    EXPECT_EQ(a.jawOpenDeg, b.jawOpenDeg);
    EXPECT_EQ(a.jawForwardCm, b.jawForwardCm);
    EXPECT_EQ(a.jawLateralCm, b.jawLateralCm);
    EXPECT_EQ(a.gazePitchDeg, b.gazePitchDeg);
    EXPECT_EQ(a.gazeYawDeg, b.gazeYawDeg);
    EXPECT_EQ(a.mouthPressureKpa, b.mouthPressureKpa);
  }
  EXPECT_NE(w.facs.find(12), nullptr);
}

// The refusals fuzz_web_face led to (docs/RELIABILITY.md, findings): with the checksum made right,
// a string longer than the file, a head of −1 vertices, a free vertex outside the head, a NaN in Φ
// and a flag byte other than 0 or 1 are refused with the reason, never allocated or read on.
TEST(WebFaceFile, DamageBehindAGoodChecksumIsRefusedWithTheReason) {
  const auto resum = [](std::string b) {
    const uint64_t sum = fnv1a64(b.data(), b.size() - 8);
    std::memcpy(b.data() + b.size() - 8, &sum, 8);
    return b;
  };
  const std::vector<MuscleDef> one = {faceMuscleDefs().front()};
  const std::string good = webFaceBytes(one, someKey(), smallBasis());
  const size_t name = 16;  // the first muscle's name length: after magic, version, count
  std::string longName = good;
  const uint32_t huge = 0xa0000000u;
  std::memcpy(longName.data() + name, &huge, 4);
  EXPECT_NE(messageOf(resum(longName)).find("a string of 2684354560 bytes"), std::string::npos) << messageOf(resum(longName));
  // The basis starts after the muscles: its key (16 bytes), then the head's vertex count.
  const size_t basis = webFaceBytes(one, someKey(), smallBasis()).size() - 8 - 4 - 4 /*takes, AUs*/ -
                       (12 * 3 * 4 + 3 * 8 + 4 * 8 + 4 * 4) - 12 - 16;
  std::string minus = good;
  const uint32_t all = 0xffffffffu;
  std::memcpy(minus.data() + basis + 16, &all, 4);
  EXPECT_NE(messageOf(resum(minus)).find("a head of 4294967295 vertices"), std::string::npos) << messageOf(resum(minus));
  std::string outside = good;
  const int32_t far = 9;
  std::memcpy(outside.data() + basis + 16 + 12, &far, 4);
  EXPECT_NE(messageOf(resum(outside)).find("free vertex 9 is outside the head's 4 vertices"), std::string::npos)
      << messageOf(resum(outside));
  ModalBasis nan = smallBasis();
  nan.Phi(5, 1) = std::nan("");
  EXPECT_NE(messageOf(webFaceBytes(one, someKey(), nan)).find("not finite"), std::string::npos);
}

TEST(WebFaceFile, ImportedMusclesAreRefusedByTheWriter) {
  std::vector<MuscleDef> muscles = {faceMuscleDefs().front()};
  muscles[0].obj = "muscle.obj";
  try {
    webFaceBytes(muscles, someKey(), smallBasis());
    FAIL() << "an imported muscle was written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is imported"), std::string::npos) << e.what();
  }
}

TEST(WebFaceFile, ThePagesCacheServesItsKeyAndNamesBothKeysOtherwise) {
  const ModalBasis b = smallBasis();
  WebFaceBasisCache cache(someKey(), b);
  ASSERT_TRUE(cache.load(someKey()).has_value());
  EXPECT_EQ(cache.load(someKey())->Phi, b.Phi);
  BasisKey other = someKey();
  other.words[1] ^= 1;
  try {
    cache.load(other);
    FAIL() << "another key was served";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(other.hex()), std::string::npos) << m;
    EXPECT_NE(m.find(someKey().hex()), std::string::npos) << m;
  }
}

// The fuzz corpus holds the writer's seeds at the format's current version (fuzz/web_face_seeds.h),
// so `make fuzz-replay` reaches the parser; after a format change they must be written again.
TEST(WebFaceFile, TheFuzzSeedsAreAtTheCurrentFormat) {
  const std::string again = "(write them again: build/bin/write_web_face_seeds fuzz/corpus/fuzz_web_face)";
  for (const fuzz::WebFaceSeed& s : fuzz::webFaceSeeds()) {
    const std::string path = std::string(MYO_SOURCE_DIR) + "/fuzz/corpus/fuzz_web_face/current_" + s.name + ".myoweb";
    std::ifstream in(path, std::ios::binary);
    ASSERT_TRUE(in) << path << " is missing " << again;
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(messageOf(bytes), "") << path << " " << again;
    const WebFace w = readWebFace(bytes, path);
    EXPECT_EQ(w.muscles.size(), s.muscles.size()) << path << " " << again;
    EXPECT_EQ(w.takes.size(), s.takes.size()) << path << " " << again;
    EXPECT_EQ(w.facs.entries.size(), s.facs.entries.size()) << path << " " << again;
    EXPECT_EQ(webFaceBytes(w.muscles, w.basisKey, w.basis, w.takes, w.facs), bytes) << path << ": written back";
  }
}

}  // namespace
}  // namespace myo
