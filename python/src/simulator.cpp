// Stepping the anatomical face in time (AnatomicalSimulator): activations by name, gravity, head
// pose and jaw, step(n) without the GIL.
#include <pybind11/stl.h>

#include <fmt/core.h>

#include <algorithm>
#include <map>

#include "activations.h"
#include "bindings.h"
#include "myoshell/core/errors.h"
#include "myoshell/head/eye_gaze.h"
#include "myoshell/head/jaw.h"

namespace myo::python {
namespace {

// Steps between checks for Ctrl-C (the GIL is taken back for each check): about 1 s of face time.
constexpr int kStepsPerSignalCheck = 256;

void step(SimulatorHandle& s, int n) {
  if (n < 0) throw InputError(fmt::format("step: the number of steps must be ≥ 0, got {}", n));
  py::gil_scoped_release unlocked;
  for (int done = 0; done < n;) {
    const int chunk = std::min(kStepsPerSignalCheck, n - done);
    for (int i = 0; i < chunk; ++i) s.sim.step();
    done += chunk;
    if (done < n) {
      py::gil_scoped_acquire locked;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }
}

MatX3 positions(const SimulatorHandle& s) {
  MatX3 out;
  s.sim.skinPositions(out);
  return out;
}

}  // namespace

void bindSimulator(py::module_& m) {
  py::class_<SimulatorHandle, std::shared_ptr<SimulatorHandle>>(m, "Simulator", R"doc(
Steps a Face in time (the anatomical face's simulator, dt = face.dt s a step). Loads are kept between
steps: activations (0 at first), the gravity scale (1), the head pose (upright) and the jaw (closed).)doc")
      .def(py::init([](std::shared_ptr<FaceHandle> face) {
             if (!face) throw InputError("Simulator: give a Face");
             return std::make_shared<SimulatorHandle>(std::move(face));
           }),
           py::arg("face"))
      .def_property_readonly("face", [](const SimulatorHandle& s) { return s.face; })
      .def("set_activation", [](SimulatorHandle& s, const std::string& name, double value) {
            const int muscle = muscleIndexByName(*s.face->face, name);
            checkActivation(name, value);
            s.sim.setActivation(muscle, value);
          }, py::arg("name"), py::arg("value"),
           "Sets a muscle's activation target in [0, 1]. InputError for an unknown name or a value out of range.")
      .def("set_activations", [](SimulatorHandle& s, const std::map<std::string, double>& values) {
            NamedValues named(values.begin(), values.end());
            for (const auto& [name, value] : named) {
              muscleIndexByName(*s.face->face, name);
              checkActivation(name, value);
            }
            for (const auto& [name, value] : named) s.sim.setActivation(muscleIndexByName(*s.face->face, name), value);
          }, py::arg("activations"),
           "Sets several activations (dict name -> value in [0, 1]); the others keep theirs. All are checked first.")
      .def("activation", [](const SimulatorHandle& s, const std::string& name) {
            return s.sim.activation(muscleIndexByName(*s.face->face, name));
          }, py::arg("name"))
      .def("activations", [](const SimulatorHandle& s) {
            std::map<std::string, double> out;
            for (int i = 0; i < s.face->face->muscleCount(); ++i) out[s.face->face->muscleName(i)] = s.sim.activation(i);
            return out;
          }, "Every muscle's activation target: dict name -> value.")
      .def("set_gravity", [](SimulatorHandle& s, double scale) { s.sim.setGravity(scale); }, py::arg("scale"),
           "Gravity scale: 1 = 981 cm/s² (the rest pose's, no load upright), 0 = weightless.")
      .def("set_head_pose", [](SimulatorHandle& s, double pitch, double yaw, double roll) {
            s.sim.setHeadPose(headPoseRotation(Vec3(pitch, yaw, roll)));
          }, py::arg("pitch"), py::arg("yaw") = 0.0, py::arg("roll") = 0.0,
           "Turns the head (gravity turns with it): degrees about the face frame's x, y, z; face-down is pitch 90.")
      .def("set_jaw", [](SimulatorHandle& s, double openDeg, double forwardCm, double lateralCm) {
            JawPose pose;
            pose.openDeg = openDeg;
            pose.forwardCm = forwardCm;
            pose.lateralCm = lateralCm;
            validateJawPose(pose, "jaw");
            s.sim.setJaw(pose);
          }, py::arg("open_deg") = 0.0, py::arg("forward_cm") = 0.0, py::arg("lateral_cm") = 0.0,
           "The jaw: opening [0, 40] degrees, protrusion [-0.5, 1.5] cm, lateral shift [-1.5, 1.5] cm.")
      .def("set_gaze", [](SimulatorHandle& s, double leftPitch, double leftYaw, double rightPitch, double rightYaw) {
            EyeGaze gaze;
            gaze.pitchDeg = {rightPitch, leftPitch};
            gaze.yawDeg = {rightYaw, leftYaw};
            s.sim.setGaze(gaze);
          }, py::arg("left_pitch") = 0.0, py::arg("left_yaw") = 0.0, py::arg("right_pitch") = 0.0,
           py::arg("right_yaw") = 0.0,
           "The eyes' turn, degrees in [-45, 45]: pitch + up, yaw + towards the subject's left; the lids follow "
           "it (docs/eyelids.md).")
      .def("step", &step, py::arg("n") = 1,
           "Advances n steps of dt (the GIL is released; Ctrl-C stops between blocks of steps). SimulationError "
           "when the skin blows up.")
      .def_property("response",
          [](const SimulatorHandle& s) { return s.sim.response() == SkinResponse::Follow ? "follow" : "dynamic"; },
          [](SimulatorHandle& s, const std::string& r) {
            if (r != "dynamic" && r != "follow")
              throw InputError("response: expected dynamic or follow (got '" + r + "')");
            s.sim.setResponse(r == "follow" ? SkinResponse::Follow : SkinResponse::Dynamic);
          },
          "The skin's response, 'dynamic' (the face's scene setting, by default) or 'follow': the "
          "activations' quasi-static shape at once, only gravity, head turns, drags and contact lag "
          "(docs/live.md, \"Lag\"). A switch keeps the current shape.")
      .def("reset", [](SimulatorHandle& s) { s.sim.reset(); }, "Back to the neutral face at rest (loads kept).")
      .def_property_readonly("step_count", [](const SimulatorHandle& s) { return s.sim.stepCount(); })
      .def_property_readonly("time", [](const SimulatorHandle& s) {
            return static_cast<double>(s.sim.stepCount()) * s.face->face->dt();
          }, "Simulated time since the start or the last reset, s")
      .def("positions", [](const SimulatorHandle& s) { return toNumpy(positions(s)); },
           "The skin's current positions: float64 array (n, 3), cm (a copy).")
      .def("displacement", [](const SimulatorHandle& s) { return toNumpy(s.sim.skinDisplacement()); },
           "The skin's displacement from rest: float64 array (n, 3), cm (a copy; without the jaw's motion).")
      .def("rest_positions", [](const SimulatorHandle& s) { return toNumpy(s.face->face->head().mesh.V); },
           "The rest positions: float64 array (n, 3), cm.")
      .def("triangles", [](const SimulatorHandle& s) { return toNumpy(s.face->face->head().mesh.F); },
           "The triangles: int32 array (m, 3).");
}

}  // namespace myo::python
