// Suggestions for misspelt names (core/close_names.h): the edit distance ignores case; the closest
// candidates are offered with those one edit further, at most three, and nothing when none is close.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "myoshell/core/close_names.h"

namespace myo {
namespace {

TEST(CloseNames, EditDistanceCountsInsertionsDeletionsAndSubstitutionsIgnoringCase) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("abc", ""), 3u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("Procerus", "procerus"), 0u);
  EXPECT_EQ(editDistance("mentalis_left", "mentalis_lft"), 1u);
}

TEST(CloseNames, TheClosestAndThoseOneEditFurtherAtMostThree) {
  const std::vector<std::string> muscles = {"zygomaticus_major_right", "zygomaticus_major_left", "procerus",
                                            "zygomaticus_minor_left"};
  // _left is 5 edits away, _right 6: both offered, closest first; minor_left (7) is two further.
  EXPECT_EQ(closeNames("zygomaticus_major", muscles),
            (std::vector<std::string>{"zygomaticus_major_left", "zygomaticus_major_right"}));
  EXPECT_EQ(closeNames("procerus", muscles), (std::vector<std::string>{"procerus"}));
  EXPECT_EQ(closeNames("frontalis", muscles), std::vector<std::string>{});
  EXPECT_EQ(closeNames("a", {"b", "c", "d", "e"}), (std::vector<std::string>{"b", "c", "d"}));  // ties alphabetical
}

}  // namespace
}  // namespace myo

namespace myo {
namespace {

TEST(CloseNames, JoinNamesSeparatesWithCommas) {
  EXPECT_EQ(joinNames({}), "");
  EXPECT_EQ(joinNames({"a"}), "a");
  EXPECT_EQ(joinNames({"jawOpen", "mouthClose", "x"}), "jawOpen, mouthClose, x");
}

}  // namespace
}  // namespace myo
