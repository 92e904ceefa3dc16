// Checks that explain themselves: a failed check names the condition, both values, and where.
#pragma once

#include <sstream>
#include <string>

#include "myoshell/core/errors.h"

namespace myo::detail {
[[noreturn]] void checkFailed(const char* file, int line, const std::string& what);

template <class A, class B>
[[noreturn]] void checkOpFailed(const char* file, int line, const char* expr, const A& a,
                                const B& b) {
  std::ostringstream os;
  os << expr << " (" << a << " vs " << b << ")";
  checkFailed(file, line, os.str());
}
}  // namespace myo::detail

#define MYO_CHECK(cond, msg)                                                        \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::ostringstream myo_check_os_;                                             \
      myo_check_os_ << #cond << ": " << msg;                                        \
      ::myo::detail::checkFailed(__FILE__, __LINE__, myo_check_os_.str());          \
    }                                                                               \
  } while (0)

#define MYO_CHECK_OP_(a, b, op)                                                      \
  do {                                                                              \
    const auto& myo_a_ = (a);                                                       \
    const auto& myo_b_ = (b);                                                       \
    if (!(myo_a_ op myo_b_))                                                        \
      ::myo::detail::checkOpFailed(__FILE__, __LINE__, #a " " #op " " #b, myo_a_, myo_b_); \
  } while (0)

#define MYO_CHECK_EQ(a, b) MYO_CHECK_OP_(a, b, ==)
#define MYO_CHECK_NE(a, b) MYO_CHECK_OP_(a, b, !=)
#define MYO_CHECK_LT(a, b) MYO_CHECK_OP_(a, b, <)
#define MYO_CHECK_LE(a, b) MYO_CHECK_OP_(a, b, <=)
#define MYO_CHECK_GT(a, b) MYO_CHECK_OP_(a, b, >)
#define MYO_CHECK_GE(a, b) MYO_CHECK_OP_(a, b, >=)
