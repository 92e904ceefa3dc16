#include "myoshell/core/errors.h"

#include <sstream>

#include "myoshell/core/check.h"
#include "myoshell/core/io_error.h"

namespace myo {

namespace {
std::string locate(const std::string& message, const std::string& file, int line, int column) {
  std::ostringstream os;  // (ostringstream: gcc 12 warns falsely on chained string appends)
  if (!file.empty()) {
    os << file;
    if (line > 0) {
      os << ':' << line;
      if (column > 0) os << ':' << column;
    }
    os << ": ";
  }
  os << message;
  return os.str();
}
}  // namespace

InputError::InputError(const std::string& message, std::string file, int line, int column)
    : std::runtime_error(locate(message, file, line, column)),
      message_(message),
      file_(std::move(file)),
      line_(line),
      column_(column) {}

IoError::IoError(const std::string& message, std::string path)
    : std::runtime_error(locate(message, path, 0, 0)), message_(message), path_(std::move(path)) {}

namespace detail {
void checkFailed(const char* file, int line, const std::string& what) {
  throw CheckError(std::string("check failed at ") + file + ":" + std::to_string(line) + ": " + what);
}
}  // namespace detail

}  // namespace myo
