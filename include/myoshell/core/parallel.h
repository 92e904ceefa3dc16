// Work that is independent, spread over threads, with results that do not depend on how many.
//
// parallelFor(count, body) calls body(i) once for every i in [0, count), on up to
// parallelThreads() threads (the calling thread among them), and returns when all are done. The
// bodies must be independent: each writes only its own outputs (slot i of a vector sized before
// the call), so the results are the same bits for every thread count — the order in which the
// bodies run is the only thing that changes, never what each one computes. When bodies throw, the
// exception of the lowest failing index is rethrown on the calling thread once the running bodies
// have finished (later ones are not started): the one a serial loop would have thrown.
//
// The thread count is one process-wide setting, as Eigen::setNbThreads is: the CLI sets it from
// --threads, the viewer leaves it at 1 (its live step has the core), a library user sets it once.
// Threads are started per call, not pooled: every call site does at least milliseconds of work per
// body (a sparse solve, an eigen-solve, a fit), next to which starting a thread (~20 µs) is noise.
#pragma once

#include <cstdint>
#include <functional>

namespace myo {

// 1 by default. setParallelThreads(0) selects every hardware thread; negative is an InputError.
void setParallelThreads(int threads);
int parallelThreads();
// The number of hardware threads (std::thread::hardware_concurrency, at least 1).
int hardwareThreads();

void parallelFor(std::int64_t count, const std::function<void(std::int64_t)>& body);

}  // namespace myo
