// Discrete-shell energy (thesis eq. 1–4): energy + gradient, Hessian assembly (exact and
// projected) and the rest stiffness K, on icospheres of 2562, 10242 and 40962 vertices.
//   build/bin/bench_shell --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/shell/discrete_shell.h"

namespace {

using namespace myo;

struct Case {
  std::unique_ptr<DiscreteShell> shell;
  MatX3 x;  // a deformed state: the rest sphere with 2% random noise
};

// Built once per subdivision level and shared by all benchmarks.
const Case& sphereCase(int subdivisions) {
  static std::map<int, Case> cache;
  auto it = cache.find(subdivisions);
  if (it != cache.end()) return it->second;
  const TriMesh s = icosphere(10.0, subdivisions);  // radius 10 cm
  Case c;
  c.shell = std::make_unique<DiscreteShell>(s.V, s.F, buildEdgeTable(s.F, s.vertexCount()), ShellMaterial{});
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  c.x = s.V;
  for (Eigen::Index i = 0; i < c.x.size(); ++i) c.x.data()[i] += u(rng);
  return cache.emplace(subdivisions, std::move(c)).first->second;
}

void setCounters(benchmark::State& state, const Case& c) {
  state.counters["vertices"] = c.shell->vertexCount();
}

void BM_Energy(benchmark::State& state) {
  const Case& c = sphereCase(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(c.shell->energy(c.x).total);
  setCounters(state, c);
}

void BM_EnergyGradient(benchmark::State& state) {
  const Case& c = sphereCase(static_cast<int>(state.range(0)));
  VecX g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.shell->energy(c.x, &g).total);
    benchmark::ClobberMemory();
  }
  setCounters(state, c);
}

void BM_HessianExact(benchmark::State& state) {
  const Case& c = sphereCase(static_cast<int>(state.range(0)));
  VecX g;
  SparseMat H;
  for (auto _ : state) {
    c.shell->energy(c.x, &g, &H);
    benchmark::DoNotOptimize(H.valuePtr());
  }
  setCounters(state, c);
}

void BM_HessianProjected(benchmark::State& state) {
  const Case& c = sphereCase(static_cast<int>(state.range(0)));
  VecX g;
  SparseMat H;
  for (auto _ : state) {
    c.shell->energy(c.x, &g, &H, HessianMode::Projected);
    benchmark::DoNotOptimize(H.valuePtr());
  }
  setCounters(state, c);
}

void BM_StiffnessAtRest(benchmark::State& state) {
  const Case& c = sphereCase(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    SparseMat K = c.shell->stiffnessAtRest();
    benchmark::DoNotOptimize(K.valuePtr());
  }
  setCounters(state, c);
}

// Subdivision levels 4, 5, 6: 2562, 10242, 40962 vertices.
BENCHMARK(BM_Energy)->DenseRange(4, 6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EnergyGradient)->DenseRange(4, 6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HessianExact)->DenseRange(4, 6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HessianProjected)->DenseRange(4, 6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StiffnessAtRest)->DenseRange(4, 6)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
