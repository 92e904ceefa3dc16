// Material of a discrete shell (thesis eq. 4), in cm–g–s units.
#pragma once

namespace myo {

struct ShellMaterial {
  double kA = 1.0e3;       // stretch stiffness k_A, dyn/cm (E_A is in cm²)
  double kL = 1.0e2;       // edge-length (shear) stiffness k_L, dyn (E_L is in cm)
  double kB = 1.0e1;       // bending stiffness k_B, erg = dyn·cm (E_B is dimensionless)
  double density = 1.0;    // ρ, g/cm³
  double thickness = 0.2;  // t, cm; areal density is ρ·t in g/cm²

  // Throws InputError naming the field when a value is negative, NaN, or (density, thickness) zero.
  void validate() const;
};

}  // namespace myo
