// The face picture's named views and framings: one set of names for every command, one parser;
// what each framing puts in the picture of a head with a neck.
#include <gtest/gtest.h>

#include <algorithm>

#include "myoshell/core/errors.h"
#include "myoshell/render/face_picture.h"
#include "support/ict.h"

namespace myo {
namespace {

TEST(FacePicture, ViewNamesRoundTripAndAnUnknownOneIsNamed) {
  for (ViewPreset v : {ViewPreset::front, ViewPreset::threeQuarter, ViewPreset::profile, ViewPreset::back})
    EXPECT_EQ(parseView(viewName(v)), v) << viewName(v);
  EXPECT_STREQ(viewName(ViewPreset::threeQuarter), "three-quarter");
  try {
    parseView("side");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "unknown view 'side' (use front, three-quarter, profile or back)");
  }
}

TEST(FacePicture, FramingNamesRoundTripAndAnUnknownOneIsNamed) {
  for (FaceFraming f : {FaceFraming::all, FaceFraming::head, FaceFraming::face})
    EXPECT_EQ(parseFraming(framingName(f)), f) << framingName(f);
  try {
    parseFraming("bust");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "unknown framing 'bust' (use face, head or all)");
  }
}

// drive --video framed the whole mesh, and on a head with a neck and shoulders (ICT's) the face
// was a small part of the picture. Face framing fills the picture with the face's landmarks; head
// framing keeps the crown and cuts the shoulders; all is the whole mesh as before.
TEST(FacePicture, FaceFramingFillsThePictureWithTheFaceOfAHeadWithANeck) {
  MYO_REQUIRE_SHARED_DATA();
  const Head head = test::ictHead();
  constexpr int kSize = 480;
  struct Seen {
    double landmarksWide = 0, landmarksHigh = 0;  // the named landmarks' box, fractions of the picture
    double top = 0, bottom = 0;                   // the mesh's highest and lowest points, pixel rows
    bool landmarksInside = true;
  };
  auto seen = [&](FaceFraming framing) {
    const Camera camera = faceCamera(head, ViewPreset::front, kSize, kSize, framing);
    Seen s;
    double x0 = kSize, x1 = 0, y0 = kSize, y1 = 0;
    for (const auto& [name, v] : head.landmarks.resolved()) {
      const ScreenPoint p = project(camera, head.mesh.V.row(v), kSize, kSize);
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
      if (p.x < 0 || p.x > kSize || p.y < 0 || p.y > kSize) s.landmarksInside = false;
    }
    s.landmarksWide = (x1 - x0) / kSize;
    s.landmarksHigh = (y1 - y0) / kSize;
    s.top = kSize, s.bottom = 0;
    for (Eigen::Index r = 0; r < head.mesh.V.rows(); ++r) {
      const double y = project(camera, head.mesh.V.row(r), kSize, kSize).y;
      s.top = std::min(s.top, y), s.bottom = std::max(s.bottom, y);
    }
    RecordProperty(std::string(framingName(framing)) + "_landmarks_wide_high",
                   std::to_string(s.landmarksWide) + " " + std::to_string(s.landmarksHigh));
    return s;
  };
  const Seen face = seen(FaceFraming::face), headFramed = seen(FaceFraming::head), all = seen(FaceFraming::all);
  EXPECT_TRUE(face.landmarksInside);
  EXPECT_GT(face.landmarksHigh, 0.5);  // brows to chin: over half the picture's height
  EXPECT_GT(face.landmarksWide * face.landmarksHigh, 0.2);
  EXPECT_LT(all.landmarksHigh, 0.45);  // the whole bust: the face is small
  EXPECT_GT(face.landmarksHigh, 1.3 * all.landmarksHigh);
  // head: crown in the picture, the shoulders below it, the face larger than with all.
  EXPECT_TRUE(headFramed.landmarksInside);
  EXPECT_GE(headFramed.top, 0.0);
  EXPECT_GT(headFramed.bottom, kSize);
  EXPECT_GT(headFramed.landmarksHigh, 1.1 * all.landmarksHigh);
  EXPECT_GE(all.top, 0.0);  // all: every point in the picture
  EXPECT_LE(all.bottom, kSize);
}

}  // namespace
}  // namespace myo
