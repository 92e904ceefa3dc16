// Automatic landmarks (head/auto_landmarks.h, findLandmarks) on one core:
//
//   landmarks/0   ICT's head, 11,248 vertices
//   landmarks/1   the same after one level of Loop subdivision, 44,806 vertices (the goal:
//                 ≤ 5 s for a 50,000-vertex head)
//
// Skipped without MYOSHELL_DATA's ict/. docs/heads.md ("Automatic landmarks") has the figures.
//
//   MYOSHELL_DATA=../shared/data build/bin/bench_landmarks --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <optional>

#include "myoshell/head/auto_landmarks.h"
#include "myoshell/io/head_files.h"
#include "myoshell/mesh/subdivision.h"

namespace {

using namespace myo;
namespace fs = std::filesystem;

const TriMesh* mesh(int which) {
  static std::optional<TriMesh> meshes[2];
  if (!meshes[which]) {
    const char* data = std::getenv("MYOSHELL_DATA");
    const fs::path dir = fs::path(data ? data : "../shared/data") / "ict";
    if (!fs::exists(dir / "head_skin.obj")) return nullptr;
    const Head ict = loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string());
    meshes[which] = which == 0 ? ict.mesh : loopSubdivide(ict.mesh, 1);
  }
  return &*meshes[which];
}

void landmarks(benchmark::State& state) {
  const TriMesh* m = mesh(static_cast<int>(state.range(0)));
  if (!m) {
    state.SkipWithError("no ICT head (set MYOSHELL_DATA)");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(findLandmarks(*m));
  state.counters["vertices"] = m->vertexCount();
}
BENCHMARK(landmarks)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
