// The size sweep (issue 19): the built-in head at 1, 2 and 3 subdivision levels (1.8k, 7.2k and 28k
// vertices) and the ICT head Loop-subdivided 0, 1 and 2 times (11k, 45k and 180k vertices;
// subdivision keeps the original vertex ids first, so the landmarks stay valid), the whole face on each — every muscle of the built-in `face` library, gravity, the jaw open 10°, one
// drag at the nose tip — built cold (no cache) and stepped with every load on. Reported per size:
// the build's seconds (precompute), a step's µs, a step plus a positions read, and the basis size,
// against Σ vertices × basis columns (the data a read streams).
//
//   MYOSHELL_DATA=../shared/data build/bin/bench_size_sweep --benchmark_counters_tabular=true
//   (threads for the build: MYOSHELL_BUILD_THREADS=2; the step is single-threaded)
//
// Arguments: head (0 built-in, 1 ICT), levels. ICT at level 2 (180k vertices) takes tens of minutes
// and gigabytes to build: run only with MYOSHELL_SWEEP_LARGE=1. ICT rows skip with a message
// without the data.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/core/parallel.h"
#include "myoshell/core/timer.h"
#include "myoshell/head/head.h"
#include "myoshell/io/head_files.h"
#include "myoshell/mesh/subdivision.h"
#include "myoshell/muscles/muscle_def.h"

namespace {

using namespace myo;
namespace fs = std::filesystem;

std::string ictFolder() {
  const char* data = std::getenv("MYOSHELL_DATA");
  return (fs::path(data ? data : "../shared/data") / "ict").string();
}

struct Built {
  std::shared_ptr<const AnatomicalFace> face;
  double buildSeconds = 0.0;
  int vertices = 0;
  int basisColumns = 0;
};

const Built* build(int headKind, int levels) {
  static std::map<std::pair<int, int>, Built> built;
  if (auto it = built.find({headKind, levels}); it != built.end()) return &it->second;
  if (const char* t = std::getenv("MYOSHELL_BUILD_THREADS")) setParallelThreads(std::atoi(t));
  Head head;
  if (headKind == 0) {
    DefaultHeadOptions o;
    o.subdivisionLevels = levels;
    head = loadDefaultHead(o);
  } else {
    const std::string dir = ictFolder();
    if (!fs::exists(fs::path(dir) / "head_skin.obj")) return nullptr;
    head = loadHead((fs::path(dir) / "head_skin.obj").string(), (fs::path(dir) / "landmarks_multipie68.json").string());
    if (levels > 0) head.mesh = loopSubdivide(head.mesh, levels, LoopOptions{});
  }
  DragDef drag;
  drag.vertex = head.landmarks.vertex("nose_tip");
  Built b;
  Stopwatch clock;
  b.face = std::make_shared<const AnatomicalFace>(head, faceMuscleDefs(), AnatomicalSettings{}, std::vector<DragDef>{drag});
  b.buildSeconds = clock.seconds();
  b.vertices = head.mesh.vertexCount();
  b.basisColumns = b.face->skin().basis()->modeCount();
  return &built.emplace(std::make_pair(headKind, levels), std::move(b)).first->second;
}

std::unique_ptr<FaceStepper> loadedStepper(const Built& b) {
  auto stepper = b.face->makeStepper(b.face);
  for (int m = 0; m < b.face->muscleCount(); ++m) stepper->setActivation(m, 0.5);
  JawPose jaw;
  jaw.openDeg = 10.0;
  stepper->setJaw(jaw);
  stepper->setDragForce(0, Vec3(2e3, 0.0, 0.0));
  for (int k = 0; k < 200; ++k) stepper->step();  // past the start-up transient
  return stepper;
}

void counters(benchmark::State& state, const Built& b) {
  state.counters["vertices"] = b.vertices;
  state.counters["basis"] = b.basisColumns;
  state.counters["vertices_x_basis"] = static_cast<double>(b.vertices) * b.basisColumns;
  state.counters["build_s"] = b.buildSeconds;
}

void BM_WholeFaceStep(benchmark::State& state) {
  const Built* b = build(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!b) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  auto stepper = loadedStepper(*b);
  for (auto _ : state) stepper->step();
  counters(state, *b);
}

void BM_WholeFaceStepAndRead(benchmark::State& state) {
  const Built* b = build(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!b) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  auto stepper = loadedStepper(*b);
  MatX3 positions;
  for (auto _ : state) {
    stepper->step();
    stepper->skinPositions(positions);
    benchmark::DoNotOptimize(positions.data());
  }
  counters(state, *b);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int levels : {1, 2, 3}) b->Args({0, levels});
  for (int levels : {0, 1}) b->Args({1, levels});
  if (std::getenv("MYOSHELL_SWEEP_LARGE")) b->Args({1, 2});
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK(BM_WholeFaceStep)->Apply(sizes);
BENCHMARK(BM_WholeFaceStepAndRead)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
