// A tracker's live stream (docs/live.md) in Python: the socket that keeps the newest frame
// (io/live_source.h's LiveSource), the frames it gives (LiveSample), the sending end (LiveSender,
// as `myoshell send`), and LiveFace: the newest frame through LiveFaceInput (hold, ease to neutral,
// calibration) and LiveFaceMapper (io/live_take.h: drive's mapping, frame by frame) onto a
// Simulator's or a ScenePlayer's stepper, as `myoshell live` drives its face. One mapping path:
// nothing is mapped in Python.
#include <pybind11/stl.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "bindings.h"
#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"
#include "myoshell/head/eye_gaze.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/live_take.h"
#include "myoshell/io/scene_face.h"

namespace myo::python {
namespace {

namespace fs = std::filesystem;

// ---- frames ----

int arkitIndex(const std::string& name) {
  const auto& names = arkitNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw InputError("weights: '" + name + "' is not one of ARKit's 52 blendshape names (myoshell.arkit_names())");
  return static_cast<int>(it - names.begin());
}

double finiteNumber(const py::handle& o, const std::string& what) {
  double v = 0.0;
  try {
    v = o.cast<double>();
  } catch (const py::cast_error&) {
    throw InputError(what + ": expected a number");
  }
  if (!std::isfinite(v)) throw InputError(fmt::format("{}: expected a finite number, got {}", what, v));
  return v;
}

// Weights as a dict ARKit name -> value (the others 0) or a sequence of 52 in arkit_names()' order.
std::array<double, kArkitWeightCount> weightsOf(const py::handle& o) {
  std::array<double, kArkitWeightCount> w{};
  if (o.is_none()) return w;
  if (py::isinstance<py::dict>(o)) {
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(o)) {
      const std::string name = py::str(key).cast<std::string>();
      w[static_cast<size_t>(arkitIndex(name))] = finiteNumber(value, "weights['" + name + "']");
    }
    return w;
  }
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(py::module_::import("numpy").attr("ravel")(o).attr("tolist")());
  if (py::len(seq) != kArkitWeightCount)
    throw InputError(fmt::format("weights: expected a dict ARKit name -> value or {} values in arkit_names()' order, got {}",
                                 kArkitWeightCount, py::len(seq)));
  for (int k = 0; k < kArkitWeightCount; ++k) w[static_cast<size_t>(k)] = finiteNumber(seq[static_cast<size_t>(k)], "weights");
  return w;
}

std::optional<Vec3> headPoseOf(const py::handle& o) {
  if (o.is_none()) return std::nullopt;
  std::vector<double> v;
  try {
    v = o.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw InputError("head_pose: expected three numbers (pitch, yaw, roll) in degrees");
  }
  if (v.size() != 3 || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
    throw InputError("head_pose: expected three finite numbers (pitch, yaw, roll) in degrees");
  return Vec3(v[0], v[1], v[2]);
}

// The gaze as Simulator.set_gaze names it: dict left_pitch, left_yaw, right_pitch, right_yaw (degrees).
std::optional<EyeGaze> gazeOf(const py::handle& o) {
  if (o.is_none()) return std::nullopt;
  if (!py::isinstance<py::dict>(o))
    throw InputError("gaze: expected a dict with left_pitch, left_yaw, right_pitch, right_yaw (degrees)");
  EyeGaze g;
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(o)) {
    const std::string k = py::str(key).cast<std::string>();
    const double v = finiteNumber(value, "gaze['" + k + "']");
    if (k == "left_pitch") g.pitchDeg[1] = v;
    else if (k == "left_yaw") g.yawDeg[1] = v;
    else if (k == "right_pitch") g.pitchDeg[0] = v;
    else if (k == "right_yaw") g.yawDeg[0] = v;
    else throw InputError("gaze: '" + k + "' is not one of left_pitch, left_yaw, right_pitch, right_yaw");
  }
  return g;
}

py::object gazeDict(const std::optional<EyeGaze>& g) {
  if (!g) return py::none();
  py::dict d;
  d["left_pitch"] = g->pitchDeg[1];
  d["left_yaw"] = g->yawDeg[1];
  d["right_pitch"] = g->pitchDeg[0];
  d["right_yaw"] = g->yawDeg[0];
  return d;
}

py::object vec3Tuple(const std::optional<Vec3>& v) {
  if (!v) return py::none();
  return py::make_tuple((*v)[0], (*v)[1], (*v)[2]);
}

py::dict weightDict(const std::array<double, kArkitWeightCount>& w) {
  py::dict d;  // in arkit_names()' order (dicts keep it)
  const auto& names = arkitNames();
  for (int k = 0; k < kArkitWeightCount; ++k) d[py::str(names[static_cast<size_t>(k)])] = w[static_cast<size_t>(k)];
  return d;
}

// ---- the source ----

struct SourceHandle {
  std::unique_ptr<LiveSource> source;
};

LiveSource& live(SourceHandle& s) {
  if (!s.source) throw InputError("LiveSource: used after close()");  // unreachable: close keeps the object
  return *s.source;
}

std::unique_ptr<SourceHandle> makeSource(const std::string& input, const py::object& port, const std::string& listen,
                                         bool lockstep) {
  LiveSourceOptions options;
  options.protocol = liveProtocolFromString(input);
  options.address = listen;
  if (port.is_none()) {
    options.port = defaultLivePort(options.protocol);
  } else {
    const double p = finiteNumber(port, "port");
    if (p != std::floor(p) || p < 0 || p > 65535)
      throw InputError(fmt::format("port: expected a whole number in 0–65535 (0: any free one), got {}", p));
    options.port = static_cast<int>(p);
  }
  options.acknowledge = lockstep;
  auto handle = std::make_unique<SourceHandle>();
  handle->source = std::make_unique<LiveSource>(std::move(options));
  return handle;
}

void closeSource(SourceHandle& s) {
  py::gil_scoped_release unlocked;  // joins the receiver thread (at most one 20 ms poll)
  s.source->stop();
}

py::dict countersDict(const LiveCounters& c) {
  py::dict d;
  d["packets"] = c.packets;
  d["frames"] = c.frames;
  d["malformed"] = c.malformed;
  d["dropped"] = c.dropped;
  d["superseded"] = c.superseded;
  d["taken"] = c.taken;
  d["ignored"] = c.ignored;
  return d;
}

// ---- the sender ----

struct SenderHandle {
  LiveProtocol protocol;
  std::unique_ptr<LiveSender> sender;
  int port = 0;
  std::int32_t frame = 0;  // Live Link numbers its frames
};

// ---- driving a face ----

struct LiveFaceHandle {
  py::object target;     // the Simulator or ScenePlayer, kept alive
  FaceStepper* stepper = nullptr;
  std::unique_ptr<LiveFaceMapper> mapper;
  std::vector<int> muscleIndex;  // per mapper.muscles(): the face's index, -1 for none
  LiveFaceInput input;
  bool warned = false;
};

std::unique_ptr<LiveFaceHandle> makeLiveFace(const py::object& target, const py::object& map, const py::object& filter,
                                             double timeout, double calibrate, double ease, const py::object& minCutoff,
                                             const py::object& beta) {
  auto h = std::make_unique<LiveFaceHandle>();
  SceneDesc scene;  // what the mapping reads: the muscles (library, selection, extras) and the map
  const FaceSystem* face = nullptr;
  if (py::isinstance<SimulatorHandle>(target)) {
    auto& s = target.cast<SimulatorHandle&>();
    scene.muscleLibrary = s.face->library;
    scene.muscles = s.face->muscles;
    h->stepper = &s.sim;
    face = s.face->face.get();
  } else if (py::isinstance<PlayerHandle>(target)) {
    auto& p = target.cast<PlayerHandle&>();
    scene = p.player->scene();
    h->stepper = &p.player->simulator();
    face = &p.player->model();
  } else {
    throw InputError("LiveFace: give a Simulator or a ScenePlayer to drive");
  }
  h->target = target;
  if (!map.is_none()) scene.performance.map = fs::absolute(py::str(map).cast<std::string>()).string();
  OneEuroSettings oneEuro;
  if (py::isinstance<py::bool_>(filter)) {
    oneEuro.enabled = filter.cast<bool>();
  } else {
    const std::string f = py::str(filter).cast<std::string>();
    if (f != "on" && f != "off") throw InputError("filter: expected True/False or 'on'/'off' (got '" + f + "')");
    oneEuro.enabled = f == "on";
  }
  if (!minCutoff.is_none()) oneEuro.minCutoff = finiteNumber(minCutoff, "min_cutoff");
  if (!beta.is_none()) oneEuro.beta = finiteNumber(beta, "beta");
  LiveFaceSettings settings;
  settings.timeout = timeout;
  settings.calibrateSeconds = calibrate;
  settings.easeSeconds = ease;
  h->input = LiveFaceInput(settings);
  h->mapper = std::make_unique<LiveFaceMapper>(scene, oneEuro);
  for (const std::string& name : h->mapper->muscles()) {
    int index = -1;
    for (int m = 0; m < face->muscleCount(); ++m)
      if (face->muscleName(m) == name) index = m;
    h->muscleIndex.push_back(index);
  }
  return h;
}

// LiveFaceInput.at(now) mapped by LiveFaceMapper and applied to the stepper, as `myoshell live` does
// before each frame; what was applied, as a dict.
py::dict applyNow(LiveFaceHandle& h, double now) {
  if (!std::isfinite(now)) throw InputError(fmt::format("now: expected a finite time in s, got {}", now));
  const MappedPerformance mapped = h.mapper->map(now, h.input.at(now));
  if (!h.warned) {
    h.warned = true;
    for (const std::string& w : mapped.warnings)
      if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  }
  LiveFaceMapper::apply(mapped, h.muscleIndex, *h.stepper);
  py::dict activations;
  for (size_t m = 0; m < mapped.activations.size(); ++m)
    if (h.muscleIndex[m] >= 0) activations[py::str(mapped.muscles[m])] = mapped.activations[m][0];
  py::dict out;
  out["activations"] = activations;
  out["jaw"] = mapped.jaw.empty() ? py::none() : vec3Tuple(mapped.jaw[0]);
  out["head_pose"] = mapped.headPose.empty() ? py::none() : vec3Tuple(mapped.headPose[0]);
  out["gaze"] = mapped.gaze.empty() ? py::none() : gazeDict(mapped.gaze[0]);
  out["liveness"] = h.input.liveness(now);
  out["calibrating"] = h.input.calibrating(now);
  return out;
}

LiveSample sampleOf(const py::handle& frame, double now) {
  if (py::isinstance<LiveSample>(frame)) return frame.cast<LiveSample>();
  LiveSample s;  // a dict of weights (or 52 values) arriving now
  s.frame.weights = weightsOf(frame);
  s.arrival = now;
  return s;
}

}  // namespace

