// A played scene's animation exports, frame by frame (`myoshell run` and `drive`, Python's
// myoshell.drive): the OBJ sequence DIR/obj/NAME_NNNN.obj written as the frames come, and the GLB
// (DIR/NAME.glb) and PC2 (DIR/NAME.pc2) of io/animation_export.h written at the end from the frames
// kept. File names are relative to DIR, as the output manifest (io/output_manifest.h) lists them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

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
  // in cm) must outlive the exporter; `frames` is how many will come (memory reserved for them).
  AnimationExporter(std::filesystem::path out, ExportFormats formats, std::string name, const TriMesh& mesh,
                    double fps, int frames);

  // Frame f's skin positions (n×3, cm): its OBJ written now (writeObj, cm), kept for the GLB and
  // PC2. Returns the OBJ's name relative to out, or "" when no OBJ is written.
  std::string addFrame(int f, const MatX3& positions);

  // Writes the GLB, then the PC2, of the frames added; returns their names relative to out.
  std::vector<std::string> finish();

  const ExportFormats& formats() const { return formats_; }
  const AnimationFrames& frames() const { return animation_; }  // the frames kept (GLB or PC2 only)

 private:
  std::filesystem::path out_;
  ExportFormats formats_;
  const TriMesh& mesh_;
  AnimationFrames animation_;
};

}  // namespace myo
