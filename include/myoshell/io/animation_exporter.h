// A played scene's animation exports, frame by frame (`myoshell run` and `drive`, Python's
// myoshell.drive): the OBJ sequence DIR/obj/NAME_NNNN.obj written as the frames come, and the GLB
// (DIR/NAME.glb) and PC2 (DIR/NAME.pc2) of io/animation_export.h written at the end from the frames
// kept. File names are relative to DIR, as the output manifest (io/output_manifest.h) lists them.
// The OBJ frames and the PC2 are in the head's own unit (the unit its OBJ was read in: cm
// positions ÷ centimetresPer(unit), as `pose` writes), the head's vertex order; the GLB is in
// metres (glTF's unit) whatever the head's, its UV seams split when the head has corner UVs.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "myoshell/head/head.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

struct ExportFormats {
  bool obj = false, glb = false, pc2 = false;
};

// Any subset of "obj", "glb", "pc2"; InputError "unknown export format 'X' (use glb, pc2 or obj)".
ExportFormats parseExportFormats(const std::vector<std::string>& names);

class AnimationExporter {
 public:
  // Makes the folder `out` (and out/obj for OBJ frames): InputError "cannot create the output folder
  // (reason)" naming it (IoError for the system's failures: no space, I/O error). `mesh` (the skin,
  // in cm) must outlive the exporter; `frames` is how many will come (memory reserved for them);
  // `units` is the head's own unit, the OBJ's and PC2's; `glb` how exact the GLB's frames are.
  AnimationExporter(std::filesystem::path out, ExportFormats formats, std::string name, const TriMesh& mesh,
                    double fps, int frames, LengthUnit units = LengthUnit::cm, GlbOptions glb = {});

  // Frame f's skin positions (n×3, cm): its OBJ written now (writeObj, in the head's unit), kept
  // for the GLB and PC2. Returns the OBJ's name relative to out, or "" when no OBJ is written.
  std::string addFrame(int f, const MatX3& positions);

  // Writes the GLB, then the PC2, of the frames added; returns their names relative to out.
  std::vector<std::string> finish();

  const ExportFormats& formats() const { return formats_; }
  const AnimationFrames& frames() const { return animation_; }  // the frames kept (GLB or PC2 only), cm
  // What the GLB holds (targets, largest error, fps), once finish() wrote it; nullptr before or
  // without a GLB.
  const GlbReport* glbReport() const { return glb_ ? &*glb_ : nullptr; }

 private:
  std::filesystem::path out_;
  ExportFormats formats_;
  const TriMesh& mesh_;
  AnimationFrames animation_;
  double perCm_ = 1.0;  // the head's unit per cm
  GlbOptions glbOptions_;
  std::optional<GlbReport> glb_;
};

}  // namespace myo
