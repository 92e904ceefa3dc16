// Accuracy cases: the reduced solutions (modal warping, linear modal) against the full-space
// nonlinear reference (reference_solver.h) and against beam theory, on a clamped strip
// (METHOD.md §5.3). Library functions returning structured results; `myoshell validate` prints
// them and tests/verify/accuracy_test.cpp asserts their bounds. docs/validation.md has the table.
//
// Error metrics (all relative, dimensionless):
//   field error   e = ‖u − u_ref‖_M / ‖u_ref‖_M over the free vertices (lumped M; METHOD.md §5.1)
//   tip error     ‖ū_tip − ū_tip,ref‖ / ‖ū_tip,ref‖ with ū_tip the load-weighted mean displacement
//                 of the tip row (a 3-vector, cm)
//   length growth (arc length of the deformed centre line from the clamp to the tip) / L − 1
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/mesh/tri_mesh.h"
#include "myoshell/verify/reference_solver.h"
#include "myoshell/shell/discrete_shell.h"
#include "myoshell/shell/shell_material.h"

namespace myo {

// A flat cantilever strip in the xy-plane: free length L along +x from the clamp line x = 0 to the
// tip, width w along y, nx×ny cells of the alternating-diagonal grid over the free part plus one
// extra column of cells at x ∈ [−L/nx, 0]; the two vertex rows at x = −L/nx and x = 0 are pinned
// (clamping ≥ 2 rows removes the rigid hinge mode, METHOD.md §2.4).
struct StripDef {
  double length = 1.0;  // L, cm (free length, clamp line to tip)
  double width = 0.1;   // w, cm
  int nx = 40;          // cells along the free length
  int ny = 4;           // cells across (even, so that a centre row of vertices exists)
  // The material of METHOD.md §5.3: k_A = 1e3 dyn/cm, k_L = 1e2 dyn, k_B = 1e-2 erg, ρ·t = 1 g/cm².
  ShellMaterial material = defaultMaterial();

  static ShellMaterial defaultMaterial() {
    ShellMaterial m;
    m.kA = 1e3;
    m.kL = 1e2;
    m.kB = 1e-2;
    m.density = 1.0;
    m.thickness = 1.0;
    return m;
  }
};

// The built strip: mesh, shell, constraints, and the vertex rows used for loads and measurements.
struct Strip {
  StripDef def;
  TriMesh mesh;
  DiscreteShell shell;
  std::vector<int> pinned;      // the two clamped vertex rows
  std::vector<int> tip;         // tip row (x = L), ordered by y
  std::vector<double> tipWeight;  // per tip vertex, trapezoidal share of a line load (sums to 1)
  std::vector<int> centreLine;  // vertices of the centre row y = w/2 from x = 0 to x = L

  // Transverse (+z) end load of total P (dyn) spread over the tip row with tipWeight (n×3, dyn).
  MatX3 tipLoad(double P) const;
  // Load-weighted mean displacement of the tip row (cm) of a full n×3 displacement.
  Vec3 tipDisplacement(const MatX3& u) const;
  // Tip rotation (rad) about −y: angle of the centre line's last segment from the +x axis.
  double tipRotation(const MatX3& u) const;
  // Centre-line length growth (dimensionless): deformed arc length from x = 0 to the tip / L − 1.
  double lengthGrowth(const MatX3& u) const;
  // Area growth (dimensionless): total deformed triangle area of the strip / rest area − 1.
  double areaGrowth(const MatX3& u) const;
  // ‖u − ref‖_M / ‖ref‖_M over all vertices (pinned ones are zero in both).
  double fieldError(const MatX3& u, const MatX3& ref) const;
};
Strip buildStrip(const StripDef& def);

// Effective bending rigidity D_eff (erg = dyn·cm) of a strip mesh's k_B·E_B, defined by
// energy per area = D_eff·κ²/2 (METHOD.md §1.7), membrane terms excluded. The energy per area is
// taken as the difference between the same strip at 2nx and nx cells over their area difference,
// which cancels the end effects at the two short ends.
//  - cylinder: E_B of the mesh bent (x, y) → (x, y, ½(κ_x x² + κ_y y²)) with κ·L = 1e-4 (E_B is
//    quadratic in κ to ~1e-8). On the alternating-diagonal grid this gives D = 6·k_B exactly and
//    no Poisson coupling (the diagonal hinges only see twist).
//  - relaxed: the cylinder imposed on two vertex columns at each end only, the interior free to
//    minimise the linearized bending energy ½zᵀK_zz z. The hinge energy admits non-affine
//    (zig-zag) fluctuations that lower the energy of a uniform curvature: measured D_relaxed =
//    0.800·D_cyl for square cells (0.61 for 2:1 cells across, 0.96 for 1:2). This is the rigidity
//    the strip actually shows (cantilever deflection and ω₁ agree with it to ≤ 2%, with D_cyl
//    they are off by 27% and 12%): see docs/validation.md.
struct BendingRigidity {
  double cylinder = 0.0;      // κ_y = 0 (bent onto a cylinder): D_cyl = 2·Q(κ,0)/κ²
  double anticlastic = 0.0;   // κ_y free (minimising): D_cyl − 2·Q_xy²/Q_yy, the narrow-beam value
  double poisson = 0.0;       // effective Poisson ratio of the discrete bending energy, Q_xy/Q_yy
  double relaxed = 0.0;       // interior relaxed, as above
};
BendingRigidity measureBendingRigidity(const StripDef& def);

// One reduced-vs-reference comparison. Values are of `quantity` (units given there).
struct AccuracyCase {
  std::string name;            // short identifier, e.g. "cantilever_small_load_40x4"
  std::string description;
  int d = 0;                   // modes in the reduced basis
  std::string quantity;        // what reference/warped/linear are, e.g. "tip deflection (cm)"
  double reference = 0.0;
  double warped = 0.0;
  double linear = 0.0;
  double errorWarped = 0.0;    // relative error of warped vs reference (metric in `metric`)
  double errorLinear = 0.0;
  std::string metric;          // e.g. "field M-norm", "tip", "tip trajectory max"
  // Further named numbers (beam theory values, rotations, timings, …) in a stable order.
  std::vector<std::pair<std::string, double>> extra;
  // The bound this case is held to, in words, and whether it holds.
  std::string bound;
  bool passed = true;

