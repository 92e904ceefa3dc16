// A small OBJ with UV seams, shared by the mesh and io tests: two quads side by side whose shared
// edge (vertices 1 and 4, 0-based) is a seam, plus a triangle whose corners give no `vt`.
//
//   3 ──── 4 ──── 5
//   │  A   ┆  B  ╱ ╲      quad A: 0 1 4 3 (split 0–4: a tie), texture coordinates 1 2 3 4
//   │      ┆   ╱    6     quad B: 1 2 5 4 (split 1–5 is longer: 2–4 taken), 5 6 7 8
//   0 ──── 1 ─ 2 ╱         triangle 2 6 5: no texture coordinates (each corner takes its vertex's)
//
// Quad B gives vertices 1 and 4 other texture coordinates than quad A: vertex 1 is (0.4, 0) in A
// and (0.6, 0) in B, vertex 4 is (0.4, 1) in A and (0.6, 1) in B. Quad A is flat, quad B is bent
// (vertex 2 is raised), so a vertex on the seam has another normal on each side.
#pragma once

#include <string>

namespace myo::test {

inline const std::string kUvSeamObj =
    "# two quads with a UV seam between them, and a triangle without texture coordinates\n"
    "v 0 0 0\nv 1 0 0\nv 1.8 0 0.3\nv 0 1 0.35\nv 1 1 0.35\nv 2 1 0.2\nv 3 0.5 0.5\n"
    "vt 0 0\nvt 0.4 0\nvt 0.4 1\nvt 0 1\n"
    "vt 0.6 0\nvt 1 0\nvt 1 1\nvt 0.6 1\n"
    "f 1/1 2/2 5/3 4/4\n"
    "f 2/5 3/6 6/7 5/8\n"
    "f 3 7 6\n";

}  // namespace myo::test
