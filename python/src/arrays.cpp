// NumPy copies in and out: Python never holds a view into the library's buffers, which the
// simulator reuses from step to step.
#include <cmath>
#include <cstring>
#include <fmt/core.h>

#include "bindings.h"
#include "myoshell/core/errors.h"

namespace myo::python {

py::array_t<double> toNumpy(const MatX3& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), py::ssize_t{3}});
  if (m.size() > 0) std::memcpy(out.mutable_data(), m.data(), sizeof(double) * static_cast<size_t>(m.size()));
  return out;
}

py::array_t<int> toNumpy(const MatX3i& m) {
  py::array_t<int> out({static_cast<py::ssize_t>(m.rows()), py::ssize_t{3}});
  if (m.size() > 0) std::memcpy(out.mutable_data(), m.data(), sizeof(int) * static_cast<size_t>(m.size()));
  return out;
}

MatX3 toMatX3(const py::handle& array, const std::string& what, Eigen::Index rows) {
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  Doubles a;
  try {
    a = py::cast<Doubles>(array);
  } catch (const py::error_already_set&) {
    throw InputError(what + ": expected an (n, 3) array of numbers");
  } catch (const py::cast_error&) {
    throw InputError(what + ": expected an (n, 3) array of numbers");
  }
  std::string shape;
  for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += fmt::format("{}{}", d ? ", " : "", a.shape(d));
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(fmt::format("{}: expected an (n, 3) array, got shape ({})", what, shape));
  if (rows >= 0 && a.shape(0) != rows)
    throw InputError(fmt::format("{}: expected {} rows (one per vertex of the head), got {}", what, rows, a.shape(0)));
  MatX3 m(a.shape(0), 3);
  if (m.size() > 0) std::memcpy(m.data(), a.data(), sizeof(double) * static_cast<size_t>(m.size()));
  if (!m.allFinite()) throw InputError(what + ": holds a NaN or an infinite value");
  return m;
}

py::array_t<double> toNumpy(const std::vector<MatX3>& frames) {
  const py::ssize_t n = frames.empty() ? 0 : static_cast<py::ssize_t>(frames.front().rows());
  py::array_t<double> out({static_cast<py::ssize_t>(frames.size()), n, py::ssize_t{3}});
  double* to = out.mutable_data();
  for (const MatX3& f : frames) {
    std::memcpy(to, f.data(), sizeof(double) * static_cast<size_t>(f.size()));
    to += f.size();
  }
  return out;
}

std::vector<MatX3> toFrames(const py::handle& frames, const std::string& what, Eigen::Index rows) {
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  Doubles a;
  try {
    a = py::cast<Doubles>(frames);
  } catch (const py::error_already_set&) {
    throw InputError(what + ": expected an (F, n, 3) array of numbers");
  } catch (const py::cast_error&) {
    throw InputError(what + ": expected an (F, n, 3) array of numbers");
  }
  std::string shape;
  for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += fmt::format("{}{}", d ? ", " : "", a.shape(d));
  if (a.ndim() != 3 || a.shape(2) != 3) throw InputError(fmt::format("{}: expected an (F, n, 3) array, got shape ({})", what, shape));
  if (a.shape(0) < 1) throw InputError(what + ": no frame given");
  if (rows >= 0 && a.shape(1) != rows)
    throw InputError(fmt::format("{}: expected {} vertices a frame (the head's), got {}", what, rows, a.shape(1)));
  std::vector<MatX3> out(static_cast<size_t>(a.shape(0)), MatX3(a.shape(1), 3));
  const double* from = a.data();
  for (MatX3& f : out) {
    std::memcpy(f.data(), from, sizeof(double) * static_cast<size_t>(f.size()));
    from += f.size();
    if (!f.allFinite()) throw InputError(what + ": holds a NaN or an infinite value");
  }
  return out;
}

const TriMesh& meshOf(const py::handle& o) {
  if (py::isinstance<HeadHandle>(o)) return o.cast<const HeadHandle&>().head.mesh;
  if (py::isinstance<FaceHandle>(o)) return o.cast<const FaceHandle&>().face->head().mesh;
  throw InputError("head: expected a Head (load_head) or a Face");
}

}  // namespace myo::python
