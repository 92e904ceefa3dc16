// myoshell.rig: an ARKit blendshape rig made by physics for a head, as `myoshell rig` makes it
// (io/rig_making.h), returned as arrays and written as a glTF rig when asked.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>

#include "bindings.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/rig_making.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

std::string text(const py::object& o) { return o.is_none() ? std::string() : py::str(o).cast<std::string>(); }

py::dict makeRig(const py::object& mapPath, const py::object& head, const py::object& landmarks, const py::object& units,
                 const std::string& library, const py::object& cacheDir, const py::object& out) {
  // As `myoshell rig`: the output checked first, then the head, then the map, then the build.
  const std::string outPath = text(out);
  if (!out.is_none()) checkRigOutputPath(outPath);
  FitHeadOptions options;
  options.head = head.is_none() ? "default" : text(head);
  options.landmarks = text(landmarks);
  options.units = units.is_none() ? "cm" : text(units);
  options.library = library;
  options.headGiven = true;
  options.unitsGiven = !units.is_none();
  const std::string mapFile = text(mapPath), cacheFolder = text(cacheDir);  // Python objects: read with the GIL
  completeFitHeadLandmarks(options, nullptr, cacheDir);
  std::unique_ptr<BasisCache> cache;
  MadeRig made;
  {
    py::gil_scoped_release unlocked;  // the build and 52 settles: seconds
    const SceneInputs inputs = fitHeadInputs(options, nullptr, "rig");
    const RetargetMap map = readRigMap(mapFile, inputs.muscles, library);
    if (!cacheFolder.empty()) cache = std::make_unique<FileBasisCache>(cacheFolder);
    made = makeArkitRig(inputs, map, cache.get());
    if (!out.is_none()) writeRigGlb(outPath, made.glb);
  }
  py::list shapes;
  for (const ArkitRigShape& s : made.settled.shapes) {
    py::dict d;
    d["name"] = s.name;
    d["mapped"] = s.mapped;
    d["max_displacement_cm"] = s.maxDisplacementCm;
    d["max_displacement_vertex"] = s.maxDisplacementVertex;
    shapes.append(d);
  }
  py::dict result;
  result["head"] = made.glb.name;
  result["vertices"] = made.glb.rest.rows();
  result["shape_names"] = made.glb.names;
  result["deltas"] = toNumpy(made.glb.deltas);
  result["shapes"] = shapes;
  result["shapes_made"] = made.settled.made;
  for (const std::string& w : made.settled.warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  result["rest"] = toNumpy(made.glb.rest);
  result["triangles"] = toNumpy(made.glb.triangles);
  result["out"] = out.is_none() ? py::object(py::none()) : py::object(py::str(outPath));
  result["build_seconds"] = made.buildSeconds;
  result["settle_seconds"] = made.settleSeconds;
  return result;
}

}  // namespace

void bindRigMaking(py::module_& m) {
  m.def("rig", &makeRig, py::arg("map") = py::none(), py::kw_only(), py::arg("head") = "default",
        py::arg("landmarks") = py::none(), py::arg("units") = py::none(), py::arg("library") = defaultMuscleLibrary(), py::arg("cache") = py::none(),
        py::arg("out") = py::none(), R"doc(
An ARKit blendshape rig made by physics for a head, as `myoshell rig` makes it (docs/fitting.md,
"Making a rig"): each shape of the retargeting map `map` (a file: fit_rig(out=...) writes one; None:
the library's shipped map, assets/retarget/arkit_ict_face.json for the whole face) settled on the
head's anatomical face without gravity.
head, landmarks, units: the head as load_head() names it ('default', a head folder, an OBJ file);
library: the muscles, 'face' (the whole face, the default), 'builtin' or a library file (the map's
muscles must be among them);
cache: a basis cache folder or None; out: a .glb file to write the rig to (its folder must exist),
byte for byte the command line's, or None.
Returns a dict: shape_names (the 52 ARKit names, ARKit's order), deltas float64 (52, n, 3) cm
(shape minus rest; zero where the map has no reachable entry; mouthClose is what it adds to jawOpen),
shapes (per shape: name, mapped, max_displacement_cm, max_displacement_vertex), shapes_made, head,
vertices, rest (n, 3) cm, triangles int32 (m, 3), out, build_seconds, settle_seconds.
InputError with the command line's messages (a bad map, a map of another library's muscles, a bad
output path); SimulationError when a warped solve does not converge; IoError when writing fails.)doc");
}

}  // namespace myo::python
