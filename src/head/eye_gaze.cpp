#include "myoshell/head/eye_gaze.h"

#include <cmath>
#include <sstream>

#include "myoshell/core/errors.h"

namespace myo {

void validateEyeGaze(const EyeGaze& g, const std::string& what) {
  const char* eyes[2] = {"right", "left"};
  auto check = [&](int eye, const char* angle, double v) {
    if (std::isfinite(v) && std::abs(v) <= kGazeMaxDeg) return;
    std::ostringstream os;
    os << what << ": " << eyes[eye] << " eye " << angle << " " << v << " degrees is "
       << (std::isfinite(v) ? "outside" : "not a number in") << " [" << -kGazeMaxDeg << ", " << kGazeMaxDeg
       << "] degrees";
    throw InputError(os.str());
  };
  for (int e = 0; e < 2; ++e) {
    check(e, "pitch", g.pitchDeg[static_cast<size_t>(e)]);
    check(e, "yaw", g.yawDeg[static_cast<size_t>(e)]);
  }
}

}  // namespace myo
