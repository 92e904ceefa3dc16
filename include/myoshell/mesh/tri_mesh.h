// A triangle mesh as read from a file: positions, triangles, optional UVs and named vertex groups.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

struct TriMesh {
  MatX3 V;    // n×3 vertex positions, cm; row i is vertex i in file order
  MatX3i F;   // m×3 triangles, counter-clockwise seen from outside (the file's winding)
  MatX2 UV;   // n×2 per-vertex texture coordinates, or 0×2 when the file has none
  // For each triangle, the index of the file polygon it came from (quads give two triangles).
  std::vector<int> sourcePolygon;
  // The file's polygons as read (before triangulation), so exports can keep quads.
  std::vector<std::vector<int>> polygons;
  // OBJ groups ("g name" / "o name") as vertex sets: name → sorted unique vertex indices.
  std::map<std::string, std::vector<int>> groups;
  std::string sourcePath;  // file it came from, for error messages ("" when built in memory)

  int vertexCount() const { return static_cast<int>(V.rows()); }
  int triangleCount() const { return static_cast<int>(F.rows()); }
};

}  // namespace myo
