// Names in error messages: suggestions for a misspelt name (the known names a few edits away, so an
// error can say "did you mean …?": blendshape names, muscle names), and lists of names.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace myo {

// Levenshtein distance between a and b, ignoring case.
std::size_t editDistance(const std::string& a, const std::string& b);

// The candidates close to `spelling`: within a third of the candidate's length in edits (at least
// one), closest first, then those one edit further (so "mouthSmile_l" finds both _L and _R), at
// most three; ties in alphabetical order. Empty when none is close.
std::vector<std::string> closeNames(const std::string& spelling, const std::vector<std::string>& candidates);

// "a, b, c" (empty for none).
std::string joinNames(const std::vector<std::string>& names);

}  // namespace myo
