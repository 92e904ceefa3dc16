// myoshell.drive: a recorded performance played on a head, as `myoshell drive` plays it (the scene of
// io/performance_scene.h through the one frame loop, ScenePlayer), its frames returned as one array
// and its exports written as the command line writes them (io/animation_exporter.h).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/core.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "bindings.h"
#include "myoshell/anim/head_motion.h"
#include "myoshell/anim/performance.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/animation_exporter.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/performance_scene.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

std::string text(const py::object& o) { return o.is_none() ? std::string() : py::str(o).cast<std::string>(); }

double number(const py::object& o, const char* name) {
  try {
    return o.cast<double>();
  } catch (const py::cast_error&) {
    throw InputError(fmt::format("{}: expected a number", name));
  }
}

// A number the command line checks with a validator: > 0 (`positive`) or in [low, high].
double checked(const py::object& o, const char* name, double low, double high, bool positive) {
  const double v = number(o, name);
  if (!std::isfinite(v) || (positive ? v <= 0.0 : (v < low || v > high)))
    throw InputError(positive ? fmt::format("{}: expected a number > 0, got {}", name, v)
                              : fmt::format("{}: expected a number in [{}, {}], got {}", name, low, high, v));
  return v;
}

py::dict drive(const py::object& performance, const py::object& out, const std::vector<std::string>& formatNames,
               const py::object& head, const py::object& landmarks, const py::object& units, const std::string& library,
               const py::object& map, const py::object& input, const py::object& auScale, const py::object& face,
               double minConfidence, const py::object& inputFps, const py::object& filter, const py::object& minCutoff,
               const py::object& beta, double start, const py::object& end, bool headMotion, const py::object& cacheDir,
               double glbToleranceMm) {
  PerformanceSceneDef def;
  def.performance = text(performance);
  def.head = head.is_none() ? "default" : text(head);
  def.landmarks = text(landmarks);
  def.units = units.is_none() ? "cm" : text(units);
  def.library = library;
  def.map = text(map);
  def.input = text(input);
  if (!auScale.is_none()) def.auScale = checked(auScale, "au_scale", 0, 0, true);
  if (!face.is_none()) def.face = static_cast<int>(checked(face, "face", 0, 1e9, false));
  def.minConfidence = checked(py::float_(minConfidence), "min_confidence", 0.0, 1.0, false);
  if (!inputFps.is_none()) def.inputFps = checked(inputFps, "input_fps", 0, 0, true);
  def.filter = py::isinstance<py::bool_>(filter) ? (filter.cast<bool>() ? "on" : "off") : text(filter);
  if (!minCutoff.is_none()) def.oneEuro.minCutoff = number(minCutoff, "min_cutoff");
  if (!beta.is_none()) def.oneEuro.beta = number(beta, "beta");
  if (!(start >= 0.0)) throw InputError(fmt::format("start: expected a number ≥ 0, got {}", start));
  def.start = start;
  if (!end.is_none()) def.end = number(end, "end");

  // In drive's order: the scene (its performance read), then, as runScene, the output folder and
  // the formats, then the face's build.
  SceneDesc scene;
  {
    py::gil_scoped_release unlocked;
    scene = performanceScene(def);
  }
  const fs::path outDir = text(out);
  if (!out.is_none() && fs::exists(outDir) && !fs::is_directory(outDir))
    throw InputError("output path exists and is not a folder", outDir.string());
  const ExportFormats formats = parseExportFormats(formatNames);
  const GlbOptions glbOptions = glbOptionsForTolerance(glbToleranceMm, "glb_tolerance");
  std::unique_ptr<BasisCache> cache;
  if (!cacheDir.is_none()) cache = std::make_unique<FileBasisCache>(text(cacheDir));
  std::shared_ptr<const FaceSystem> model;
  {
    py::gil_scoped_release unlocked;
    model = buildSceneFace(scene, cache.get());
  }
  for (const std::string& w : scene.performanceReport->warnings)  // the command line's warnings on stderr
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();

  std::optional<AnimationExporter> exporter;
  ScenePlayer player(scene, model);
  const int frameCount = player.frameCount();
  if (!out.is_none()) exporter.emplace(outDir, formats, scene.name, model->head().mesh, scene.fps, frameCount, scene.head.units, glbOptions);
  const Eigen::Index n = model->head().mesh.vertexCount();
  py::array_t<double> frames({static_cast<py::ssize_t>(frameCount), static_cast<py::ssize_t>(n), py::ssize_t{3}});
  py::array_t<double> times(frameCount);
  double* framesData = frames.mutable_data();
  double* timesData = times.mutable_data();
  const bool turnHead = headMotion && !scene.headPose.empty();
  std::vector<std::string> written;
  long long steps = 0;
  {
    py::gil_scoped_release unlocked;
    MatX3 turned;
    for (int f = 0; f < frameCount; ++f) {
      player.advanceTo(f);
      const FrameSnapshot& snap = player.snapshot(false);
      steps += snap.steps;
      const MatX3* shown = &snap.positions;
      if (turnHead) {
        turnWithHead(snap.positions, model->head().frame(), scene.headPose, snap.time, turned);
        shown = &turned;
      }
      std::memcpy(framesData + f * n * 3, shown->data(), sizeof(double) * static_cast<size_t>(n * 3));
      timesData[f] = snap.time;
      if (exporter)
        if (const std::string rel = exporter->addFrame(f, *shown); !rel.empty()) written.push_back(rel);
      py::gil_scoped_acquire locked;  // Ctrl-C is seen between frames
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    if (exporter)
      for (const std::string& rel : exporter->finish()) written.push_back(rel);
  }

  const PerformanceReport& p = *scene.performanceReport;
  py::dict report;
  report["file"] = p.file;
  report["input"] = toString(p.input);
  report["au_scale"] = p.auScale;
  report["frames"] = p.frames;
  report["fps"] = p.fps;
  report["duration"] = p.duration;
  report["dropped_frames"] = p.droppedFrames;
  report["warnings"] = p.warnings;
  report["unmapped"] = p.unmapped;
  py::dict result;
  result["name"] = scene.name;
  result["frames"] = frames;
  result["times"] = times;
  result["fps"] = scene.fps;
  result["rest"] = toNumpy(model->head().mesh.V);
  result["triangles"] = toNumpy(model->head().mesh.F);
  result["muscle_names"] = [&] {
    std::vector<std::string> names;
    for (int i = 0; i < model->muscleCount(); ++i) names.push_back(model->muscleName(i));
    return names;
  }();
  result["steps"] = steps;
  result["performance"] = report;
  result["written"] = written;
  if (const GlbReport* glb = exporter ? exporter->glbReport() : nullptr) result["glb"] = glbDict(*glb);
  return result;
}

}  // namespace

