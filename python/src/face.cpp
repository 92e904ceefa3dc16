// The anatomical face (docs/anatomical_model.md) built on a head, its static pose under
// activations (`myoshell pose`), and the activation fit (`myoshell fit`).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "activations.h"
#include "bindings.h"
#include "myoshell/anim/scene.h"
#include "myoshell/anim/scene_parser.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/activation_fit.h"
#include "myoshell/head/jaw.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/muscle_library_file.h"
#include "myoshell/io/scene_face.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/muscles/muscle.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

NamedValues namedValues(const py::object& activations) {
  NamedValues values;
  if (activations.is_none()) return values;
  if (!py::isinstance<py::dict>(activations)) throw InputError("activations: expected a dict muscle name -> value");
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(activations)) {
    const std::string name = py::str(key).cast<std::string>();
    try {
      values.emplace_back(name, value.cast<double>());
    } catch (const py::cast_error&) {
      throw InputError("activations: the value of '" + name + "' is not a number");
    }
  }
  return values;
}

Vec3 threeNumbers(const py::object& o, const std::string& what) {
  std::vector<double> v;
  try {
    v = o.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw InputError(what + ": expected three numbers");
  }
  if (v.size() != 3) throw InputError(fmt::format("{}: expected three numbers, got {}", what, v.size()));
  for (double x : v)
    if (!std::isfinite(x)) throw InputError(what + ": expected three finite numbers");
  return {v[0], v[1], v[2]};
}

JawPose jawPose(const py::object& o) {
  JawPose pose;
  if (o.is_none()) return pose;
  const Vec3 v = threeNumbers(o, "jaw (OPEN_DEG, FORWARD_CM, LATERAL_CM)");
  pose.openDeg = v.x();
  pose.forwardCm = v.y();
  pose.lateralCm = v.z();
  validateJawPose(pose, "jaw");
  return pose;
}

// The muscles an anatomical scene on this head would use: the library's (or the `use` selection of them).
std::vector<MuscleDef> libraryMuscles(const std::string& library, const std::vector<std::string>& use) {
  SceneDesc scene;
  scene.muscleLibrary = library;
  scene.muscles = use;
  const std::vector<MuscleDef>* builtin = builtinMuscleLibrary(library, FaceModelKind::Anatomical);
  std::vector<MuscleDef> muscles = sceneMuscles(scene, builtin ? *builtin : readMuscleDefs(library));
  readMuscleShells(muscles);
  return muscles;
}

std::shared_ptr<FaceHandle> buildFace(std::shared_ptr<const HeadHandle> head, const std::string& library,
                                      const std::vector<std::string>& use, const py::object& cacheDir, bool gravity) {
  auto handle = std::make_shared<FaceHandle>();
  if (!head) {
    auto builtIn = std::make_shared<HeadHandle>();
    builtIn->head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical));
    head = builtIn;
  }
  handle->head = head;
  handle->library = sceneMuscleLibrary(library);
  handle->muscles = use;
  if (!cacheDir.is_none()) handle->cache = std::make_shared<FileBasisCache>(cacheDir.cast<fs::path>());
  const std::vector<MuscleDef> muscles = libraryMuscles(library, use);
  py::gil_scoped_release unlocked;  // seconds without a cached basis
  // As buildSceneFace for a scene with only this head: default anatomical settings, no drags.
  handle->face = std::make_shared<const AnatomicalFace>(head->head, muscles, AnatomicalSettings{}, std::vector<DragDef>{},
                                                        gravity, handle->cache.get());
  return handle;
}

// A basis that could not be kept is no error (the next build computes it again), but say so once,
// as the command line does.
void warnIfNotKept(const FaceHandle& face) {
  const auto* files = dynamic_cast<const FileBasisCache*>(face.cache.get());
  if (files && !files->lastStoreError().empty())
    if (PyErr_WarnEx(PyExc_RuntimeWarning, ("the basis cache keeps nothing: " + files->lastStoreError()).c_str(), 1) != 0)
      throw py::error_already_set();  // warnings turned into errors
}

