#include "option_checks.h"

#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace myo::cli {

namespace {

struct NumberRule {
  bool whole = false;
  double lo = 0.0;
  bool loOpen = false;  // > lo rather than ≥ lo
  double hi = std::numeric_limits<double>::infinity();
  std::string note;

  // "≥ 0", "> 0", "in [64, 4096]"; `ascii` for the help's type column, whose alignment counts bytes.
  std::string text(bool ascii) const {
    if (std::isfinite(hi)) return fmt::format("in [{:g}, {:g}]", lo, hi);
    return fmt::format("{} {:g}", loOpen ? ">" : ascii ? ">=" : "≥", lo);
  }

  // The value's fault, or "" when it holds.
  std::string check(const std::string& input) const {
    const std::string rule = "must be " + text(false) + (note.empty() ? "" : " (" + note + ")");
    const std::string kind = "must be " + std::string(whole ? "a whole number " : "a number ") + text(false) +
                             (note.empty() ? "" : " (" + note + ")");
    double value = 0.0;
    if (whole) {
      long long v = 0;
      const char* end = input.data() + input.size();
      const auto [p, ec] = std::from_chars(input.data(), end, v);
      if (input.empty() || ec != std::errc() || p != end) return kind + ", got '" + input + "'";
      value = static_cast<double>(v);
    } else {
      char* end = nullptr;
      value = std::strtod(input.c_str(), &end);
      if (input.empty() || end != input.c_str() + input.size() || !std::isfinite(value))
        return kind + ", got '" + input + "'";
    }
    const bool holds = (loOpen ? value > lo : value >= lo) && value <= hi;
    return holds ? std::string() : rule + ", got " + input;
  }
};

CLI::Validator validator(NumberRule rule) {
  const std::string description = rule.text(true);
  return CLI::Validator([rule](std::string& input) { return rule.check(input); }, description);
}

}  // namespace

CLI::Validator wholeAtLeast(long long lo, const std::string& note) {
  return validator({true, static_cast<double>(lo), false, std::numeric_limits<double>::infinity(), note});
}
CLI::Validator wholeIn(long long lo, long long hi) {
  return validator({true, static_cast<double>(lo), false, static_cast<double>(hi), ""});
}
CLI::Validator numberAtLeast(double lo) { return validator({false, lo, false, std::numeric_limits<double>::infinity(), ""}); }
CLI::Validator numberAbove(double lo) { return validator({false, lo, true, std::numeric_limits<double>::infinity(), ""}); }
CLI::Validator numberIn(double lo, double hi) { return validator({false, lo, false, hi, ""}); }

}  // namespace myo::cli
