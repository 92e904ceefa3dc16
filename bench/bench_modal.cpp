// Modal engine benchmarks: constrained modal analysis vs mesh size and d, the warped step vs
// size and d, and in the same run the floor of streaming the basis once (Φq and Ψq as matvecs).
//
//   build/bin/bench_modal --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Meshes: curved grids (a shallow bump, so membrane and bending couple) of about 1k, 5k, 11k and
// 40k vertices, pinned on their first two columns; the default ShellMaterial.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/primitives.h"
#include "myoshell/reduce/modal_analysis.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/shell/discrete_shell.h"

namespace {

using namespace myo;

// Grid dimensions (nx, ny) by target vertex count.
std::pair<int, int> gridFor(int vertices) {
  switch (vertices) {
    case 1000: return {40, 24};    // 1,025 vertices
    case 5000: return {100, 49};   // 5,050
    case 11000: return {150, 72};  // 11,023
    default: return {284, 140};    // 40,185
  }
}

struct Problem {
  TriMesh mesh;
  std::unique_ptr<DiscreteShell> shell;
  std::vector<int> pins;
};

const Problem& problem(int vertices) {
  static std::map<int, Problem> cache;
  auto it = cache.find(vertices);
  if (it != cache.end()) return it->second;
  const auto [nx, ny] = gridFor(vertices);
  Problem p;
  p.mesh = gridMesh(20.0, 20.0 * ny / nx, nx, ny);
  for (Eigen::Index i = 0; i < p.mesh.V.rows(); ++i) {
    const double x = p.mesh.V(i, 0) / 20.0, y = p.mesh.V(i, 1) / 10.0;
    p.mesh.V(i, 2) = 2.0 * std::sin(3.14159 * x) * std::sin(3.14159 * y);
  }
  p.shell = std::make_unique<DiscreteShell>(p.mesh.V, p.mesh.F, buildEdgeTable(p.mesh.F, p.mesh.vertexCount()),
                                            ShellMaterial{});
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < 2; ++i) p.pins.push_back(j * (nx + 1) + i);
  return cache.emplace(vertices, std::move(p)).first->second;
}

