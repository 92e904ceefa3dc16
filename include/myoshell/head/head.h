// Heads: a skin mesh with its landmarks and the vertices pinned under gravity.
//
// Two kinds (docs/heads.md):
// - the default head, built into the library: MediaPipe's canonical face mesh (Apache-2.0,
//   assets/default_head/NOTICE), mouth opened along the inner lip lines, eyes opened along the lid
//   margins (the anatomical model's lids need them; the thesis model keeps them closed:
//   defaultHeadOptions in face_system.h), refined by two levels of Loop subdivision with the boundary
//   as a crease; ids 0–467 are MediaPipe's;
// - any OBJ head with a landmark file (landmarks.h), e.g. ICT-FaceKit's in ../shared/data/ict.
#pragma once

#include <string>
#include <vector>

#include "myoshell/head/face_frame.h"
#include "myoshell/head/landmarks.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// The length unit a head file is written in; heads are used in cm (DESIGN.md, "Units").
// Conversions and checks: head/head_checks.h.
enum class LengthUnit { cm, m, mm };

struct Head {
  std::string name;              // "default", or the OBJ file's stem
  TriMesh mesh;                  // the skin, cm, +y up, +z out of the face, +x subject's left
  Landmarks landmarks;           // resolves every kRequiredLandmarks name (checked on load)
  std::vector<int> gravityPins;  // sorted vertex ids held fixed under gravity
  std::string pinsSource;        // how gravityPins were chosen ("rigid_vertices.json", "rim + …")
  // The skull under the skin, cm, same space as `mesh`; empty (0 vertices) when the head has none.
  // When present, muscle origins sit on it (docs/muscles.md).
  TriMesh skull;
  bool hasSkull() const { return skull.vertexCount() > 0; }
  FaceFrame frame() const { return faceFrame(mesh.V, landmarks); }
};

struct DefaultHeadOptions {
  int subdivisionLevels = 2;  // 0 gives the 468-vertex mesh with the mouth (and eyes) opened
  bool openMouth = true;      // delete the triangles between the inner lip lines
  // Delete the triangles between each eye's lid margins (openMediapipeEyes), so the lids can part
  // and close (anatomy/eyelids.h). False gives the closed-eyed head the thesis model's figures were
  // made on, bit for bit.
  bool openEyes = true;
};

// The default head from the data embedded at build time (no file access). About 7k vertices; four
// boundary loops (outer rim, mouth, the two eyes), two with closed eyes. Pins: defaultGravityPins.
// Vertex ids 0–467 are MediaPipe's whatever the options; the ids of the subdivision's edge points
// (468 on) depend on them.
Head loadDefaultHead(const DefaultHeadOptions& options = {});

// The canonical mesh as embedded (468 vertices, 898 triangles, cm), before any processing.
TriMesh defaultHeadSourceMesh();
// The default head's landmark file as embedded (assets/default_head/landmarks_multipie68.json).
std::string defaultHeadLandmarkJson();
// SHA-256 (hex) of the embedded binarypb slice, checked by scripts/fetch_default_head and at configure.
std::string defaultHeadSourceSha256();

// Any OBJ head with its landmark file: io/head_files.h (loadHead).

// Pins for a face without a back of the head: every vertex of the longest boundary loop (by
// length; the outer rim of a face mask) plus the bone-backed nose-bridge landmarks nasion_approx
// and Multi-PIE point 28 when present. Empty rim (closed mesh) gives only the landmarks.
std::vector<int> defaultGravityPins(const TriMesh& mesh, const Landmarks& landmarks);

}  // namespace myo
