// Pictures of a simulated face: the skin (optionally coloured by displacement magnitude), the
// muscles shown through it, a caption. Shared by `run --render`, `demo` and the figure commands.
#pragma once

#include <string>
#include <vector>

#include "myoshell/face/simulator.h"
#include "myoshell/render/camera.h"
#include "myoshell/render/image.h"

namespace myo::cli {

struct FacePictureOptions {
  int width = 480, height = 480;           // pixels of the final picture
  ViewPreset view = ViewPreset::front;
  bool showMuscles = false;                // muscles drawn through a half-transparent skin
  double displacementScale = 0.0;          // > 0: colour the skin by |u| on [0, this] cm, with a colour bar
  std::string caption;                     // drawn under the picture when not empty
};

// The face of `sim` as it is now.
Image renderFace(const Simulator& sim, const FacePictureOptions& options);

}  // namespace myo::cli
