// The face picture's named views: one set of names for every command, one parser.
#include <gtest/gtest.h>

#include "myoshell/core/errors.h"
#include "myoshell/render/face_picture.h"

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

}  // namespace
}  // namespace myo
