// Heads (the built-in one, a head folder, an OBJ with its landmark file), the muscle libraries'
// names, and writing a shape as OBJ in the head's own unit.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "bindings.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/auto_landmark_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/io/muscle_library_file.h"
#include "myoshell/io/obj_writer.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

std::string text(const py::object& o) { return o.is_none() ? std::string() : py::str(o).cast<std::string>(); }

// findLandmarkFile (the command line's path for an OBJ without --landmarks), its result as a dict.
FoundLandmarkFile findLandmarks(const std::string& obj, const py::object& units, const py::object& cache) {
  std::optional<LengthUnit> unit;
  if (!units.is_none()) unit = parseLengthUnit(text(units));
  const fs::path cacheFolder = cache.is_none() ? fs::path() : fs::path(text(cache));  // with the GIL
  py::gil_scoped_release unlocked;  // a second or two of search
  return findLandmarkFile(obj, cacheFolder, unit);
}

py::dict foundDict(const FoundLandmarkFile& f) {
  py::dict d;
  d["path"] = f.path;
  d["reused"] = f.reused;
  d["units"] = std::string(lengthUnitName(f.unit));
  d["units_inferred"] = f.unitInferred;
  d["eyes"] = f.eyesOpen ? "open" : "closed";
  d["mouth"] = f.mouthOpen ? "open" : "closed";
  d["warnings"] = f.warnings;
  d["seconds"] = f.seconds;
  return d;
}

// The command line's line on automatic landmarks, as a UserWarning.
void warnFound(const FoundLandmarkFile& f) {
  std::string line = (f.reused ? "using the landmarks of " + f.obj + " found automatically before (" + f.path
                               : "found the landmarks of " + f.obj + " automatically (written to " + f.path) +
                     "; units " + lengthUnitName(f.unit) + (f.unitInferred ? ", inferred from its size" : "") + ")";
  for (const std::string& w : f.warnings) line += "; " + w;
  if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 1) != 0) throw py::error_already_set();
}

std::shared_ptr<HeadHandle> loadHeadHandle(const std::string& head, std::string landmarks, const std::string& pins,
                                           const py::object& units, const py::object& cache) {
  std::string unitName = units.is_none() ? "cm" : text(units);
  // An OBJ without a landmark file: found automatically, as every command does (docs/heads.md).
  if (landmarks.empty() && head != "default" && fs::is_regular_file(head)) {
    const FoundLandmarkFile f = findLandmarks(head, units, cache);
    landmarks = f.path;
    unitName = lengthUnitName(f.unit);
    warnFound(f);
  }
  const HeadFiles files = resolveHeadArgument(head, landmarks, pins, unitName);
  auto handle = std::make_shared<HeadHandle>();
  handle->obj = files.obj;
  handle->unit = files.unit;
  py::gil_scoped_release unlocked;
  // Python's Face is the anatomical model: the built-in head as that model uses it (open eyes).
  handle->head = files.builtIn() ? loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical))
                                 : loadHead(files.obj, files.landmarks, files.pins, files.unit);
  return handle;
}

std::vector<std::string> muscleNames(const std::string& library) {
  const std::vector<MuscleDef>* builtin = builtinMuscleLibrary(library, FaceModelKind::Anatomical);
  const std::vector<MuscleDef> defs = builtin ? *builtin : readMuscleDefs(library);
  std::vector<std::string> names;
  for (const MuscleDef& d : defs) names.push_back(d.name);
  return names;
}

}  // namespace

void writeHeadObj(const HeadHandle& h, const std::string& path, const MatX3& positions) {
  const fs::path p(path);
  if (fs::is_directory(p)) throw InputError("is a folder; give the OBJ file to write", path);
  const fs::path parent = p.parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) throw InputError("no such folder '" + parent.string() + "'");
  // As `myoshell pose --out`: back in the file's unit (exact in cm); a head read from a file as a copy
  // of that file with new positions (UV seams, quads, groups kept), the built-in head as its mesh.
  const MatX3 shape = positions / centimetresPer(h.unit);
  if (h.obj.empty() || !writeObjLikeFile(path, h.head.mesh.sourcePath, shape)) writeObj(path, h.head.mesh, &shape);
}

void completeFitHeadLandmarks(FitHeadOptions& o, const RigFile* rig, const py::object& cache) {
  if (!o.landmarks.empty()) return;
  const fs::path cacheFolder = cache.is_none() ? fs::path() : fs::path(text(cache));
  FoundLandmarkFile f;
  if (usesRigBase(o, rig)) {
    py::gil_scoped_release unlocked;
    f = findRigBaseLandmarkFile(*rig, cacheFolder);
  } else if (o.head != "default" && fs::is_regular_file(o.head)) {
    f = findLandmarks(o.head, o.unitsGiven ? py::object(py::str(o.units)) : py::object(py::none()), cache);
    o.units = lengthUnitName(f.unit);
  } else {
    return;  // the built-in head, a head folder, or a file error the head's reader names
  }
  o.landmarks = f.path;
  warnFound(f);
}

