// The small head with UV seams (uv_seam_mesh.h) as a rig: the rig tests' one seam rig, instead of a
// copy in each glTF test (tests/io).
#pragma once

#include <string>
#include <vector>

#include "myoshell/io/rig_export.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo::test {

// `mesh` with its UVs and corner UVs, one target per name: target k moves vertex v by
// (0.1·v·(k + 1), −0.05·v, 0.2·((v + k) mod 3)) cm, so no two targets and no two vertices agree.
inline RigExport seamRig(const TriMesh& mesh, const std::vector<std::string>& names = {"jawOpen", "cheekPuff"}) {
  RigExport rig;
  rig.name = "seam";
  rig.rest = mesh.V;
  rig.triangles = mesh.F;
  rig.uv = mesh.UV;
  rig.cornerUV = mesh.cornerUV;
  rig.names = names;
  for (int k = 0; k < static_cast<int>(names.size()); ++k) {
    MatX3 d(mesh.V.rows(), 3);
    for (int v = 0; v < d.rows(); ++v) d.row(v) << 0.1 * v * (k + 1), -0.05 * v, 0.2 * ((v + k) % 3);
    rig.deltas.push_back(d);
  }
  return rig;
}

}  // namespace myo::test
