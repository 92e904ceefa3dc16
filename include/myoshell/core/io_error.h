// The run-time I/O error, beside core/errors.h's InputError (bad input, exit 2) and NumericalError.
#pragma once

#include <stdexcept>
#include <string>

namespace myo {

// A run-time failure of the system while writing or creating an output: no space left, a file
// too large (RLIMIT_FSIZE), an I/O error, too many open files; any failure once the file is open.
// Not the user's input: the CLI exits 1 (InputError exits 2). what() reads "path: message (reason)",
// the reason being the OS's (strerror). Thrown by core/atomic_file.h and render's VideoWriter.
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& message, std::string path);

  const std::string& message() const { return message_; }
  const std::string& path() const { return path_; }

 private:
  std::string message_;
  std::string path_;
};

}  // namespace myo
