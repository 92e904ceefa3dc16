// The web page's face data (io/web_face_file.h): the whole face's muscles and a basis round-trip
// (Φ to float32, the rest exactly); truncated, damaged and foreign files are refused with the
// reason; the page's cache serves only its key.
#include <gtest/gtest.h>

#include <cmath>

#include "myoshell/core/errors.h"
#include "myoshell/io/web_face_file.h"

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
    EXPECT_EQ(a.ring.lipBody, c.ring.lipBody);
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

}  // namespace
}  // namespace myo
