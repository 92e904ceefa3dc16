// Reading Wavefront OBJ meshes (through tinyobjloader) and validating them (writing: io/obj_writer.h).
//
// Triangulation: a triangle is kept; a quad is split along the shorter diagonal of the *rest*
// positions (ties: the v0–v2 diagonal); larger polygons are fanned from their first vertex.
// A deformed mesh or an expression shape reuses its rest mesh's triangulation (readObjLike).
// Vertex order is the file's, exactly.
// Texture coordinates: TriMesh::UV per vertex (the first face corner's that names the vertex) and
// TriMesh::cornerUV per triangle corner (every corner's own, so UV seams survive); a corner without
// a `vt` takes its vertex's UV. Both are empty when no face corner names a texture coordinate.
#pragma once

#include <string>
#include <vector>

#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// A fault found while reading or validating a mesh.
struct MeshFault {
  std::string kind;     // stable key: "degenerate_triangle", "non_manifold_edge", …
  std::string message;  // human text naming the element ("triangle 12 (face on line 40) has zero area")
  int line = 0;         // 1-based line in the file, 0 when not tied to one line
};

struct MeshReport {
  std::vector<MeshFault> faults;  // every fault found, in file order
  int count(const std::string& kind) const;
};

// Strict read for everything that simulates: throws InputError at the first fault, naming the file,
// the line where possible, and the fault (missing file, unreadable number, index out of range,
// fewer than 3 vertices in a face, NaN/Inf coordinate, degenerate triangle, non-manifold edge,
// inconsistent orientation, no faces).
TriMesh readObj(const std::string& path);

// Lenient read for `myoshell info`: reads what it can and reports every fault with its count.
// Throws InputError only when the file cannot be opened or read at all.
TriMesh readObjLenient(const std::string& path, MeshReport& report);

// Reads a mesh that shares rest's topology (a deformed pose, an expression shape) and triangulates
// it exactly as rest was. Throws InputError if the vertex count or polygon list differs.
TriMesh readObjLike(const std::string& path, const TriMesh& rest);

// The same readers over OBJ text in memory (tests, embedded assets); name is used in messages.
TriMesh readObjFromString(const std::string& text, const std::string& name = "<string>");
TriMesh readObjFromStringLenient(const std::string& text, MeshReport& report,
                                 const std::string& name = "<string>");
TriMesh readObjLikeFromString(const std::string& text, const TriMesh& rest,
                              const std::string& name = "<string>");

// Checks a triangle mesh for the simulation faults (NaN/Inf, degenerate triangles, non-manifold
// edges, inconsistent orientation) and throws InputError naming the first one.
void validateMesh(const TriMesh& mesh);

}  // namespace myo