void BM_ModalAnalysis(benchmark::State& state) {
  const Problem& p = problem(static_cast<int>(state.range(0)));
  ModalSettings s;
  s.modeCount = static_cast<int>(state.range(1));
  double solve = 0.0;
  for (auto _ : state) {
    ModalBasis b = computeModalBasis(*p.shell, p.pins, s);
    solve = b.solveSeconds;
    benchmark::DoNotOptimize(b.lambda.data());
  }
  state.counters["vertices"] = p.mesh.vertexCount();
  state.counters["eigen_solve_s"] = solve;  // eigen-solve only (K assembly and Ψ excluded)
}
BENCHMARK(BM_ModalAnalysis)
    ->ArgsProduct({{1000, 5000, 11000}, {20, 40}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_ModalAnalysis)->Args({40000, 20})->Args({40000, 40})->Unit(benchmark::kMillisecond)->Iterations(1);

// A synthetic basis with the real problem's size (values random; the step's cost does not depend
// on them), scaled so that rotations are ~0.1 rad at |q| ~ 1.
std::shared_ptr<const ModalBasis> syntheticBasis(int vertices, int d) {
  static std::map<std::pair<int, int>, std::shared_ptr<const ModalBasis>> cache;
  auto key = std::make_pair(vertices, d);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const auto [nx, ny] = gridFor(vertices);
  const int n = (nx + 1) * (ny + 1);
  auto b = std::make_shared<ModalBasis>();
  b->fullVertexCount = n;
  for (int i = 0; i < n; ++i)
    if (i % (nx + 1) >= 2) b->freeVertices.push_back(i);
  const int f = b->freeCount();
  std::mt19937 rng(1);
  std::normal_distribution<double> N01;
  b->Phi.resize(3 * f, d);
  b->Psi.resize(3 * f, d);
  for (Eigen::Index i = 0; i < b->Phi.size(); ++i) b->Phi.data()[i] = 0.01 * N01(rng);
  for (Eigen::Index i = 0; i < b->Psi.size(); ++i) b->Psi.data()[i] = 0.02 * N01(rng);
  b->lambda = VecX::LinSpaced(d, 1.0, 1e4);
  b->freeMass = VecX::Ones(f);
  cache[key] = b;
  return b;
}

// Arguments: vertices, d, precision (0 float, 1 double), load (0 none, 1 local 5%, 2 everywhere).
void BM_WarpedStep(benchmark::State& state) {
  auto b = syntheticBasis(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  ModalWarpingSettings s;
  s.precision = state.range(2) == 0 ? ModalPrecision::Float : ModalPrecision::Double;
  s.rayleighMass = 0.5;
  ModalWarpingIntegrator integ(b, s);
  MatX3 F = MatX3::Zero(b->freeCount(), 3);
  const int load = static_cast<int>(state.range(3));
  for (int i = 0; i < b->freeCount(); ++i)
    if (load == 2 || (load == 1 && i % 20 == 0)) F.row(i) << 1.0, -2.0, 3.0;
  integ.setState(VecX::Ones(b->modeCount()), VecX::Zero(b->modeCount()));
  for (auto _ : state) {
    integ.step(F);
    benchmark::DoNotOptimize(integ.freeDisplacement().data());
  }
  state.counters["vertices"] = b->freeCount();
  state.counters["max_rotation"] = integ.freeRotations().rowwise().norm().maxCoeff();
}
BENCHMARK(BM_WarpedStep)
    ->ArgsProduct({{1000, 5000, 11000, 40000}, {20, 30, 40}, {0, 1}, {1}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WarpedStep)->ArgsProduct({{11000}, {30}, {0, 1}, {0, 2}})->Unit(benchmark::kMicrosecond);

// The floor: Φq and Ψq as two plain matvecs over column-major 3f×d matrices (what any modal
// warping step must at least read). Arguments: vertices, d, precision (0 float, 1 double).
template <class Scalar>
void floorImpl(benchmark::State& state) {
  auto b = syntheticBasis(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const Mat Phi = b->Phi.cast<Scalar>(), Psi = b->Psi.cast<Scalar>();
  const Vec q = Vec::Ones(b->modeCount());
  Vec u(Phi.rows()), w(Psi.rows());
  for (auto _ : state) {
    u.noalias() = Phi * q;
    w.noalias() = Psi * q;
    benchmark::DoNotOptimize(u.data());
    benchmark::DoNotOptimize(w.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = b->freeCount();
}
void BM_Floor(benchmark::State& state) {
  if (state.range(2) == 0)
    floorImpl<float>(state);
  else
    floorImpl<double>(state);
}
BENCHMARK(BM_Floor)->ArgsProduct({{1000, 5000, 11000, 40000}, {20, 30, 40}, {0, 1}})->Unit(benchmark::kMicrosecond);

// The same bytes read as one row-major matvec over the per-vertex interleaved [Φ_i; Ψ_i] (6f×d),
// the layout step() uses: the tightest "stream the basis once" floor.
template <class Scalar>
void floorInterleavedImpl(benchmark::State& state) {
  auto b = syntheticBasis(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const int f = b->freeCount(), d = b->modeCount();
  Mat B(6 * f, d);
  for (int i = 0; i < f; ++i) {
    B.middleRows(6 * i, 3) = b->Phi.middleRows(3 * i, 3).cast<Scalar>();
    B.middleRows(6 * i + 3, 3) = b->Psi.middleRows(3 * i, 3).cast<Scalar>();
  }
  const Vec q = Vec::Ones(d);
  Vec y(B.rows());
  for (auto _ : state) {
    y.noalias() = B * q;
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = f;
}
void BM_FloorInterleaved(benchmark::State& state) {
  if (state.range(2) == 0)
    floorInterleavedImpl<float>(state);
  else
    floorInterleavedImpl<double>(state);
}
BENCHMARK(BM_FloorInterleaved)
    ->ArgsProduct({{1000, 5000, 11000, 40000}, {20, 30, 40}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
