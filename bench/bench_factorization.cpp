// Eigen's simplicial LDLᵀ against CHOLMOD's supernodal LLᵀ (SuiteSparse, through Eigen's
// CholmodSupport) on the stiffness the anatomical build factorises: the ICT head's K̂ (skin shell,
// attachment, held couplings; 11,248 vertices, 33,744 unknowns). Factorisation and one solve, each
// backend as Debian ships it (CHOLMOD on Debian's reference BLAS). docs/PERFORMANCE.md has the figures
// and the decision they led to.
//
//   MYOSHELL_DATA=../shared/data build/bin/bench_factorization --benchmark_repetitions=5 \
//     --benchmark_report_aggregates_only=true
//
// The first run builds the whole face once into a basis cache of its own (a minute) to get K̂.
#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
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

const SparseMat* stiffness() {
  static std::unique_ptr<SparseMat> K;
  static bool tried = false;
  if (tried) return K.get();
  tried = true;
  const char* data = std::getenv("MYOSHELL_DATA");
  const fs::path dir = fs::path(data ? data : "../shared/data") / "ict";
  if (!fs::exists(dir / "head_skin.obj")) return nullptr;
  const Head head = loadHead((dir / "head_skin.obj").string(), (dir / "landmarks_multipie68.json").string());
  FileBasisCache cache(fs::temp_directory_path() / "myoshell_bench_factorization_cache");
  const AnatomicalFace face(head, faceMuscleDefs(), AnatomicalSettings{}, {}, true, &cache);
  K = std::make_unique<SparseMat>(face.skin().stiffness());
  return K.get();
}

template <class Factor>
void factorize(benchmark::State& state) {
  const SparseMat* K = stiffness();
  if (!K) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  for (auto _ : state) {
    Factor f(*K);
    if (f.info() != Eigen::Success) return state.SkipWithError("factorisation failed");
    benchmark::ClobberMemory();
  }
  state.counters["unknowns"] = static_cast<double>(K->rows());
}

template <class Factor>
void solve(benchmark::State& state) {
  const SparseMat* K = stiffness();
  if (!K) return state.SkipWithError("no ICT head: set MYOSHELL_DATA to the folder holding ict/");
  const Factor f(*K);
  const VecX b = VecX::Ones(K->rows());
  VecX x;
  for (auto _ : state) {
    x = f.solve(b);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["residual"] = (*K * x - b).norm() / b.norm();
}

using EigenLdlt = Eigen::SimplicialLDLT<SparseMat>;
using CholmodSupernodal = Eigen::CholmodSupernodalLLT<SparseMat>;
BENCHMARK_TEMPLATE(factorize, EigenLdlt)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(factorize, CholmodSupernodal)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(solve, EigenLdlt)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(solve, CholmodSupernodal)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
