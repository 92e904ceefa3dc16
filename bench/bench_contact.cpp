// What placing a shape costs with the lids and the contact projections (anatomy/eyelids.h,
// anatomy/mouth_contact.h) against placing it without them, on ICT's whole face: the rest + u copy
// alone (every shape pays it), + the jaw, + the lids turned and the eyeballs, + the teeth and the
// lips. The shape is a settled blink with the mouth's ring pressed and the jaw at 10°, so every
// projection has work. Placement runs at output, not in the step: this is the price per written
// frame. docs/PERFORMANCE.md ("Contact") has the figures. The penalty forces (anatomy/contact_penalty.h)
// run in the step: penaltyForce/0 (the reduced force at the pressed shape's q), penaltyForce/1
// (with the Gauss–Newton K_c the step's implicit solve needs), and one AnatomicalStepper step with
// the contact on against off, in that pressed state (docs/mouth_contact.md, "Penalty forces").
//
//   MYOSHELL_DATA=../shared/data build/bin/bench_contact --benchmark_repetitions=9 \
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/muscles/muscle_def.h"

namespace {

using namespace myo;
namespace fs = std::filesystem;

struct Scene {
  std::unique_ptr<AnatomicalFace> face;
  MatX3 u;
  VecX q;
  VecX activations;
  JawPose jaw;
};

const Scene* scene() {
  static std::unique_ptr<Scene> s;
  static bool tried = false;
  if (tried) return s.get();
  tried = true;
  const char* data = std::getenv("MYOSHELL_DATA");
  const fs::path dir = fs::path(data ? data : "../shared/data") / "ict";
  if (!fs::exists(dir / "head_skin.obj")) return nullptr;
  const Head head = loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string());
  FileBasisCache cache(fs::temp_directory_path() / "myoshell_bench_contact_cache");
  s = std::make_unique<Scene>();
  s->face = std::make_unique<AnatomicalFace>(head, faceMuscleDefs(), AnatomicalSettings{}, std::vector<DragDef>{}, false,
                                             &cache);
  const AnatomicalSkin& skin = s->face->skin();
  SkinLoads loads;
  loads.activations = VecX::Zero(s->face->muscleCount());
  for (const char* m : {"orbicularis_oculi_palpebral_left", "orbicularis_oculi_palpebral_right", "orbicularis_oris_upper",
                        "orbicularis_oris_lower"})
    loads.activations(skin.muscleIndex(m)) = 1.0;
  loads.gravity = skin.restGravity();
  const SettledSkin settled = skin.settle(loads, false);
  s->u = settled.u;
  s->q = settled.q;
  s->activations = loads.activations;
  s->jaw.openDeg = 10.0;
  return s.get();
}

void copyOnly(benchmark::State& state) {
  const Scene* s = scene();
  if (!s) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  MatX3 out;
  for (auto _ : state) {
    out = s->face->head().mesh.V + s->u;
    benchmark::DoNotOptimize(out.data());
  }
}

void withJaw(benchmark::State& state) {
  const Scene* s = scene();
  if (!s) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  MatX3 out;
  for (auto _ : state) {
    jawedPositions(*s->face->jawRig(), s->jaw, s->face->head().mesh.V, s->u, out);
    benchmark::DoNotOptimize(out.data());
  }
}

void withJawAndLids(benchmark::State& state) {
  const Scene* s = scene();
  if (!s) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  MatX3 out;
  const LidPose lids = s->face->lidPose(s->activations);
  for (auto _ : state) {
    jawedPositions(*s->face->jawRig(), s->jaw, s->face->head().mesh.V, s->u, out);
    benchmark::DoNotOptimize(applyLids(*s->face->lidRig(), lids, out));
  }
}

void placeSkin(benchmark::State& state) {  // jaw, lids and eyeballs, teeth and lips: what every user calls
  const Scene* s = scene();
  if (!s) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  MatX3 out;
  ContactReport r;
  for (auto _ : state) {
    r = s->face->placeSkin(s->u, s->jaw, s->activations, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["projected"] = r.projected;
  state.counters["before_mm"] = 10 * r.maxPenetrationBefore;
}

// The reduced penalty force at the pressed shape's q (Arg 0), or the force and its stiffness (Arg 1,
// what a step that touches evaluates).
void penaltyForce(benchmark::State& state) {
  const Scene* s = scene();
  if (!s) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  const bool withStiffness = state.range(0) != 0;
  const ContactPenalty& pen = *s->face->skin().contactPenalty();
  ContactPenalty::Workspace ws = pen.workspace();
  const LidPose lids = s->face->lidPose(s->activations);
  VecX f = VecX::Zero(s->q.size());
  MatX K = MatX::Zero(withStiffness ? s->q.size() : 0, withStiffness ? s->q.size() : 0);
  for (auto _ : state) {
    f.setZero();
    if (withStiffness) K.setZero();
    benchmark::DoNotOptimize(pen.evaluate(s->q, s->jaw, lids, ws, &f, withStiffness ? &K : nullptr));
  }
  state.counters["active_rows"] = static_cast<double>(ws.active.size());
  state.counters["candidates"] = static_cast<double>(pen.candidates().size());
}

// One step of the pressed, blinking face after 0.5 s of steps (the contact active), contact on or off.
void stepPressed(benchmark::State& state) {
  const Scene* s = scene();
  if (!s) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  const AnatomicalSkin& skin = s->face->skin();
  AnatomicalStepper stepper(s->face->skinPtr());
  SkinLoads loads;
  loads.activations = s->activations;
  loads.gravity = skin.restGravity();
  loads.jaw = s->jaw;
  loads.contact = state.range(0) != 0;
  for (int k = 0; k < 120; ++k) stepper.step(loads);
  for (auto _ : state) stepper.step(loads);
  state.counters["contact"] = static_cast<double>(state.range(0));
}

BENCHMARK(penaltyForce)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(stepPressed)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(copyOnly)->Unit(benchmark::kMicrosecond);
BENCHMARK(withJaw)->Unit(benchmark::kMicrosecond);
BENCHMARK(withJawAndLids)->Unit(benchmark::kMicrosecond);
BENCHMARK(placeSkin)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
