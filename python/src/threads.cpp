// The library's one thread-count setting (core/parallel.h), as the command line's --threads sets it.
#include "bindings.h"
#include "myoshell/core/parallel.h"

namespace myo::python {

void bindThreads(py::module_& m) {
  m.def("set_threads", &setParallelThreads, py::arg("threads"), R"doc(
Threads for the precompute (a face's build: eigen-solves, static responses) and for independent work
(fit_rig's shapes), as the command line's --threads: 0 = every hardware thread; 1 (the module's
default) = none besides the caller. The results do not depend on it, bit for bit. Stepping
(Simulator.step, ScenePlayer, drive's frames) stays on the calling thread. InputError when negative.)doc");
  m.def("threads", &parallelThreads, "The thread count set_threads set (1 by default).");
}

}  // namespace myo::python
