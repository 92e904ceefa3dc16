#include "myoshell/shell/shell_material.h"

#include <cmath>
#include <sstream>
#include <string>

#include "myoshell/core/errors.h"

namespace myo {

namespace {
// Throws "<name> must be ≥ 0 (got v)" or "> 0"; NaN fails both comparisons, so it is rejected too.
void require(const char* name, double value, bool strictlyPositive) {
  const bool ok = strictlyPositive ? value > 0.0 : value >= 0.0;
  if (ok && std::isfinite(value)) return;
  std::ostringstream os;
  os << name << (strictlyPositive ? " must be > 0" : " must be ≥ 0");
  if (ok) os << " and finite";
  os << " (got " << value << ")";
  throw InputError(os.str());
}
}  // namespace

void ShellMaterial::validate() const {
  require("k_A", kA, false);
  require("k_L", kL, false);
  require("k_B", kB, false);
  require("density", density, true);
  require("thickness", thickness, true);
}

}  // namespace myo
