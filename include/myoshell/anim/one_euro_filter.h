// The One-Euro filter (Casiez, Roussel and Vogel, "1€ Filter: A Simple Speed-based Low-pass Filter
// for Noisy Input in Interactive Systems", CHI 2012): a first-order low-pass filter whose cutoff
// rises with the signal's speed, so a tracker's jitter at rest is smoothed while fast motion (a
// blink, a smile's onset) keeps little lag. Used on a recorded performance's input curves
// (docs/performance_input.md, "Filtering").
//
// Per sample i with Δt = t_i − t_{i−1}:  α(f) = 1 / (1 + 1/(2π f Δt))
//   ẋ_i = α(d_cutoff)·(x_i − x̂_{i−1})/Δt + (1 − α(d_cutoff))·ẋ_{i−1}      (the speed, low-passed)
//   f_i = min_cutoff + β·|ẋ_i|                                              (the adaptive cutoff)
//   x̂_i = α(f_i)·x_i + (1 − α(f_i))·x̂_{i−1},   with x̂_0 = x_0, ẋ_0 = 0.
#pragma once

#include <string>
#include <vector>

namespace myo {

struct OneEuroSettings {
  bool enabled = true;
  double minCutoff = 1.5;         // Hz: the cutoff at rest (lower: smoother, more lag)
  double beta = 0.5;              // s per unit: how fast the cutoff rises with speed (units of the curve per s)
  double derivativeCutoff = 1.0;  // Hz: the cutoff of the speed estimate
};

// Throws InputError naming `what` for a cutoff that is not finite and > 0 or a β that is not finite
// and ≥ 0.
void checkOneEuroSettings(const OneEuroSettings& settings, const std::string& what = "filter");

// The same filter one sample at a time, for a live stream (io/live_source.h): filter(t, x) gives
// x̂ at time t (s, increasing). oneEuroFilter runs it over a curve, so both are one formula.
class OneEuroStream {
 public:
  explicit OneEuroStream(const OneEuroSettings& settings = {}) : settings_(settings) {}
  double filter(double t, double x);

 private:
  OneEuroSettings settings_;
  bool started_ = false;
  double lastTime_ = 0.0, last_ = 0.0, speed_ = 0.0;
};

// The filtered curve of `values` sampled at `times` (s, strictly increasing, same length). Returns
// `values` unchanged when the filter is off or has fewer than two samples. CheckError on mismatched
// lengths or times that do not increase.
std::vector<double> oneEuroFilter(const std::vector<double>& times, const std::vector<double>& values,
                                  const OneEuroSettings& settings);

}  // namespace myo
