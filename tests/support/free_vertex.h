// A skin vertex that no pin holds: for drags in tests (landmarks are pinned with the gravity pins).
#pragma once

#include <algorithm>
#include <vector>

#include "myoshell/head/head.h"

namespace myo::test {

// The vertex nearest to halfway between the left mouth corner and the left eye's outer corner
// (a point of the left cheek) that is not in `sortedPins`.
inline int freeLeftCheekVertex(const Head& head, const std::vector<int>& sortedPins) {
  const Vec3 aim = 0.5 * (Vec3(head.mesh.V.row(head.landmarks.vertex("mouth_corner_left"))) +
                          Vec3(head.mesh.V.row(head.landmarks.vertex("left_eye_outer"))));
  int best = -1;
  for (int v = 0; v < head.mesh.vertexCount(); ++v)
    if (!std::binary_search(sortedPins.begin(), sortedPins.end(), v) &&
        (best < 0 || (Vec3(head.mesh.V.row(v)) - aim).norm() < (Vec3(head.mesh.V.row(best)) - aim).norm()))
      best = v;
  return best;
}

}  // namespace myo::test
