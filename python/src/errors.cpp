// The library's errors as Python exceptions with the same messages: InputError (bad input, a
// ValueError) and SimulationError (a numerical failure, a RuntimeError).
#include "bindings.h"
#include "myoshell/core/errors.h"

namespace myo::python {

void bindErrors(py::module_& m) {
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError)
      .doc() = "Bad input from a file or an argument (the C++ myo::InputError; same message). A ValueError.";
  py::register_exception<NumericalError>(m, "SimulationError", PyExc_RuntimeError)
      .doc() = "A numerical failure: a solve that did not converge, a simulation that blew up (the C++ "
               "myo::NumericalError; same message). A RuntimeError.";
}

}  // namespace myo::python
