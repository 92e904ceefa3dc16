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
  // 3m×2 texture coordinates per triangle corner (row 3t + c: corner c of triangle t, OBJ
  // convention, v up), or 0×2 when unknown. An OBJ vertex may carry several texture coordinates
  // (a UV seam: one per side); UV keeps the first corner's, cornerUV keeps them all. Kept beside
  // UV rather than replacing it so that every per-vertex user (simulation, animation export)
  // works unchanged. Whatever rebuilds F must rebuild this too or clear it (empty = unknown).
  MatX2 cornerUV;
  // For each triangle, the index of the file polygon it came from (quads give two triangles).
  std::vector<int> sourcePolygon;
  // The file's polygons as read (before triangulation), so exports can keep quads.
  std::vector<std::vector<int>> polygons;
  // OBJ groups ("g name" / "o name") as vertex sets: name → sorted unique vertex indices.
  std::map<std::string, std::vector<int>> groups;
  std::string sourcePath;  // file it came from, for error messages ("" when built in memory)

  int vertexCount() const { return static_cast<int>(V.rows()); }
  int triangleCount() const { return static_cast<int>(F.rows()); }
  // True when cornerUV holds one row per triangle corner.
  bool hasCornerUV() const { return cornerUV.rows() > 0 && cornerUV.rows() == 3 * F.rows(); }
};

}  // namespace myo
