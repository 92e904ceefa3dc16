// Checks of number options for CLI::Option::check, whose failures read like every other error of
// the CLI: the option, the rule and the value given ("--threads: must be ≥ 0 (0 = every core), got
// -1"), where CLI11's own ranges print their limits in full (a 300-digit DBL_MAX). Shared by
// `myoshell` and `myoshell-view`.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace myo::cli {

// A whole number ≥ lo; `note` (e.g. "0 = every core") follows the rule in the message.
CLI::Validator wholeAtLeast(long long lo, const std::string& note = "");
// A whole number in [lo, hi].
CLI::Validator wholeIn(long long lo, long long hi);
// A finite number ≥ lo, > lo, or in [lo, hi].
CLI::Validator numberAtLeast(double lo);
CLI::Validator numberAbove(double lo);
CLI::Validator numberIn(double lo, double hi);

}  // namespace myo::cli
