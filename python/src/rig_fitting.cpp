// myoshell.fit_rig: every ARKit-named shape of a glTF rig fitted to activations of the anatomical
// face, as `myoshell fit-rig` fits them (io/rig_fitting.h); the retargeting map written when asked.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>

#include "bindings.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/output_paths.h"
#include "myoshell/io/retarget_map_file.h"
#include "myoshell/io/auto_landmark_file.h"
#include "myoshell/io/rig_fitting.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo::python {
namespace {

std::string text(const py::object& o) { return o.is_none() ? std::string() : py::str(o).cast<std::string>(); }

py::dict namedValues(const NamedValues& values) {
  py::dict d;
  for (const auto& [name, v] : values) d[py::str(name)] = v;
  return d;
}

py::object orNone(bool has, double value) { return has ? py::object(py::float_(value)) : py::object(py::none()); }

py::dict fitRigShapesPy(const py::object& rigOrPath, const py::object& head, const py::object& landmarks,
                        const py::object& units, const std::string& library, const py::object& sparsity,
                        const py::object& cacheDir, const py::object& out) {
  FitSettings settings;
  // The command line's --lambda text, so that the messages are its own ("--lambda: '-1' is not a number ≥ 0").
  settings.lambda = parseLambda(py::str(sparsity).cast<std::string>());
  const std::string outPath = text(out);
  checkOutputFile(outPath, "--out", "map file (JSON)");
  FitHeadOptions options;
  options.head = head.is_none() ? "default" : text(head);
  options.landmarks = text(landmarks);
  options.units = units.is_none() ? "cm" : text(units);
  options.library = library;
  options.headGiven = !head.is_none();
  options.unitsGiven = !units.is_none();

  std::shared_ptr<const RigFile> rig;
  if (py::isinstance<RigFile>(rigOrPath)) rig = rigOrPath.cast<std::shared_ptr<RigFile>>();
  const std::string rigFile = rig ? std::string() : text(rigOrPath);  // Python objects: read with the GIL
  const std::string cacheFolder = text(cacheDir);
  std::unique_ptr<BasisCache> cache;
  FittedRig fitted;
  std::optional<FoundLandmarkFile> found;
  {
    py::gil_scoped_release unlocked;  // the build and one fit per shape: seconds
    if (!rig) rig = std::make_shared<const RigFile>(readRig(rigFile));
    if (usesRigBase(options, rig.get()) && options.landmarks.empty()) {  // as the command line: found automatically
      found = findRigBaseLandmarkFile(rig->path, rig->base, cacheFolder);
      options.landmarks = found->path;
    }
    const SceneInputs inputs = rigFitInputs(*rig, options);
    if (!cacheFolder.empty()) cache = std::make_unique<FileBasisCache>(cacheFolder);
    fitted = fitRigShapes(*rig, inputs, options.library, settings, cache.get());
  }
  if (found)  // the command line's line, as a warning
    if (PyErr_WarnEx(PyExc_UserWarning,
                     (rig->path + ": the rig's base carries no landmarks; found automatically (" + found->path +
                      "; pass it as landmarks to edit)").c_str(), 1) != 0)
      throw py::error_already_set();
  const RigFit& fit = fitted.fit;
  for (const std::string& n : fit.skipped)  // the command line's warning, without its program name
    if (PyErr_WarnEx(PyExc_UserWarning, (rig->path + ": shape '" + n + "' is no ARKit name; not fitted").c_str(), 1) != 0)
      throw py::error_already_set();
  if (!outPath.empty()) writeRetargetMapFile(outPath, fit.map);

  py::list shapes;
  py::dict activations;
  for (size_t i = 0; i < fit.shapes.size(); ++i) {
    const RigShapeFit& s = fit.shapes[i];
    const RetargetShape& entry = *fit.map.find(s.name);  // by name: the map holds every ARKit name
    const bool f = s.fit.has_value();
    py::dict d;
    d["name"] = s.name;
    d["reachable"] = s.reachable;
    d["reason"] = s.reason;
    d["sources"] = s.sources;
    d["corrective_of"] = s.correctiveOf.empty() ? py::object(py::none()) : py::object(py::str(s.correctiveOf));
    d["cosine"] = orNone(f, f ? s.fit->metric.cosine : 0.0);
    d["magnitude_ratio"] = orNone(f, f ? s.fit->metric.magnitudeRatio : 0.0);
    d["rms_mm"] = orNone(f, f ? s.fit->rmsMm : 0.0);
    d["max_mm"] = orNone(f, f ? s.fit->maxMm : 0.0);
    d["compared_vertices"] = f ? s.fit->metric.comparedVertices : 0;
    d["activations"] = namedValues(entry.activations);
    d["jaw"] = namedValues(entry.jaw);
    d["target"] = toNumpy(s.target);
    d["displacement"] = f ? py::object(toNumpy(s.fit->displacement)) : py::object(py::none());
    shapes.append(d);
    activations[py::str(s.name)] = namedValues(entry.activations);
  }
  py::dict result;
  result["rig"] = rig->path;
  result["head"] = fitted.face->head().name;
  result["muscle_names"] = [&] {
    std::vector<std::string> names;
    for (int i = 0; i < fitted.face->muscleCount(); ++i) names.push_back(fitted.face->muscleName(i));
    return names;
  }();
  result["activations"] = activations;
  result["shapes"] = shapes;
  result["median_cosine"] = fit.medianCosine;
  result["median_rms_mm"] = fit.medianRmsMm;
  result["skipped"] = fit.skipped;
  result["map"] = serialiseRetargetMap(fit.map);
  result["out"] = outPath.empty() ? py::object(py::none()) : py::object(py::str(outPath));
  result["build_seconds"] = fitted.buildSeconds;
  result["fit_seconds"] = fit.seconds;
  return result;
}

}  // namespace

void bindRigFitting(py::module_& m) {
  m.def("fit_rig", &fitRigShapesPy, py::arg("rig"), py::kw_only(), py::arg("head") = py::none(),
        py::arg("landmarks") = py::none(), py::arg("units") = py::none(), py::arg("library") = defaultMuscleLibrary(),
        py::arg("sparsity") = 0.02, py::arg("cache") = py::none(), py::arg("out") = py::none(), R"doc(
Fits every ARKit-named shape of a glTF rig to activations of the anatomical face, as `myoshell
fit-rig` does (docs/fitting.md, "Fitting a rig"), and gathers them into a retargeting map that rig()
plays on any head.
rig: a Rig (read_rig) or the path of a .glb/.gltf file.
head: None (the rig's base mesh; its landmarks file, else found automatically and kept in cache), or as load_head() names a head ('default',
  a head folder, an OBJ file with landmarks and units); its vertices must be the rig's.
library: the muscles ('face', the default, 'builtin' or a library file); sparsity: the weight λ ≥ 0 (--lambda);
cache: a basis cache folder or None; out: the map's JSON file to write (the command line's bytes).
Returns a dict: activations (shape name -> {muscle: activation}), shapes (per shape, ARKit order:
name, reachable, reason, sources, corrective_of, cosine, magnitude_ratio, rms_mm, max_mm (None when
not fitted), compared_vertices, activations, jaw, target and displacement float64 (n, 3) cm: what was
fitted and the fit's shape), median_cosine, median_rms_mm, skipped (names that are no ARKit name; a
UserWarning each), map (the map's JSON text), muscle_names, rig, head, out, build_seconds,
fit_seconds. InputError with the command line's messages; SimulationError; IoError.)doc");
}

}  // namespace myo::python