void bindHeads(py::module_& m) {
  py::class_<HeadHandle, std::shared_ptr<HeadHandle>>(m, "Head", R"doc(
A face mesh with its landmarks, in cm (+y up, +z out of the face, +x the subject's left).
Made by load_head(); pass it to Face(head=...).)doc")
      .def_property_readonly("name", [](const HeadHandle& h) { return h.head.name; },
                             "'default', or the OBJ file's stem")
      .def_property_readonly("vertex_count", [](const HeadHandle& h) { return h.head.mesh.vertexCount(); })
      .def_property_readonly("triangle_count", [](const HeadHandle& h) { return h.head.mesh.triangleCount(); })
      .def_property_readonly("obj_path", [](const HeadHandle& h) -> py::object {
            return h.obj.empty() ? py::object(py::none()) : py::object(py::str(h.obj));
          }, "The OBJ file the head was read from; None for the built-in head")
      .def_property_readonly("units", [](const HeadHandle& h) { return std::string(lengthUnitName(h.unit)); },
                             "The unit the head's OBJ is written in: 'cm', 'm' or 'mm' (positions here are always cm)")
      .def_property_readonly("has_jaw", [](const HeadHandle& h) { return h.head.landmarks.multipie68.size() == 68; },
                             "Whether the landmarks have the 68-point jaw line a jaw pose needs (docs/jaw.md)")
      .def("rest_positions", [](const HeadHandle& h) { return toNumpy(h.head.mesh.V); },
           "The rest positions: float64 array (n, 3), cm.")
      .def("triangles", [](const HeadHandle& h) { return toNumpy(h.head.mesh.F); },
           "The triangles: int32 array (m, 3) of vertex indices, counter-clockwise seen from outside.")
      .def("landmarks", [](const HeadHandle& h) { return h.head.landmarks.resolved(); },
           "Every landmark the head resolves: dict name -> vertex index.")
      .def_property_readonly("gravity_pins", [](const HeadHandle& h) { return h.head.gravityPins; },
                             "Sorted vertex indices held fixed under gravity (list of int)")
      .def("write_obj", [](const HeadHandle& h, const fs::path& path, const py::object& positions) {
            const MatX3 V = positions.is_none() ? h.head.mesh.V : toMatX3(positions, "positions", h.head.mesh.vertexCount());
            writeHeadObj(h, path.string(), V);
          }, py::arg("path"), py::arg("positions") = py::none(), R"doc(
Writes positions (float array (n, 3), cm; default: the rest shape) as an OBJ in the head's vertex
order and own unit, as `myoshell pose --out` does: a head read from a file is written as a copy of
that file with its positions replaced. The folder must exist. InputError otherwise.)doc")
      .def("__repr__", [](const HeadHandle& h) {
        return "<myoshell.Head '" + h.head.name + "': " + std::to_string(h.head.mesh.vertexCount()) + " vertices>";
      });

  m.def("load_head",
        [](const py::object& head, const py::object& landmarks, const py::object& units, const py::object& pins,
           const py::object& cache) {
          return loadHeadHandle(head.is_none() ? "default" : text(head), text(landmarks), text(pins), units, cache);
        },
        py::arg("head") = "default", py::arg("landmarks") = py::none(), py::arg("units") = py::none(),
        py::arg("pins") = py::none(), py::arg("cache") = py::none(), R"doc(
Loads a head as `myoshell --head` names it:
  load_head()                                   the built-in head (about 7.2k vertices)
  load_head("../shared/data/ict")               a folder with head_skin.obj and its landmark file
  load_head("face.obj", landmarks="face.json", units="mm")   any OBJ head (docs/heads.md)
  load_head("face.obj")                         landmarks found automatically (find_landmarks)
units: the OBJ's length unit, 'm', 'mm' or 'cm' (the head is used in cm); default 'cm' with a
landmark file, the unit inferred from the face's size without one. Without landmarks the file
find_landmarks writes (in `cache`/landmarks, else the temporary folder) is used and a UserWarning
says where. pins: a vertex-set file of gravity pins (default: a folder's rigid_vertices.json, else
the rim rule). Raises InputError with the command line's message for a missing file, a bad unit,
a mesh that is not a head or a head that fails the checks.)doc");

  m.def("find_landmarks",
        [](const fs::path& obj, const py::object& units, const py::object& cache) {
          return foundDict(findLandmarks(obj.string(), units, cache));
        },
        py::arg("obj"), py::arg("units") = py::none(), py::arg("cache") = py::none(), R"doc(
Finds an OBJ head's landmarks automatically, as `myoshell landmarks` and every command given an OBJ
without --landmarks do (docs/heads.md), and keeps the landmark file in `cache`/landmarks (a basis
cache folder; default: the temporary folder's myoshell-landmarks), keyed on the OBJ's bytes: a
second call on the same file reuses it. units: 'm', 'mm' or 'cm' (default: inferred from the size).
Returns a dict: path (the landmark file, editable, for load_head(landmarks=...)), reused, units,
units_inferred, eyes and mouth ('open' or 'closed'), warnings, seconds. InputError for a mesh that
is not a head.)doc");

  m.def("muscle_names", &muscleNames, py::arg("library") = defaultMuscleLibrary(), R"doc(
The muscle names of a library, in its order: 'face' (the whole face's 40, docs/muscles.md; the
default), 'builtin' (the built-in ten: the thesis's eight and the lips' two rings) or the path of a
library file (JSON or YAML).)doc");
}

}  // namespace myo::python