void bindDrive(py::module_& m) {
  m.def("drive", &drive, py::arg("performance"), py::kw_only(), py::arg("out") = py::none(),
        py::arg("formats") = std::vector<std::string>{"glb"}, py::arg("head") = "default",
        py::arg("landmarks") = py::none(), py::arg("units") = py::none(), py::arg("library") = defaultMuscleLibrary(),
        py::arg("map") = py::none(), py::arg("input") = py::none(), py::arg("au_scale") = py::none(),
        py::arg("face") = py::none(), py::arg("min_confidence") = 0.7, py::arg("input_fps") = py::none(),
        py::arg("filter") = true, py::arg("min_cutoff") = py::none(), py::arg("beta") = py::none(),
        py::arg("start") = 0.0, py::arg("end") = py::none(), py::arg("head_motion") = false,
        py::arg("cache") = py::none(), py::arg("glb_tolerance") = kDefaultGlbToleranceMm, R"doc(
Plays a recorded performance (OpenFace action units, Live Link Face or MediaPipe blendshape weights;
docs/performance_input.md) on a head, as `myoshell drive` plays it: the frames come at the
performance's rate over its duration, simulated by the frame loop every app uses.
performance: the file. out: a folder to write the exports to (made if missing; None: nothing
written); formats: any of 'glb' (OUT/NAME.glb), 'pc2' (OUT/NAME.pc2), 'obj' (OUT/obj/NAME_NNNN.obj),
NAME being the file's stem; the files are the command line's byte for byte (its stats.json, output
manifest and video are not written here).
head, landmarks, units: as load_head(); library: 'face' (default), 'builtin' or a library file;
map: ARKit input's retargeting map (default the shipped one); input: 'openface', 'livelink',
'mediapipe' (default from the header); au_scale (> 0), face (OpenFace face_id ≥ 0), min_confidence
[0, 1], input_fps (> 0, Hz): as drive's options; filter: the One-Euro filter, True/False (or
'on'/'off'), min_cutoff (Hz) and beta its settings; start, end: the window played, s after the
first frame; head_motion: turn the frames with the performance's head rotation; cache: a basis
cache folder or None; glb_tolerance: the GLB's largest vertex error in any frame, mm (> 0; default
0.05, as --glb-tolerance). The GIL is released while it plays (Ctrl-C is seen between frames).
Returns a dict: frames float64 (F, n, 3) cm (frame k at times[k] = k / fps s), times (F,), fps,
name, rest (n, 3), triangles int32 (m, 3), muscle_names, steps, written (files relative to out),
performance (file, input, au_scale, frames, fps, duration, dropped_frames, warnings, unmapped; each
warning is also a UserWarning), and with a GLB written glb (targets, tolerance_mm, max_error_mm, within_tolerance,
fps, frames, vertices; docs/exports.md). The OBJ frames and the PC2 are in the head's units, the GLB
in metres; frames, rest and times stay in cm. InputError with drive's messages; SimulationError; IoError.)doc");
}

}  // namespace myo::python
