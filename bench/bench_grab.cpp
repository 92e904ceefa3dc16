// The grab latency of the anatomical model (AnatomicalSimulator::setDragVertex →
// AnatomicalStepper::grab): a drag's grip moved to a new vertex at run time, as the viewer's mouse
// does, on the whole face (all muscles, released across, contact on) of ICT and of the built-in
// head, each built with the viewer's mouse drag (nose tip, 1 cm) and started warm from a basis cache.
//
//   grab/H       a simulator that has grabbed once already grabs the next of 11 landmarks over the face
//                (none is the grip it has): the three solves with the skin's kept
//                factorisation, the release, the new basis, the integrator, load patterns and contact
//                penalty on it. The counters split it (ms per grab).
//   firstGrab/H  the first grab on a face started warm: the above plus making the skin's
//                factorisation of K̂ and reading its held basis (once per face, shared by its
//                simulators). One grab per repetition (each on a new face from the cache, untimed).
//
// H: 0 the built-in head, 1 ICT (skipped without MYOSHELL_DATA's ict/). docs/PERFORMANCE.md
// ("Grabbing a drag at run time") has the figures.
//
//   MYOSHELL_DATA=../shared/data build/bin/bench_grab --benchmark_repetitions=5 \
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/muscles/muscle_def.h"

namespace {

using namespace myo;
namespace fs = std::filesystem;

const Head* head(int which) {
  static std::optional<Head> heads[2];
  static bool tried[2] = {false, false};
  if (!tried[which]) {
    tried[which] = true;
    if (which == 0) {
      heads[0] = loadDefaultHead();
    } else {
      const char* data = std::getenv("MYOSHELL_DATA");
      const fs::path dir = fs::path(data ? data : "../shared/data") / "ict";
      if (fs::exists(dir / "head_skin.obj"))
        heads[1] = loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string());
    }
  }
  return heads[which] ? &*heads[which] : nullptr;
}

// The face as the viewer builds it for the whole face: every muscle, the mouse drag at the nose tip.
std::shared_ptr<const AnatomicalFace> warmFace(const Head& h) {
  FileBasisCache cache(fs::temp_directory_path() / "myoshell_bench_grab_cache");
  const int nose = h.landmarks.vertex("nose_tip");
  return std::make_shared<const AnatomicalFace>(h, faceMuscleDefs(), AnatomicalSettings{},
                                                std::vector<DragDef>{{"mouse", nose, 1.0, {}}}, true, &cache);
}

// Spots over the face, at landmarks both heads name (none is the nose tip, the drag's own).
std::vector<int> spots(const Head& h) {
  std::vector<int> v;
  for (const char* name : {"mouth_corner_left", "left_brow_inner", "chin_menton", "mouth_corner_right", "left_eye_outer",
                           "upper_lip_top", "right_brow_inner", "lower_lip_bottom", "right_eye_inner", "nasion_approx",
                           "left_eye_inner"})
    v.push_back(h.landmarks.vertex(name));
  return v;
}

void grab(benchmark::State& state) {
  const Head* h = head(static_cast<int>(state.range(0)));
  if (!h) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  static std::shared_ptr<const AnatomicalFace> faces[2];
  auto& face = faces[state.range(0)];
  if (!face) face = warmFace(*h);
  AnatomicalSimulator sim(face);
  const std::vector<int> at = spots(*h);
  sim.setDragVertex(0, at.back());  // the skin's factorisation made (firstGrab times that)
  size_t next = 0;
  double responses = 0.0, solves = 0.0, basis = 0.0, finish = 0.0;
  for (auto _ : state) {
    sim.setDragVertex(0, at[next++ % at.size()]);
    const AnatomicalStepper::GrabTimes& t = sim.stepper().lastGrabTimes();
    responses += t.responses, solves += t.solves, basis += t.basis, finish += t.finish;
  }
  const double k = 1e3 / static_cast<double>(state.iterations());
  state.counters["responses_ms"] = responses * k;
  state.counters["solves_ms"] = solves * k;
  state.counters["basis_ms"] = basis * k;
  state.counters["finish_ms"] = finish * k;
  state.counters["modes"] = static_cast<double>(sim.stepper().integrator().basis().modeCount());
  state.counters["vertices"] = h->mesh.vertexCount();
}

void firstGrab(benchmark::State& state) {
  const Head* h = head(static_cast<int>(state.range(0)));
  if (!h) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  const int corner = h->landmarks.vertex("mouth_corner_left");
  double factorisation = 0.0;
  for (auto _ : state) {
    const auto face = warmFace(*h);
    AnatomicalSimulator sim(face);
    sim.setDragVertex(0, corner);
    state.SetIterationTime(sim.lastGrabSeconds());
    factorisation += sim.stepper().lastGrabTimes().factorisation;
  }
  state.counters["factorisation_ms"] = 1e3 * factorisation / static_cast<double>(state.iterations());
}

}  // namespace

BENCHMARK(grab)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(11);
BENCHMARK(firstGrab)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1);
BENCHMARK_MAIN();
