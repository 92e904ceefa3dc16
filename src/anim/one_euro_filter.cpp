#include "myoshell/anim/one_euro_filter.h"

#include <cmath>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo {
namespace {

// The smoothing factor of a first-order low-pass filter of cutoff f (Hz) over a step dt (s):
// τ = 1/(2πf), α = 1/(1 + τ/dt) (Casiez et al. 2012, eq. 1 and the filter's definition).
double smoothingFactor(double cutoff, double dt) {
  const double tau = 1.0 / (2.0 * M_PI * cutoff);
  return 1.0 / (1.0 + tau / dt);
}

}  // namespace

void checkOneEuroSettings(const OneEuroSettings& s, const std::string& what) {
  if (!(std::isfinite(s.minCutoff) && s.minCutoff > 0.0))
    throw InputError(what + ": min_cutoff must be a positive number of Hz");
  if (!(std::isfinite(s.derivativeCutoff) && s.derivativeCutoff > 0.0))
    throw InputError(what + ": d_cutoff must be a positive number of Hz");
  if (!(std::isfinite(s.beta) && s.beta >= 0.0)) throw InputError(what + ": beta must be a number ≥ 0");
}

double OneEuroStream::filter(double t, double x) {
  if (!settings_.enabled) return x;
  if (!started_) {
    started_ = true;
    lastTime_ = t;
    last_ = x;
    return x;
  }
  const double dt = t - lastTime_;
  MYO_CHECK(dt > 0.0, "oneEuroFilter: times must increase");
  const double rawSpeed = (x - last_) / dt;
  const double aD = smoothingFactor(settings_.derivativeCutoff, dt);
  speed_ = aD * rawSpeed + (1.0 - aD) * speed_;
  const double a = smoothingFactor(settings_.minCutoff + settings_.beta * std::abs(speed_), dt);
  last_ = a * x + (1.0 - a) * last_;
  lastTime_ = t;
  return last_;
}

std::vector<double> oneEuroFilter(const std::vector<double>& times, const std::vector<double>& values,
                                  const OneEuroSettings& s) {
  MYO_CHECK(times.size() == values.size(), "oneEuroFilter: times and values differ in length");
  if (!s.enabled || values.size() < 2) return values;
  std::vector<double> out(values.size());
  OneEuroStream stream(s);
  for (size_t i = 0; i < values.size(); ++i) out[i] = stream.filter(times[i], values[i]);
  return out;
}

}  // namespace myo
