#include "myoshell/anim/timeline.h"

#include <algorithm>
#include <cmath>

#include "myoshell/core/errors.h"

namespace myo {

Interpolation interpolationFromString(const std::string& name) {
  if (name == "step") return Interpolation::Step;
  if (name == "linear") return Interpolation::Linear;
  if (name == "smooth") return Interpolation::Smooth;
  throw InputError("unknown interpolation '" + name + "' (use step, linear or smooth)");
}

const char* toString(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::Step: return "step";
    case Interpolation::Linear: return "linear";
    case Interpolation::Smooth: return "smooth";
  }
  return "linear";
}

template <class Value>
Track<Value>::Track(std::vector<Keyframe<Value>> keys, const std::string& what) : keys_(std::move(keys)) {
  for (size_t k = 0; k < keys_.size(); ++k) {
    if (!std::isfinite(keys_[k].time)) throw InputError(what + ": key " + std::to_string(k) + " has a non-finite time");
    if (k > 0 && !(keys_[k].time > keys_[k - 1].time))
      throw InputError(what + ": key times must increase (key " + std::to_string(k) + " at " +
                       std::to_string(keys_[k].time) + " s follows " + std::to_string(keys_[k - 1].time) + " s)");
  }
}

template <class Value>
Value Track<Value>::at(double time) const {
  if (keys_.empty()) {
    if constexpr (std::is_same_v<Value, double>) return 0.0;
    else return Value::Zero();
  }
  if (time <= keys_.front().time) return keys_.front().value;
  if (time >= keys_.back().time) return keys_.back().value;
  // The key at or before `time`.
  const auto next = std::upper_bound(keys_.begin(), keys_.end(), time,
                                     [](double t, const Keyframe<Value>& k) { return t < k.time; });
  const Keyframe<Value>& a = *(next - 1);
  const Keyframe<Value>& b = *next;
  double s = (time - a.time) / (b.time - a.time);
  switch (a.interpolation) {
    case Interpolation::Step: return a.value;
    case Interpolation::Linear: break;
    case Interpolation::Smooth: s = s * s * (3.0 - 2.0 * s); break;
  }
  return Value(a.value + s * (b.value - a.value));
}

template class Track<double>;
template class Track<Vec3>;

}  // namespace myo
