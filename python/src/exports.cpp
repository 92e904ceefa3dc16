// The animation exports (io/animation_export.h, io/animation_exporter.h) for frames made in Python:
// an OBJ sequence, a GLB with the frames as morph targets, a PC2 point cache — the files `myoshell
// run` and `drive` write for the same frames, byte for byte.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "bindings.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/animation_exporter.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

// The file's folder must exist and the path must not be a folder (as the command line's outputs).
void checkFilePath(const fs::path& path, const std::string& what) {
  if (fs::is_directory(path)) throw InputError("is a folder; give the " + what + " to write", path.string());
  const fs::path parent = path.parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) throw InputError("no such folder '" + parent.string() + "'");
}

double checkedFps(double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw InputError("fps: expected a frame rate > 0, got " + std::to_string(fps));
  return fps;
}

AnimationFrames animationOf(const py::handle& head, const py::handle& frames, double fps, const std::string& name) {
  const TriMesh& mesh = meshOf(head);
  AnimationFrames a;
  a.name = name;
  a.triangles = mesh.F;
  a.rest = mesh.V;
  a.uv = mesh.UV;
  a.cornerUV = mesh.cornerUV;
  a.fps = checkedFps(fps);
  a.positions = toFrames(frames, "frames", mesh.vertexCount());
  return a;
}

}  // namespace

py::dict glbDict(const GlbReport& report) {
  py::dict d;
  d["targets"] = report.targets;
  d["tolerance_mm"] = report.toleranceMm;
  d["max_error_mm"] = 10.0 * report.maxErrorCm;
  d["within_tolerance"] = report.withinTolerance;
  d["fps"] = report.fps;
  d["frames"] = report.frames;
  d["vertices"] = report.vertices;
  return d;
}

void bindExports(py::module_& m) {
  m.def("write_glb", [](const fs::path& path, const py::object& head, const py::object& frames, double fps,
                        const std::string& name, double toleranceMm) {
          const GlbOptions options = glbOptionsForTolerance(toleranceMm, "glb_tolerance");
          checkFilePath(path, "GLB file");
          const AnimationFrames a = animationOf(head, frames, fps, name);
          GlbReport report;
          {
            py::gil_scoped_release unlocked;
            report = writeGlb(path, a, options);
          }
          return glbDict(report);
        },
        py::arg("path"), py::arg("head"), py::arg("frames"), py::kw_only(), py::arg("fps") = 30.0,
        py::arg("name") = "animation", py::arg("glb_tolerance") = kDefaultGlbToleranceMm, R"doc(
Writes frames (float (F, n, 3) cm, n the head's vertex count) as a glTF binary in metres: every frame,
exact to glb_tolerance mm (> 0; default 0.05, as the command line's --glb-tolerance), as the head's mesh (a Head or a Face; UV seams split) plus a few morph targets with
a weight key at every frame, k / fps s (docs/exports.md "The animation GLB"). name: the mesh's and
animation's (drive names them after the performance file's stem). With drive's frames, fps and name
the file is drive's. Returns {targets, tolerance_mm, max_error_mm, within_tolerance, fps, frames, vertices}.)doc");

  m.def("write_pc2", [](const fs::path& path, const py::object& frames) {
          checkFilePath(path, "PC2 file");
          AnimationFrames a;
          a.positions = toFrames(frames, "frames", -1);
          a.rest = a.positions.front();  // the point count only
          py::gil_scoped_release unlocked;
          writePc2(path, a);
        },
        py::arg("path"), py::arg("frames"), R"doc(
Writes frames (float (F, n, 3) cm) as a PC2 point cache (float32, one sample per frame; Blender, 3ds
Max, Houdini read it), as `myoshell drive --format pc2` writes it.)doc");

  m.def("write_obj_sequence", [](const fs::path& folder, const py::object& head, const py::object& frames,
                                 const std::string& name) {
          const TriMesh& mesh = meshOf(head);
          const std::vector<MatX3> positions = toFrames(frames, "frames", mesh.vertexCount());
          if (fs::exists(folder) && !fs::is_directory(folder))
            throw InputError("output path exists and is not a folder", folder.string());
          ExportFormats formats;
          formats.obj = true;
          std::vector<std::string> written;
          py::gil_scoped_release unlocked;
          AnimationExporter exporter(folder, formats, name, mesh, 30.0, static_cast<int>(positions.size()));
          for (size_t f = 0; f < positions.size(); ++f) written.push_back(exporter.addFrame(static_cast<int>(f), positions[f]));
          return written;
        },
        py::arg("folder"), py::arg("head"), py::arg("frames"), py::kw_only(), py::arg("name") = "animation", R"doc(
Writes frames (float (F, n, 3) cm) as FOLDER/obj/NAME_NNNN.obj, one OBJ of the head's mesh (a Head or
a Face) per frame in cm, as `myoshell run` and `drive --format obj` write them. The folder is made if
missing. Returns the files written, relative to the folder.)doc");
}

}  // namespace myo::python