// `myoshell pose`: the static equilibrium under the activations, gravity (turned with the head pose)
// and the jaw; rest + u, or the jawed rest + u turned with the jaw.
py::array_t<double> pose(const FaceHandle& f, const py::object& activations, const py::object& gravityOn, const py::object& headPose,
           const py::object& jaw, const py::object& contactOn) {
  const AnatomicalFace& face = *f.face;
  const AnatomicalSkin& skin = face.skin();
  const Head& head = skin.head();
  const VecX act = activationVector(face, namedValues(activations));
  const Vec3 pyr = headPose.is_none() ? Vec3::Zero() : threeNumbers(headPose, "head_pose (PITCH, YAW, ROLL)");
  const JawPose jp = jawPose(jaw);
  if (!jp.isZero() && !face.jawRig())
    throw InputError("jaw: this head has no jaw: its landmarks have no 68-point jaw line (docs/jaw.md)",
                     head.landmarks.sourcePath);
  const bool gravity = gravityOn.is_none() ? face.gravityEnabled() : gravityOn.cast<bool>();
  SkinLoads loads;
  loads.activations = act;
  loads.drags.assign(static_cast<size_t>(skin.dragCount()), Vec3::Zero());
  // Upright it is exactly the rest gravity (no load); turned, gravityForPose; off, the rest gravity.
  loads.gravity = gravity && !pyr.isZero() ? gravityForPose(head.frame(), pyr, skin.settings().gravity) : skin.restGravity();
  loads.jaw = jp;
  // The contact penalty and projection, as pose and the playing face (contact=False: neither).
  loads.contact = contactOn.is_none() ? skin.settings().contact : contactOn.cast<bool>();
  MatX3 positions;
  {
    py::gil_scoped_release unlocked;
    const SettledSkin settled = skin.settle(loads, skin.settings().warping);
    if (!settled.converged || !settled.u.allFinite())
      throw NumericalError(fmt::format("pose: the static solve did not converge (residual {:.3g} after {} "
                                       "iterations)",
                                       settled.residual, settled.iterations));
    face.placement().place(settled.u, jp, loads.activations, positions, loads.contact);
  }
  return toNumpy(positions);
}

FitAlignment alignment(const std::string& text) {
  if (text == "none") return FitAlignment::None;
  if (text == "rigid") return FitAlignment::Rigid;
  if (text == "similarity") return FitAlignment::Similarity;
  throw InputError("align: '" + text + "' is not one of none, rigid, similarity");
}

