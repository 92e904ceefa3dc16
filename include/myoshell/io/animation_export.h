// Animation exports: a simulated skin sequence as a PC2 point cache or a glTF 2.0 binary (GLB)
// with the frames baked as morph targets. (The OBJ sequence is mesh/obj_reader.h's writeObj.)
//
// PC2 ("POINTCACHE2", read by Blender, 3ds Max, Houdini), little-endian:
//   signature "POINTCACHE2\0" (12 bytes) | version i32 = 1 | numPoints i32 | startFrame f32 |
//   sampleRate f32 | numSamples i32 | numSamples × numPoints × (x, y, z) f32
// We write startFrame 0 and sampleRate 1 (one sample per frame), points in the head's vertex order.
//
// GLB: one mesh (the rest skin: POSITION, NORMAL of the rest, TEXCOORD_0 when the frames carry
// UVs, UNSIGNED_INT indices), one node, one scene. Each exported frame k becomes morph target k holding the displacement
// positions[k] − rest; the animation's "weights" channel (LINEAR) has keyframe times
// frame_k / fps with the one-hot weights e_k, so the player shows rest + target k at frame k and
// blends neighbours in between (the scheme three.js and Blender play). Every POSITION accessor
// carries min/max. At most maxMorphTargets frames are exported: with more frames, every
// stride-th frame (stride = ceil(frames / maxMorphTargets)) and always the last one.
// TEXCOORD_0 (float VEC2, one per vertex) holds (u, 1 − v) of AnimationFrames::uv: UVs here are
// per vertex in the OBJ convention (origin at the image's bottom-left, TriMesh::UV), glTF's origin
// is the top-left. A head whose OBJ gave one vertex several texture coordinates (a UV seam) is
// written with the first corner's (TriMesh::UV) and no vertex is split, so the GLB keeps the head's
// vertex order and count, as the PC2 cache and OBJ frames do (those keep the seams' own UVs;
// docs/exports.md). Rigs split seams (io/rig_export.h). Without UVs no TEXCOORD_0 is written.
// Both writers go through a temporary name renamed into place; a failure leaves no file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "myoshell/core/types.h"

namespace myo {

// A skin animation sampled at a fixed frame rate.
struct AnimationFrames {
  std::string name = "animation";  // mesh / animation name written into the GLB
  MatX3i triangles;                // m×3 triangles of the skin, counter-clockwise seen from outside
  MatX3 rest;                      // n×3 rest positions, cm; row i is vertex i
  std::vector<MatX3> positions;    // one n×3 matrix per frame, cm, same vertex order as rest
  double fps = 30.0;               // frames per second; frame k is at time k / fps, s
  MatX2 uv;                        // n×2 per-vertex texture coordinates (TriMesh::UV), or 0×2: none
};

// A PC2 file read back.
struct PointCache {
  int numPoints = 0;
  float startFrame = 0.0f;
  float sampleRate = 1.0f;          // frames per sample
  std::vector<MatX3> samples;       // numSamples matrices, numPoints×3 (values as stored, f32)
};

// Writes frames.positions as a PC2 point cache. Throws InputError when the file cannot be written
// (a missing folder, say) and CheckError when positions are empty or their shapes disagree.
void writePc2(const std::filesystem::path& path, const AnimationFrames& frames);

// Reads a PC2 file; throws InputError naming the file when it is missing, not a PC2 file
// (signature, version) or its size disagrees with its header.
PointCache readPc2(const std::filesystem::path& path);

// The frame indices writeGlb exports for `frameCount` frames (see above): 0, s, 2s, … and the last.
std::vector<int> glbFrameIndices(int frameCount, int maxMorphTargets = 240);

// Writes the GLB described above. Throws InputError when the file cannot be written and
// CheckError when the frames are inconsistent (no frames, shapes, uv neither 0 nor n rows, fps ≤ 0,
// bad triangle indices).
void writeGlb(const std::filesystem::path& path, const AnimationFrames& frames, int maxMorphTargets = 240);

}  // namespace myo
