// A scene file played by the one frame loop (ScenePlayer), as `myoshell run` plays it.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "bindings.h"
#include "myoshell/anim/scene_player.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/scene_face.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

// Face time played between checks for Ctrl-C (the GIL is taken back for each check).
constexpr int kStepsPerSignalCheck = 256;

std::shared_ptr<PlayerHandle> openScene(const fs::path& path, const py::object& cacheDir) {
  auto handle = std::make_shared<PlayerHandle>();
  if (!cacheDir.is_none()) handle->cache = std::make_shared<FileBasisCache>(cacheDir.cast<fs::path>());
  py::gil_scoped_release unlocked;
  const SceneDesc scene = readScene(path.string());
  const std::shared_ptr<const FaceSystem> face = buildSceneFace(scene, handle->cache.get());
  handle->player = std::make_unique<ScenePlayer>(scene, face);
  return handle;
}

// ScenePlayer::playTo(t) in pieces, so that Ctrl-C is seen: each piece ends at most
// kStepsPerSignalCheck steps further; the steps taken are those of one call.
void playTo(PlayerHandle& h, double t) {
  ScenePlayer& p = *h.player;
  const double piece = kStepsPerSignalCheck * p.model().dt();
  py::gil_scoped_release unlocked;
  while (true) {
    const double target = std::min(t, p.time() + piece);
    p.playTo(target);
    if (target >= t) return;
    py::gil_scoped_acquire locked;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

}  // namespace

void bindScenePlayer(py::module_& m) {
  py::class_<PlayerHandle, std::shared_ptr<PlayerHandle>>(m, "ScenePlayer", R"doc(
A scene file (docs/scene_format.md) played frame by frame by the frame loop `myoshell run` uses:
before every step the timeline (activations, gravity, head pose, drags, jaw) is applied at the clock's
time. Frame k is at time k / fps.)doc")
      .def(py::init(&openScene), py::arg("scene"), py::arg("cache") = py::none(), R"doc(
Reads the scene file and builds its face (anatomical or thesis). cache: a basis cache folder, or None.
Paths in the scene are relative to its folder. InputError for a bad scene.)doc")
      .def_property_readonly("name", [](const PlayerHandle& h) { return h.player->scene().name; })
      .def_property_readonly("fps", [](const PlayerHandle& h) { return h.player->scene().fps; })
      .def_property_readonly("duration", [](const PlayerHandle& h) { return h.player->scene().duration; }, "s")
      .def_property_readonly("frame_count", [](const PlayerHandle& h) { return h.player->frameCount(); })
      .def_property_readonly("time", [](const PlayerHandle& h) { return h.player->time(); }, "The clock, s")
      .def_property_readonly("dt", [](const PlayerHandle& h) { return h.player->model().dt(); }, "The step, s")
      .def_property_readonly("muscle_names", [](const PlayerHandle& h) {
            std::vector<std::string> names;
            for (int i = 0; i < h.player->model().muscleCount(); ++i) names.push_back(h.player->model().muscleName(i));
            return names;
          })
      .def("activations", [](const PlayerHandle& h) {
            std::map<std::string, double> out;
            const FaceStepper& sim = h.player->simulator();
            for (int i = 0; i < h.player->model().muscleCount(); ++i) out[h.player->model().muscleName(i)] = sim.activation(i);
            return out;
          }, "Every muscle's activation target as last set (by the timeline before the last step, or a LiveFace): "
             "dict name -> value.")
      .def("frame_time", [](const PlayerHandle& h, int k) { return h.player->frameTime(k); }, py::arg("k"),
           "Frame k's time, s")
      .def("advance_to", [](PlayerHandle& h, int k) { playTo(h, h.player->frameTime(k)); }, py::arg("k"),
           "Steps until the clock reaches frame k's time (the GIL is released).")
      .def("play_to", &playTo, py::arg("t"), "Steps until the clock reaches t seconds (the GIL is released).")
      .def("restart", [](PlayerHandle& h, double t0) { h.player->restart(t0); }, py::arg("t0") = 0.0,
           "Back to the neutral face at rest with the clock at t0 s.")
      .def("positions", [](PlayerHandle& h) { return toNumpy(h.player->snapshot(false).positions); },
           "The skin's positions now: float64 array (n, 3), cm (a copy).")
      .def("displacement", [](PlayerHandle& h) { return toNumpy(h.player->snapshot(false).displacement); },
           "The skin's displacement now: float64 array (n, 3), cm (a copy).")
      .def("rest_positions", [](const PlayerHandle& h) { return toNumpy(h.player->model().head().mesh.V); },
           "The rest positions: float64 array (n, 3), cm.")
      .def("triangles", [](const PlayerHandle& h) { return toNumpy(h.player->model().head().mesh.F); },
           "The triangles: int32 array (m, 3).");
}

}  // namespace myo::python