  double get(const std::string& key) const;  // an `extra` value by name; throws CheckError if absent
};

// Settings of the whole suite (defaults: what `myoshell validate` and the tests run).
struct ValidationSettings {
  int modes = 20;                   // d of the reduced bases
  StripDef coarse{};                // 40×4 cells
  StripDef fine = fineStrip();      // 80×8 cells
  double smallLoad = 0.01;          // δ_lin/L of the small-load case
  double largeLoad = 0.8;           // δ_lin/L of the large-load case (tip rotation ≈ 50°)
  double dynamicLoad = 0.3;         // δ_lin/L of the released-tip case
  double dynamicPeriods = 3.0;      // simulated time in periods of mode 1
  int stepsPerPeriod = 200;         // h = T₁/stepsPerPeriod for both integrators
  double dampingRatio = 0.02;       // mode-1 damping ratio, as mass-proportional ξ = 2·ratio·ω₁
  bool dynamic = true;              // run the dynamic case (the slowest)

  static StripDef fineStrip() {
    StripDef d;
    d.nx = 80;
    d.ny = 8;
    return d;
  }
};

// Clamped strip, small transverse end load (δ_lin/L = loadRatio): warped, linear-modal and
// full-space static deflections (bound: all agree within 2%, tip and field), plus beam theory:
// tip deflection P·L³/(3·D_eff·w) vs the full-space one and ω₁ = 1.875²·√(D_eff/(ρ·t·L⁴)) vs √λ₁
// (bound: 5% with D_eff = D_relaxed; the D_cyl values are reported in `extra`).
AccuracyCase cantileverSmallLoad(const StripDef& def, int d, double loadRatio = 0.01);

// Same strip under a large end load (δ_lin/L = loadRatio; tip rotation ≥ 45° at the default):
// field errors of warped and linear vs the reference, their ratio, tip rotations and length growth.
// Bound: warped error ≤ errorLinear/3.
AccuracyCase cantileverLargeLoad(const StripDef& def, int d, double loadRatio = 0.8);

// Released tip: each model starts at rest in its own static equilibrium under the end load
// (δ_lin/L = loadRatio), then the load is removed. Warped (Exact stepper) and linear modal vs the
// full-space BDF2 reference at the same h = T₁/stepsPerPeriod, over `periods` periods, light
// mass-proportional damping. Errors: max over time of the tip-deflection difference / max |ref|.
// scheme: the reference's time discretisation (BDF2 by default: backward Euler's numerical damping,
// ≈ exp(−π·h·ω) in amplitude per period, is 9% per period at h = T₁/200).
AccuracyCase releasedTip(const StripDef& def, int d, double loadRatio, double periods,
                         int stepsPerPeriod, double dampingRatio,
                         ImplicitScheme scheme = ImplicitScheme::BDF2);

struct ValidationReport {
  std::vector<AccuracyCase> cases;
  double seconds = 0.0;  // wall time of the whole suite
  bool allPassed() const;
};

// Runs every case of the suite.
ValidationReport runValidation(const ValidationSettings& settings = {});

}  // namespace myo
