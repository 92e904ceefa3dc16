#include "export_file.h"
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo::detail {

void checkFrames(const AnimationFrames& frames) {
  MYO_CHECK(!frames.positions.empty(), "an animation export needs at least one frame");
  MYO_CHECK(frames.rest.rows() > 0, "an animation export needs a rest mesh");
  for (size_t k = 0; k < frames.positions.size(); ++k)
    MYO_CHECK(frames.positions[k].rows() == frames.rest.rows(),
              "frame " << k << " has " << frames.positions[k].rows() << " vertices, the rest mesh "
                       << frames.rest.rows());
}

}  // namespace myo::detail
