// Blendshape rigs from glTF 2.0 files (.glb binary or .gltf JSON): a head mesh plus named morph
// targets, in cm (docs/rigs.md has the rules; glTF is in metres by specification, so every position
// is multiplied by 100).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

struct RigFile {
  std::string path;                 // the file it was read from
  TriMesh base;                     // n×3 positions (cm) and m×3 triangles of the welded base mesh; no UVs
  std::vector<std::string> names;   // k target names, in the file's order
  std::vector<MatX3> targets;       // k shapes, each n×3 absolute positions (cm) in base's vertex order
  std::vector<int> weldedIndex;     // the primitive's vertex i is base vertex weldedIndex[i]

  int vertexCount() const { return static_cast<int>(base.V.rows()); }
  // The index of a target name, or -1.
  int find(const std::string& name) const;
  // The absolute shape (n×3, cm) of a target. InputError naming the file when the name is unknown:
  // "no shape 'X' (the rig has: a, b, …)".
  const MatX3& shape(const std::string& name) const;
  // The target minus the base (n×3, cm).
  MatX3 delta(const std::string& name) const;
};

// Reads the rig at `path`. The head is the first mesh (in `meshes` order) whose single triangle
// primitive has morph targets, placed by the first node that references it (with its parents'
// transforms; the identity when no node does). Vertices at exactly the same position (glTF's seam
// copies) are welded in first-seen order. InputError "path: /json/pointer: fault" on bad input.
RigFile readRig(const std::string& path);

// The same from bytes already read; side-car buffers (`uri` a relative file name) are read next to
// `path`.
RigFile parseRig(std::string_view bytes, const std::string& path);

// "RIG.glb#shape" split at the last '#': {path, shape}; shape is empty when there is no '#'.
struct RigShapeRef {
  std::string path;
  std::string shape;
};
RigShapeRef splitRigShape(const std::string& pathHashShape);

// True when `argument` names a rig shape: "….glb#name" or "….gltf#name" (case-insensitive suffix).
bool isRigShapeArgument(const std::string& argument);

// The absolute shape (n×3, cm, base vertex order) that "RIG.glb#shape" names. InputError when there
// is no '#shape' part or the rig has no such shape (the message lists the rig's names).
MatX3 rigShape(const std::string& pathHashShape);

}  // namespace myo