// `myoshell fit` on a target given as positions (every vertex) or markers (a few vertices).
py::dict fit(const FaceHandle& f, const py::object& positions, const py::object& markers,
             const std::vector<std::string>& muscles, const std::string& align, double sparsity) {
  const AnatomicalSkin& skin = f.face->skin();
  const Head& head = skin.head();
  const int n = head.mesh.vertexCount();
  FitSettings settings;
  settings.alignment = alignment(align);
  settings.lambda = sparsity;
  settings.muscles = muscles;
  settings.validate();
  if (positions.is_none() == markers.is_none())
    throw InputError("fit: give either positions (an (n, 3) array) or markers (a dict vertex -> (x, y, z))");
  FitTarget target;
  if (!positions.is_none()) {
    target.displacement = toMatX3(positions, "positions", n) - head.mesh.V;
  } else {
    if (!py::isinstance<py::dict>(markers)) throw InputError("markers: expected a dict vertex index -> (x, y, z) in cm");
    const auto dict = py::reinterpret_borrow<py::dict>(markers);
    target.markerPositions.resize(static_cast<Eigen::Index>(dict.size()), 3);
    Eigen::Index row = 0;
    for (const auto& [vertex, xyz] : dict) {
      const int v = vertex.cast<int>();
      if (v < 0 || v >= n) throw InputError(fmt::format("markers: vertex {} is outside [0, {})", v, n));
      target.markerVertices.push_back(v);
      target.markerPositions.row(row++) = threeNumbers(py::reinterpret_borrow<py::object>(xyz), "markers").transpose();
    }
    if (target.markerVertices.empty()) throw InputError("markers: no marker given");
  }
  ActivationFit result;
  {
    py::gil_scoped_release unlocked;
    result = fitActivations(skin, target, settings);
  }
  py::dict acts;
  for (size_t m = 0; m < skin.muscles().size(); ++m)
    acts[py::str(skin.muscles()[m].muscle.def.name)] = result.activations(static_cast<Eigen::Index>(m));
  py::dict out;
  out["activations"] = acts;
  out["positions"] = toNumpy(MatX3(head.mesh.V + result.displacement));
  out["compared_vertices"] = result.metric.comparedVertices;
  out["cosine"] = result.metric.cosine;
  out["magnitude_ratio"] = result.metric.magnitudeRatio;
  out["rms_mm"] = result.rmsMm;
  out["max_mm"] = result.maxMm;
  out["condition_number"] = result.conditionNumber;
  out["iterations"] = result.iterations;
  out["seconds"] = result.seconds;
  return out;
}

// Positions in cm to the unit asked: 'cm', 'm', 'mm', or 'head' (the unit the head's OBJ is in).
double perCentimetre(const std::string& units, const HeadHandle& head) {
  if (units == "head") return 1.0 / centimetresPer(head.unit);
  if (units != "cm" && units != "m" && units != "mm")
    throw InputError("units: '" + units + "' is not one of cm, m, mm, head");
  return 1.0 / centimetresPer(parseLengthUnit(units));
}

// One muscle's rest shell for an overlay: its name, side, kind, vertices and triangles, and the
// centres of its origin and insertion rings, in `scale` × cm (the head's frame).
py::dict muscleDict(const Muscle& mu, double scale) {
  py::dict d;
  d["name"] = mu.def.name;
  d["side"] = mu.def.side;
  d["kind"] = toString(mu.def.kind);
  d["vertices"] = toNumpy(MatX3(mu.mesh.V * scale));
  d["triangles"] = toNumpy(mu.mesh.F);
  d["origin"] = std::vector<double>{scale * mu.originPoint.x(), scale * mu.originPoint.y(), scale * mu.originPoint.z()};
  d["insertion"] = std::vector<double>{scale * mu.insertionPoint.x(), scale * mu.insertionPoint.y(),
                                       scale * mu.insertionPoint.z()};
  d["rest_length"] = scale * mu.restLength;
  return d;
}

// The library's muscles placed on a head as the anatomical face places them (AnatomicalSkin:
// coupleMuscle → buildMuscle, the right side mirrored, one closest-point locator over the skin), without
// building the face (no basis): the same shells Face.muscle_meshes() gives.
py::list placeMuscles(std::shared_ptr<const HeadHandle> head, const std::string& library,
                      const std::vector<std::string>& use, const std::string& units) {
  if (!head) {
    auto builtIn = std::make_shared<HeadHandle>();
    builtIn->head = loadDefaultHead(defaultHeadOptions(FaceModelKind::Anatomical));
    head = builtIn;
  }
  const double scale = perCentimetre(units, *head);
  const std::vector<MuscleDef> defs = libraryMuscles(library, use);
  std::vector<Muscle> placed;
  {
    py::gil_scoped_release unlocked;
    const MatX3& V = head->head.mesh.V;
    const MatX3i& F = head->head.mesh.F;
    const SurfaceLocator skin(V, F, vertexNormals(V, F));
    for (const MuscleDef& def : defs) placed.push_back(buildMuscle(def, head->head, TubeOrientation::MirrorRightSide, &skin));
  }
  py::list out;
  for (const Muscle& mu : placed) out.append(muscleDict(mu, scale));
  return out;
}

}  // namespace

