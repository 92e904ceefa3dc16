// Timelines: keyframed values over time, so the thesis's transitions (Fig. 26: contract, relax,
// then another muscle) are a few lines of a scene file.
#pragma once

#include <string>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

// How a key's value goes to the next key's value.
enum class Interpolation {
  Step,    // holds the key's value until the next key
  Linear,  // straight line
  Smooth,  // smoothstep 3s² − 2s³: zero slope at both keys
};

// "step", "linear", "smooth"; throws InputError for anything else.
Interpolation interpolationFromString(const std::string& name);
const char* toString(Interpolation interpolation);

template <class Value>
struct Keyframe {
  double time = 0.0;  // s
  Value value{};
  Interpolation interpolation = Interpolation::Linear;  // towards the next key
};

// A track: keys sorted by time (strictly increasing). Before the first key it holds the first
// value, after the last the last value; an empty track evaluates to `Value{}` (zero).
template <class Value>
class Track {
 public:
  Track() = default;
  // Throws InputError (naming `what`) when times are not finite or not strictly increasing.
  Track(std::vector<Keyframe<Value>> keys, const std::string& what = "track");

  Value at(double time) const;
  const std::vector<Keyframe<Value>>& keys() const { return keys_; }
  bool empty() const { return keys_.empty(); }
  double endTime() const { return keys_.empty() ? 0.0 : keys_.back().time; }

 private:
  std::vector<Keyframe<Value>> keys_;
};

using ScalarTrack = Track<double>;
using VectorTrack = Track<Vec3>;

extern template class Track<double>;
extern template class Track<Vec3>;

}  // namespace myo
