// Animation exports: a simulated skin sequence as a PC2 point cache or a glTF 2.0 binary (GLB)
// with the frames baked as morph targets. (The OBJ sequence is mesh/obj_reader.h's writeObj.)
//
// PC2 ("POINTCACHE2", read by Blender, 3ds Max, Houdini), little-endian:
//   signature "POINTCACHE2\0" (12 bytes) | version i32 = 1 | numPoints i32 | startFrame f32 |
//   sampleRate f32 | numSamples i32 | numSamples × numPoints × (x, y, z) f32
// We write startFrame 0 and sampleRate 1 (one sample per frame), points in the head's vertex order.
//
// GLB (docs/exports.md "The animation GLB"): one mesh (POSITION, NORMAL of the rest, TEXCOORD_0
// when the frames carry UVs, UNSIGNED_INT indices), one node without transform, one scene, one
// animation; in metres (glTF's unit: the frames' cm × 0.01). Every frame is exact to a tolerance:
// the frames are compressed (io/morph_compression.h) to a base mesh (POSITION) plus k morph targets
// with one weight per target and frame in [0, 1], so frame f plays as base + Σ_k s_fk T_k. The
// animation's one "weights" channel (LINEAR) has a key at every frame, f / fps s. The frame rate
// and count are in the animation's and the scene's extras, {"fps": F, "frames": N}; the mesh's
// default weights are frame 0's (a viewer that plays nothing shows the first frame), its
// extras.targetNames "mode_00", "mode_01", …. Every POSITION accessor carries min/max.
// TEXCOORD_0 (float VEC2) holds (u, 1 − v): OBJ's texture origin is the image's bottom-left,
// glTF's the top-left. With per-corner UVs (AnimationFrames::cornerUV) the seams are split as in
// rigs (io/rig_export.h, mesh/uv_seams.h): each further UV a vertex has is a duplicate appended after
// the head's vertices, moving exactly as its original in every frame; the first n vertices are the
// head's, in its order. Without UVs no TEXCOORD_0 is written.
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
  MatX2 cornerUV;                  // 3m×2 per-corner UVs (TriMesh::cornerUV) or 0×2: the GLB splits seams
};

// How exact the GLB's frames are, and how many targets that takes (io/morph_compression.h).
// The GLB's default tolerance, mm: half of issue 44's 0.1 mm, the other half left to the player's sums.
inline constexpr double kDefaultGlbToleranceMm = 0.05;

struct GlbOptions {
  // Largest vertex error allowed in any frame, mm (--glb-tolerance; in mm, the unit users give it,
  // so that the report repeats it exactly).
  double toleranceMm = kDefaultGlbToleranceMm;
  int maxTargets = 256;  // the cap; reached, the GLB keeps this many and reports its error
};

// The options for a tolerance given in mm (`--glb-tolerance`, Python's glb_tolerance): InputError
// "`what`: must be a number > 0 (mm), got X" unless finite and > 0.
GlbOptions glbOptionsForTolerance(double toleranceMm, const std::string& what = "--glb-tolerance");

// What writeGlb wrote.
struct GlbReport {
  int targets = 0;              // morph targets k
  double toleranceMm = 0.0;     // the tolerance asked for (GlbOptions::toleranceMm), mm
  double maxErrorCm = 0.0;      // largest vertex distance over all frames between the played GLB and the frames
  bool withinTolerance = true;  // false when the cap was reached before the tolerance
  int frames = 0;               // keys (one per frame)
  double fps = 0.0;
  int vertices = 0;             // the GLB's, seam duplicates included
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

// Writes the GLB described above. Throws InputError when the file cannot be written and
// CheckError when the frames are inconsistent (no frames, shapes, uv neither 0 nor n rows,
// cornerUV neither 0 nor 3m rows, fps ≤ 0, bad triangle indices).
GlbReport writeGlb(const std::filesystem::path& path, const AnimationFrames& frames, const GlbOptions& options = {});

}  // namespace myo
