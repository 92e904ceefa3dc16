// Blendshape rigs written as glTF 2.0 binaries (`myoshell rig`; docs/rigs.md "Writing a rig"): one
// mesh, one triangle primitive (POSITION, NORMAL, TEXCOORD_0 when the head has UVs, UNSIGNED_INT
// indices), one dense POSITION morph target per name, the names in meshes[0].extras.targetNames, all
// weights 0, one node without transform. Positions are written in metres (glTF's unit), vertices in
// the head's own order; with per-corner UVs, each further UV a vertex has on a seam is an appended
// duplicate vertex (mesh/uv_seams.h: same position, normal and deltas as its original, its own UV),
// and the triangles use it where their corners have that UV. Normals are those of the unsplit mesh.
// io/rig_file.h reads it back (welding the duplicates). The file goes through a temporary name
// renamed into place: a failure leaves no file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

struct RigExport {
  std::string name = "face";       // mesh, node and scene name
  MatX3 rest;                      // n×3, cm
  MatX3i triangles;                // m×3, counter-clockwise seen from outside
  MatX2 uv;                        // n×2 per-vertex UVs (TriMesh::UV, OBJ convention) or 0×2
  MatX2 cornerUV;                  // 3m×2 per-corner UVs (TriMesh::cornerUV) or 0×2: seams are split
  std::vector<std::string> names;  // one per target
  std::vector<MatX3> deltas;       // n×3 each, cm: the target minus the rest
};

// Throws InputError when the file cannot be written, CheckError when the rig is inconsistent.
void writeRigGlb(const std::filesystem::path& path, const RigExport& rig);

}  // namespace myo
