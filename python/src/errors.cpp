// The library's errors as Python exceptions with the same messages: InputError (bad input, a
// ValueError), SimulationError (a numerical failure, a RuntimeError) and IoError (the system failing
// to write an output, an OSError).
#include "bindings.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"

namespace myo::python {

void bindErrors(py::module_& m) {
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError)
      .doc() = "Bad input from a file or an argument (the C++ myo::InputError; same message). A ValueError.";
  py::register_exception<NumericalError>(m, "SimulationError", PyExc_RuntimeError)
      .doc() = "A numerical failure: a solve that did not converge, a simulation that blew up (the C++ "
               "myo::NumericalError; same message). A RuntimeError.";
  // Not the user's input (the command line exits 1 for it, 2 for InputError): a path that cannot be
  // a file (a missing folder, no permission) is an InputError; a full disk is an IoError.
  py::register_exception<IoError>(m, "IoError", PyExc_OSError)
      .doc() = "The system failed while writing an output: no space left, a file too large, an I/O error "
               "(the C++ myo::IoError; message 'path: what (reason)'). An OSError. Nothing half-written is left.";
}

}  // namespace myo::python
