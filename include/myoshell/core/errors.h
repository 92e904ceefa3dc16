// Error types. The library never exits: it throws, and only apps/ turns errors into exit codes.
#pragma once

#include <stdexcept>
#include <string>

namespace myo {

// Bad input from a user's file or arguments. what() reads "file:line:col: message", with the
// parts that are unknown left out ("file: message", "file:line: message", or just "message").
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message, std::string file = {}, int line = 0, int column = 0);

  const std::string& message() const { return message_; }
  const std::string& file() const { return file_; }
  int line() const { return line_; }      // 1-based; 0 when unknown
  int column() const { return column_; }  // 1-based; 0 when unknown

 private:
  std::string message_;
  std::string file_;
  int line_;
  int column_;
};

// A violated internal invariant (a bug, or an API misuse), raised by MYO_CHECK.
class CheckError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// A numerical failure at run time (a solver that did not converge, a simulation that blew up).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A picture that cannot be drawn: no OpenGL context could be made (no EGL display, no GL 3.3 core,
// no window system), or a shader did not compile. Callers may fall back to the software renderer.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace myo
