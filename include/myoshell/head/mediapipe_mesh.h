// MediaPipe's canonical face mesh (Apache-2.0): decoding its protobuf, and opening its mouth and eyes.
//
// The mesh comes from `geometry_pipeline_metadata_landmarks.binarypb` of the npm package
// @mediapipe/face_mesh@0.4.1657299874 (scripts/fetch_default_head), a serialized
// mediapipe.face_geometry.GeometryPipelineMetadata whose field 1 is a Mesh3d:
//   Mesh3d { 1: vertex_type (enum, 0 = VERTEX_PT), 2: primitive_type (enum, 0 = TRIANGLE),
//            3: vertex_buffer (repeated float: X Y Z U V per vertex),
//            4: index_buffer (repeated uint32: 3 per triangle) }
// Repeated scalars may be stored packed (one length-delimited field) or unpacked (one field per
// value, as in that file); both are accepted. Unknown fields are skipped. See docs/heads.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// Decodes a serialized Mesh3d. V (n×3, the file's units: cm for the canonical mesh), UV (n×2) and
// F (m×3, the file's winding). Throws InputError naming `name` and the byte offset on a malformed
// message, a vertex buffer that is not a multiple of 5 floats, an index buffer not a multiple of 3,
// an index out of range, or a vertex type or primitive type other than 0 (VERTEX_PT, TRIANGLE).
TriMesh parseMesh3d(const std::uint8_t* data, std::size_t size, const std::string& name = "<mesh3d>");

// Decodes a serialized GeometryPipelineMetadata and returns its Mesh3d (field 1). Throws InputError
// when the message has no field 1.
TriMesh parseGeometryPipelineMetadata(const std::uint8_t* data, std::size_t size,
                                      const std::string& name = "<binarypb>");

// The inner lip lines of the 468-point topology (METHOD.md §8), from the right mouth corner (78,
// subject's right) to the left one (308).
inline constexpr std::array<int, 11> kMediapipeInnerLipUpper = {78,  191, 80,  81,  82, 13,
                                                                 312, 311, 310, 415, 308};
inline constexpr std::array<int, 11> kMediapipeInnerLipLower = {78,  95,  88,  178, 87, 14,
                                                                 317, 402, 318, 324, 308};

// Opens the mouth of a 468-point MediaPipe mesh: removes every triangle whose three vertices lie
// on the inner lip lines and which has a vertex on each line besides the corners (the 18 triangles
// between the lips of the canonical mesh). Vertices are kept. Returns the number removed.
int openMediapipeMouth(TriMesh& mesh);

// The lid margins of the 468-point topology, each from the eye's outer corner to its inner corner:
// MediaPipe's eye contours (face_mesh_connections' FACEMESH_RIGHT_EYE / FACEMESH_LEFT_EYE, the
// `rightEyeUpper0`/`rightEyeLower0` keypoint contours of npm @tensorflow-models/face-landmarks-detection).
// "Right" is the subject's right (−x); 33/133 and 263/362 are the default head's eye corner landmarks.
// On the canonical mesh the lines do not coincide: the fissure is 6.8 mm high at its middle (159–145),
// closed over by a strip of triangles (docs/heads.md).
inline constexpr std::array<int, 9> kMediapipeRightEyeUpper = {33, 246, 161, 160, 159, 158, 157, 173, 133};
inline constexpr std::array<int, 9> kMediapipeRightEyeLower = {33, 7, 163, 144, 145, 153, 154, 155, 133};
inline constexpr std::array<int, 9> kMediapipeLeftEyeUpper = {263, 466, 388, 387, 386, 385, 384, 398, 362};
inline constexpr std::array<int, 9> kMediapipeLeftEyeLower = {263, 249, 390, 373, 374, 380, 381, 382, 362};

// Opens both eyes of a 468-point MediaPipe mesh by the mouth's rule applied to each eye's lid
// margins: removes every triangle whose three vertices lie on the eye's two margins and which has a
// vertex on each margin besides the corners (the 14 triangles over each fissure of the canonical
// mesh, 28 in all). Each eye becomes a boundary loop of both margins (16 edges). Vertices are kept.
// Returns the number removed.
int openMediapipeEyes(TriMesh& mesh);

}  // namespace myo