void bindLive(py::module_& m) {
  m.def("arkit_names", [] { return arkitNames(); },
        "ARKit's 52 blendshape names, in the order of LiveSample.weight_array (eyeBlinkLeft, …, tongueOut).");
  m.def("live_clock", [] { return steadyLiveClock()(); },
        "Now on the clock LiveSource stamps arrivals with (s, monotonic; its origin is arbitrary).");

  py::class_<LiveSample>(m, "LiveSample", R"doc(
One tracked frame as it arrived: ARKit's 52 weights, the head's rotation and the eyes' turn when the
packet carries them, its arrival time (s on live_clock()) and its number in order of arrival.)doc")
      .def(py::init([](const py::object& weights, const py::object& headPose, const py::object& gaze, double arrival) {
             LiveSample s;
             s.frame.weights = weightsOf(weights);
             s.frame.headPose = headPoseOf(headPose);
             s.frame.gaze = gazeOf(gaze);
             s.arrival = arrival;
             return s;
           }),
           py::arg("weights") = py::none(), py::arg("head_pose") = py::none(), py::arg("gaze") = py::none(),
           py::arg("arrival") = 0.0, R"doc(
A frame made in Python (to send with LiveSender, or to apply with LiveFace.apply): weights a dict
ARKit name -> value (the others 0) or 52 values in arkit_names()' order; head_pose (pitch, yaw,
roll) degrees or None; gaze a dict left_pitch, left_yaw, right_pitch, right_yaw (degrees) or None;
arrival s. InputError for an unknown name or a value that is not a finite number.)doc")
      .def_property_readonly("weights", [](const LiveSample& s) { return weightDict(s.frame.weights); },
                             "dict ARKit name -> weight, all 52 in arkit_names()' order (the packet's float32 values)")
      .def_property_readonly("weight_array", [](const LiveSample& s) {
            py::array_t<double> a(kArkitWeightCount);
            std::copy(s.frame.weights.begin(), s.frame.weights.end(), a.mutable_data());
            return a;
          }, "The weights as float64 (52,) in arkit_names()' order")
      .def_property_readonly("head_pose", [](const LiveSample& s) { return vec3Tuple(s.frame.headPose); },
                             "(pitch, yaw, roll) degrees about the face frame's x, y, z, or None when not sent")
      .def_property_readonly("gaze", [](const LiveSample& s) { return gazeDict(s.frame.gaze); },
                             "dict left_pitch, left_yaw, right_pitch, right_yaw (degrees), or None when not sent")
      .def_property_readonly("arrival", [](const LiveSample& s) { return s.arrival; }, "s on live_clock()")
      .def_property_readonly("sequence", [](const LiveSample& s) { return s.sequence; },
                             "1, 2, … in order of arrival of complete frames (0 for a frame made in Python)")
      .def("__repr__", [](const LiveSample& s) {
        return fmt::format("<myoshell.LiveSample #{} at {:.3f} s>", s.sequence, s.arrival);
      });

  py::class_<SourceHandle>(m, "LiveSource", R"doc(
Listens for a tracker's stream over UDP (docs/live.md): Live Link Face or VMC packets, decoded by a
receiver thread that keeps only the newest complete frame (no queue: a slow consumer skips to the
present; the frames it never saw count as superseded). As `myoshell live` listens. Use it as a
context manager, or call close().)doc")
      .def(py::init(&makeSource), py::arg("input"), py::arg("port") = py::none(), py::arg("listen") = "127.0.0.1",
           py::arg("lockstep") = false, R"doc(
input: 'livelink' or 'vmc'. port: the UDP port (None: the protocol's, 11111 for livelink, 39539 for
vmc; 0: any free one, see .port). listen: the address to listen on (127.0.0.1, or 0.0.0.0 for any
interface). lockstep: acknowledge each frame taken to its sender (`myoshell send --lockstep`, which
then waits for it: no frame is superseded). InputError for an unknown input, or a port in use
("port P on ADDRESS is in use ...").)doc")
      .def_property_readonly("port", [](SourceHandle& s) { return live(s).port(); },
                             "The bound port (the free one chosen when asked for 0)")
      .def_property_readonly("input", [](SourceHandle& s) { return std::string(toString(live(s).protocol())); })
      .def("take_newest", [](SourceHandle& s) -> py::object {
            std::optional<LiveSample> sample;
            {
              py::gil_scoped_release unlocked;
              sample = live(s).takeNewest();
            }
            if (!sample) return py::none();
            return py::cast(*sample);
          }, "The newest complete frame not yet taken (a LiveSample), or None when none came since the last take.")
      .def("wait_for_frame", [](SourceHandle& s, double timeout) {
            if (!(timeout >= 0)) throw InputError(fmt::format("timeout: expected a number of s ≥ 0, got {}", timeout));
            py::gil_scoped_release unlocked;
            return live(s).waitForFrame(timeout);
          }, py::arg("timeout"),
           "Waits until a frame is waiting to be taken, or timeout s (wall time) pass; True when one is. The GIL is "
           "released meanwhile.")
      .def("wait_for_packets", [](SourceHandle& s, long packets, double timeout) {
            if (!(timeout >= 0)) throw InputError(fmt::format("timeout: expected a number of s ≥ 0, got {}", timeout));
            py::gil_scoped_release unlocked;
            return live(s).waitForPackets(packets, timeout);
          }, py::arg("packets"), py::arg("timeout"),
           "Waits until `packets` datagrams in all have been received, or timeout s pass; True when reached.")
      .def("counters", [](SourceHandle& s) { return countersDict(live(s).counters()); }, R"doc(
dict: packets (datagrams received), frames (complete frames decoded), malformed (dropped, see
last_malformed), dropped (Live Link frames the sender numbered that never arrived), superseded
(replaced by a newer frame before being taken), taken, ignored (well-formed, nothing uses them).)doc")
      .def_property_readonly("last_malformed", [](SourceHandle& s) { return live(s).lastMalformed(); },
                             "Why the last malformed packet was dropped ('' when none was)")
      .def_property_readonly("unknown_names", [](SourceHandle& s) { return live(s).unknownNames(); },
                             "VMC blend names that mean nothing here (ignored)")
      .def("close", &closeSource, "Stops listening (the port is free again); counters and a frame waiting stay readable.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](SourceHandle& s, const py::args&) {
            closeSource(s);
            return false;
          })
      .def("__repr__", [](SourceHandle& s) {
        return fmt::format("<myoshell.LiveSource {} on port {}>", toString(live(s).protocol()), live(s).port());
      });

  py::class_<SenderHandle>(m, "LiveSender", R"doc(
The sending end, as `myoshell send`: LiveSamples as Live Link Face or VMC packets to HOST:PORT over
UDP (a stand-in for a phone or VSeeFace in tests and demos).)doc")
      .def(py::init([](const std::string& output, const std::string& host, const py::object& port) {
             auto h = std::make_unique<SenderHandle>();
             h->protocol = liveProtocolFromString(output);
             const double p = port.is_none() ? defaultLivePort(h->protocol) : finiteNumber(port, "port");
             if (p != std::floor(p) || p < 1 || p > 65535)
               throw InputError(fmt::format("port: expected a whole number in 1–65535, got {}", p));
             h->port = static_cast<int>(p);
             h->sender = std::make_unique<LiveSender>(host, h->port);
             return h;
           }),
           py::arg("output"), py::arg("host") = "127.0.0.1", py::arg("port") = py::none(),
           "output: 'livelink' or 'vmc'; host, port: where to (port None: the protocol's). InputError for a host "
           "that does not resolve.")
      .def("send", [](SenderHandle& h, const py::object& frame) {
            const LiveSample s = sampleOf(frame, 0.0);
            const std::vector<std::uint8_t> packet =
                h.protocol == LiveProtocol::Vmc ? encodeVmcPacket(s.frame)
                                                : encodeLiveLinkPacket(s.frame, {h.frame++, 0.0f, 60, 1});
            h.sender->send(packet);
          }, py::arg("frame"),
           "Sends one frame: a LiveSample, or weights (a dict ARKit name -> value, or 52 values). Live Link frames are "
           "numbered 0, 1, … at 60 fps; weights go as float32.")
      .def("wait_for_ack", [](SenderHandle& h, double timeout) {
            py::gil_scoped_release unlocked;
            return h.sender->waitForAcknowledgement(timeout);
          }, py::arg("timeout"), "Waits for a lockstep receiver's acknowledgement; False after timeout s.");

  py::class_<LiveFaceHandle>(m, "LiveFace", R"doc(
Drives a Simulator or a ScenePlayer from live frames as `myoshell live` drives its face: the last
frame received is held through dropped packets, eased to neutral after `timeout` s of silence, less
the performer's resting weights when calibrating; each input curve goes through drive's One-Euro
filter, then through drive's mapping (the retargeting map, the FACS fallback, the jaw and eyes'
rules; io/live_take.h's LiveFaceMapper) onto the face's muscles, jaw, gaze and head pose.)doc")
      .def(py::init(&makeLiveFace), py::arg("target"), py::kw_only(), py::arg("map") = py::none(),
           py::arg("filter") = true, py::arg("timeout") = 0.5, py::arg("calibrate") = 0.0, py::arg("ease") = 0.5,
           py::arg("min_cutoff") = py::none(), py::arg("beta") = py::none(), R"doc(
target: a Simulator (its Face's muscles) or a ScenePlayer (its scene's muscles and map; a muscle the
scene's timeline tracks is set again by the timeline before each step). map: a retargeting map file
(fit-rig --out; default the scene's, else the shipped one). filter: the One-Euro filter, True/False
(or 'on'/'off'), min_cutoff (Hz) and beta its settings. timeout: s of silence before the face eases
to neutral over `ease` s; calibrate: s of the first frames whose mean weights are the resting face
(neutral meanwhile). InputError for a map made for another muscle library, or bad settings.)doc")
      .def("apply", [](LiveFaceHandle& h, const py::object& frame, double now) {
            if (!frame.is_none()) h.input.receive(sampleOf(frame, now));
            return applyNow(h, now);
          }, py::arg("frame"), py::arg("now"), R"doc(
Receives `frame` (a LiveSample, weights as a dict ARKit name -> value or 52 values arriving at `now`,
or None: no new frame), then sets on the target what the face plays at `now` (s, on the frames'
clock, increasing). Returns what was set: dict activations (muscle name -> value), jaw
(open_deg, forward_cm, lateral_cm) or None, head_pose (pitch, yaw, roll) or None, gaze or None,
liveness (1 live … 0 eased to neutral), calibrating. The target is not stepped.)doc")
      .def("update", [](LiveFaceHandle& h, SourceHandle& source, const py::object& now) {
            std::optional<LiveSample> sample;
            {
              py::gil_scoped_release unlocked;
              sample = live(source).takeNewest();
            }
            if (sample) h.input.receive(*sample);
            py::dict out = applyNow(h, now.is_none() ? steadyLiveClock()() : finiteNumber(now, "now"));
            out["sample"] = sample ? py::cast(*sample) : py::none();
            return out;
          }, py::arg("source"), py::arg("now") = py::none(), R"doc(
Takes the source's newest frame (if any) and applies what the face plays at `now` (default
live_clock(), the source's clock), as apply(); the dict also holds `sample`, the LiveSample taken
or None.)doc")
      .def_property_readonly("muscles", [](const LiveFaceHandle& h) { return h.mapper->muscles(); },
                             "The muscles the mapping drives (the target's)");
}

}  // namespace myo::python
