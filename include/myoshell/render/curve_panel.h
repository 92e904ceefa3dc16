// A panel of input curves over time with a playhead (`myoshell drive --video`: the face beside the
// curves that drove it, so a user sees what moved each frame). One lane per curve, its name at the
// left, the value range [0, 1] bottom to top; the playhead a vertical line at the frame's time.
#pragma once

#include <string>
#include <vector>

#include "myoshell/render/image.h"

namespace myo {

struct PanelCurve {
  std::string name;
  std::vector<double> values;  // one per time, drawn clamped to [0, 1]
};

struct CurvePanel {
  std::vector<double> times;       // s, increasing
  std::vector<PanelCurve> curves;  // drawn top to bottom
};

// The `maxCurves` curves whose peak is largest (at least `minPeak`), in their given order: the ones
// worth a lane.
CurvePanel activeCurves(const CurvePanel& all, int maxCurves = 10, double minPeak = 0.05);

// The panel at `time` (s), width × height pixels. CheckError when a curve's length differs from the
// times'.
Image drawCurvePanel(const CurvePanel& panel, double time, int width, int height);

// `left` and `right` side by side (the taller sets the height; white fills the rest).
Image besideEachOther(const Image& left, const Image& right);

}  // namespace myo
