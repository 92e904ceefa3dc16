// What the binding files share: the objects Python holds (a head with the files it came from, a
// built face), NumPy conversions, and each file's bind function (module.cpp calls them in order).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/types.h"
#include "myoshell/head/head.h"
#include "myoshell/io/animation_export.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/io/rig_file.h"
#include "myoshell/reduce/basis_cache.h"

namespace myo::python {

namespace py = pybind11;

// A loaded head and where it came from: writing a shape back needs the OBJ file and its unit.
struct HeadHandle {
  Head head;              // in cm
  std::string obj;        // the OBJ file; "" for the built-in head
  LengthUnit unit = LengthUnit::cm;  // the unit the OBJ is written in
};

// A built anatomical face (the model a scene with only this head would build) and its head.
struct FaceHandle {
  std::shared_ptr<const HeadHandle> head;
  std::shared_ptr<const AnatomicalFace> face;
  std::shared_ptr<BasisCache> cache;  // kept for the face's lifetime (null: none)
  // What it was built from, as a scene names it (io/scene_face.h's sceneMuscleLibrary: "face",
  // "builtin" or an absolute file; the names used, empty = all): the live input maps onto it.
  std::string library;
  std::vector<std::string> muscles;
};

// A Simulator: a face's AnatomicalSimulator (a FaceStepper).
struct SimulatorHandle {
  std::shared_ptr<FaceHandle> face;
  AnatomicalSimulator sim;
  explicit SimulatorHandle(std::shared_ptr<FaceHandle> f) : face(std::move(f)), sim(face->face) {}
};

// A ScenePlayer: a scene played by the one frame loop (its simulator() is the FaceStepper).
struct PlayerHandle {
  std::shared_ptr<BasisCache> cache;
  std::unique_ptr<ScenePlayer> player;
};

// The fitting functions' head (rig, fit_rig) without a landmark file: an OBJ head's, or a rig's base
// mesh's when no head is given, found automatically as load_head finds them (the same UserWarning),
// into options.landmarks (and options.units when none was given). Needs the GIL.
void completeFitHeadLandmarks(FitHeadOptions& options, const RigFile* rig, const py::object& cache);

// NumPy copies of the library's n×3 arrays: float64 (n, 3) and int32 (m, 3).
py::array_t<double> toNumpy(const MatX3& m);
py::array_t<int> toNumpy(const MatX3i& m);
// An (n, 3) array-like of finite numbers as an n×3 matrix; `rows` < 0 accepts any n. InputError
// naming `what` for another shape or a non-finite value.
MatX3 toMatX3(const py::handle& array, const std::string& what, Eigen::Index rows = -1);
// Frames as one float64 (F, n, 3) copy, and back: an (F, n, 3) array-like (or a sequence of (n, 3)
// arrays) of finite numbers, F ≥ 1, n = `rows` (any n when < 0); InputError naming `what` otherwise.
py::array_t<double> toNumpy(const std::vector<MatX3>& frames);
std::vector<MatX3> toFrames(const py::handle& frames, const std::string& what, Eigen::Index rows);

// The skin mesh (cm) of a Head or a Face given to a function as `head`; InputError for anything else.
const TriMesh& meshOf(const py::handle& headOrFace);

// Writes `positions` (n×3, cm) as an OBJ in the head's own unit, as `myoshell pose --out` does.
void writeHeadObj(const HeadHandle& head, const std::string& path, const MatX3& positions);

// An animation GLB's report (io/animation_export.h) as drive's and write_glb's dict: targets,
// max_error_mm, within_tolerance, fps, frames, vertices (the CLI's --json "glb").
py::dict glbDict(const GlbReport& report);

void bindErrors(py::module_& m);
void bindHeads(py::module_& m);
void bindFace(py::module_& m);
void bindSimulator(py::module_& m);
void bindScenePlayer(py::module_& m);
void bindRigs(py::module_& m);
void bindRigMaking(py::module_& m);
void bindRigFitting(py::module_& m);
void bindDrive(py::module_& m);
void bindExports(py::module_& m);
void bindThreads(py::module_& m);
void bindLive(py::module_& m);

}  // namespace myo::python
