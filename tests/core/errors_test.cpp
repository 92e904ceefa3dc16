#include <gtest/gtest.h>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/types.h"

namespace myo {
namespace {

TEST(InputError, NamesFileLineAndColumnOnlyWhenKnown) {
  EXPECT_STREQ(InputError("bad", "a.obj", 3, 7).what(), "a.obj:3:7: bad");
  EXPECT_STREQ(InputError("bad", "a.obj", 3).what(), "a.obj:3: bad");
  EXPECT_STREQ(InputError("bad", "a.obj").what(), "a.obj: bad");
  EXPECT_STREQ(InputError("bad").what(), "bad");
  EXPECT_EQ(InputError("bad", "a.obj", 3).line(), 3);
}

TEST(Check, FailedComparisonPrintsBothValues) {
  try {
    MYO_CHECK_EQ(1 + 1, 3);
    FAIL() << "MYO_CHECK_EQ did not throw";
  } catch (const CheckError& e) {
    EXPECT_NE(std::string(e.what()).find("1 + 1 == 3 (2 vs 3)"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(MYO_CHECK(true, "never"));
  EXPECT_THROW(MYO_CHECK(false, "always"), CheckError);
}

TEST(Types, FlatViewSharesMemoryWithRows) {
  MatX3 m(2, 3);
  m << 1, 2, 3, 4, 5, 6;
  auto v = flat(m);
  EXPECT_EQ(v(3), 4);
  v(5) = 9;
  EXPECT_EQ(m(1, 2), 9);
}

}  // namespace
}  // namespace myo