void bindFace(py::module_& m) {
  m.def("muscle_meshes",
        [](const std::shared_ptr<HeadHandle>& head, const std::string& library,
           const std::optional<std::vector<std::string>>& muscles, const std::string& units) {
          return placeMuscles(head, library, muscles.value_or(std::vector<std::string>{}), units);
        },
        py::arg("head") = py::none(), py::kw_only(), py::arg("library") = defaultMuscleLibrary(),
        py::arg("muscles") = py::none(), py::arg("units") = "cm", R"doc(
The muscles of a library placed on a head (a Head from load_head(); default the built-in head), as
the anatomical face places them, without building the face (no basis: a fraction of a second):
the same shells Face(head, library).muscle_meshes() gives. library, muscles: as Face().
units: 'cm' (default, as every array of the module), 'm', 'mm', or 'head' (the head's OBJ's unit).
Returns a list, in the model's order, of dicts: name, side, kind ('linear' or 'ring'), vertices
(float64 (k, 3): the muscle's closed shell at rest, in the head's frame: +y up, +z out of the face),
triangles (int32 (t, 3)), origin and insertion (the centres of its end rings), rest_length.
InputError for an unknown library or muscle, or a head whose landmarks do not fit the library.)doc");

  py::class_<FaceHandle, std::shared_ptr<FaceHandle>>(m, "Face", R"doc(
The anatomical face (docs/anatomical_model.md) on a head: the skin held by the skull, the muscles of
a library, gravity; the face `myoshell pose` and `myoshell fit` build.)doc")
      .def(py::init([](const std::shared_ptr<HeadHandle>& head, const std::string& library,
                       const std::optional<std::vector<std::string>>& muscles, const py::object& cache, bool gravity) {
             auto face = buildFace(head, library, muscles.value_or(std::vector<std::string>{}), cache, gravity);
             warnIfNotKept(*face);
             return face;
           }),
           py::arg("head") = py::none(), py::arg("library") = defaultMuscleLibrary(), py::arg("muscles") = py::none(),
           py::arg("cache") = py::none(), py::arg("gravity") = true, R"doc(
Builds the face on `head` (a Head from load_head(); default the built-in head).
library: 'face' (the whole face's 40, the default), 'builtin' (the built-in ten: the thesis's eight
and the lips' two rings) or a library file.
muscles: a list of the library's names to use (default all).
cache: a basis cache folder (made if missing; the command line's is ~/.cache/myoshell): a build
  whose basis it holds skips the basis computation (on the built-in head 0.2 s instead of 3 s).
  None: computed, not kept.
gravity: False builds the face without any gravity load.)doc")
      .def_property_readonly("head", [](const FaceHandle& f) { return std::const_pointer_cast<HeadHandle>(f.head); })
      .def_property_readonly("muscle_names", [](const FaceHandle& f) {
            std::vector<std::string> names;
            for (int i = 0; i < f.face->muscleCount(); ++i) names.push_back(f.face->muscleName(i));
            return names;
          }, "The muscles in the model's order (list of str)")
      .def_property_readonly("vertex_count", [](const FaceHandle& f) { return f.face->head().mesh.vertexCount(); })
      .def_property_readonly("dt", [](const FaceHandle& f) { return f.face->dt(); }, "The time step, s")
      .def_property_readonly("has_jaw", [](const FaceHandle& f) { return f.face->jawRig() != nullptr; })
      .def_property_readonly("has_lids", [](const FaceHandle& f) { return f.face->lidRig() != nullptr; },
                             "Whether the head's eyes are open, so the lid muscles turn the lids (docs/eyelids.md)")
      .def_property_readonly("basis_from_cache", [](const FaceHandle& f) { return f.face->skin().basisFromCache(); },
                             "Whether the skin's basis came from the cache folder")
      .def_property_readonly("build_seconds", [](const FaceHandle& f) { return f.face->buildSeconds(); })
      .def("rest_positions", [](const FaceHandle& f) { return toNumpy(f.face->head().mesh.V); },
           "The rest positions: float64 array (n, 3), cm.")
      .def("muscle_meshes", [](const FaceHandle& f, const std::string& units) {
            const double scale = perCentimetre(units, *f.head);
            py::list out;
            for (const CoupledMuscle& m : f.face->skin().muscles()) out.append(muscleDict(m.muscle, scale));
            return out;
          }, py::kw_only(), py::arg("units") = "cm", R"doc(
The face's muscles at rest, as the simulator placed them on its head (the viewer draws these
shells): a list in muscle_names' order of dicts name, side, kind, vertices (float64 (k, 3)),
triangles (int32 (t, 3)), origin, insertion, rest_length; units 'cm' (default), 'm', 'mm' or 'head'
(the head's OBJ's unit). As myoshell.muscle_meshes(head, library).)doc")
      .def("triangles", [](const FaceHandle& f) { return toNumpy(f.face->head().mesh.F); },
           "The triangles: int32 array (m, 3) of vertex indices.")
      .def("pose", &pose, py::arg("activations") = py::none(), py::arg("gravity") = py::none(),
           py::arg("head_pose") = py::none(), py::arg("jaw") = py::none(), py::arg("contact") = py::none(), R"doc(
The settled shape (static equilibrium) under fixed activations, as `myoshell pose`:
activations: dict muscle name -> activation in [0, 1] (others 0).
gravity: True/False (default: as the face was built).
head_pose: (pitch, yaw, roll) in degrees about the face frame's x, y, z (face-down: (90, 0, 0)).
jaw: (open_deg, forward_cm, lateral_cm): opening [0, 40] degrees, protrusion [-0.5, 1.5] cm,
  lateral shift [-1.5, 1.5] cm (+ the subject's left).
contact: True/False (default: as the face was built, on): the lids and lips kept out of the eyeballs,
  teeth and each other by penalty forces and projection; False gives the shape without contact
  (exactly linear in the activations), as `myoshell pose --contact off`.
Returns the positions: float64 array (n, 3), cm. InputError for an unknown muscle or a value out of
range (the command line's messages); SimulationError when the warped solve does not converge.)doc")
      .def("fit", &fit, py::arg("positions") = py::none(), py::kw_only(), py::arg("markers") = py::none(),
           py::arg("muscles") = std::vector<std::string>{}, py::arg("align") = "none", py::arg("sparsity") = 0.02,
           R"doc(
The activations in [0, 1] whose settled shape best matches a target, as `myoshell fit`
(docs/fitting.md). The target is either
  positions: float array (n, 3), cm, in the head's space (an expression of this head), or
  markers: dict vertex index -> (x, y, z) in cm: where a few vertices should be.
muscles: fit only these (default all); align: 'none', 'rigid' or 'similarity' (remove the target's
motion first); sparsity: the weight λ >= 0 of the command line's --lambda (default 0.02).
Returns a dict: activations (name -> value), positions (the fitted shape, float64 (n, 3), cm),
cosine, magnitude_ratio, rms_mm, max_mm, compared_vertices, condition_number, iterations, seconds.)doc")
      .def("write_obj", [](const FaceHandle& f, const fs::path& path, const py::object& positions) {
            writeHeadObj(*f.head, path.string(), toMatX3(positions, "positions", f.face->head().mesh.vertexCount()));
          }, py::arg("path"), py::arg("positions"),
           "Writes positions (float array (n, 3), cm) as an OBJ of the head (Head.write_obj).")
      .def("__repr__", [](const FaceHandle& f) {
        return fmt::format("<myoshell.Face on '{}': {} vertices, {} muscles>", f.face->head().name,
                           f.face->head().mesh.vertexCount(), f.face->muscleCount());
      });
}

}  // namespace myo::python
