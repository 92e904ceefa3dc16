// Blendshape rigs from glTF files (io/rig_file.h): the base mesh and its named shapes, in cm; a
// shape is a target for Face.fit on the rig's head.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "bindings.h"
#include "myoshell/io/rig_file.h"

namespace myo::python {

void bindRigs(py::module_& m) {
  py::class_<RigFile, std::shared_ptr<RigFile>>(m, "Rig", R"doc(
A blendshape rig read from a glTF 2.0 file (.glb or .gltf; docs/rigs.md): a base mesh and named
shapes, in cm (glTF's metres times 100), vertices welded as `myoshell fit RIG.glb#shape` reads them.)doc")
      .def_property_readonly("path", [](const RigFile& r) { return r.path; })
      .def_property_readonly("shape_names", [](const RigFile& r) { return r.names; }, "In the file's order")
      .def_property_readonly("vertex_count", [](const RigFile& r) { return r.vertexCount(); })
      .def("rest_positions", [](const RigFile& r) { return toNumpy(r.base.V); },
           "The base mesh's positions: float64 array (n, 3), cm.")
      .def("triangles", [](const RigFile& r) { return toNumpy(r.base.F); }, "The base's triangles: int32 (m, 3).")
      .def("shape", [](const RigFile& r, const std::string& name) { return toNumpy(r.shape(name)); }, py::arg("name"),
           "A shape's positions: float64 array (n, 3), cm. InputError listing the rig's shapes for an unknown name.")
      .def("delta", [](const RigFile& r, const std::string& name) { return toNumpy(r.delta(name)); }, py::arg("name"),
           "A shape minus the base: float64 array (n, 3), cm.")
      .def("__repr__", [](const RigFile& r) {
        return "<myoshell.Rig '" + r.path + "': " + std::to_string(r.names.size()) + " shapes, " +
               std::to_string(r.vertexCount()) + " vertices>";
      });

  m.def("read_rig", [](const std::filesystem::path& path) {
          auto rig = std::make_shared<RigFile>();
          py::gil_scoped_release unlocked;
          *rig = readRig(path.string());
          return rig;
        }, py::arg("path"), "Reads a glTF rig (Rig). InputError naming the file and the fault on bad input.");
}

}  // namespace myo::python
