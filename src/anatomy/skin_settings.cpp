#include "myoshell/anatomy/skin_settings.h"

#include <cmath>
#include <string>

#include "myoshell/core/errors.h"

namespace myo {

void AnatomicalSettings::validate() const {
  auto bad = [](const std::string& what) { throw InputError("anatomical model: " + what); };
  if (!(skinYoungModulus > 0) || !std::isfinite(skinYoungModulus)) bad("skin Young's modulus must be > 0 dyn/cm²");
  if (!(skinThickness > 0) || !std::isfinite(skinThickness)) bad("skin thickness must be > 0 cm");
  if (skinModes < 0) bad("skin modes must be ≥ 0");
  if (!std::isfinite(gravity)) bad("gravity is not finite");
  if (!(dt > 0) || !std::isfinite(dt)) bad("dt must be > 0");
  if (!(dampingMass >= 0) || !(dampingStiffness >= 0)) bad("damping must be ≥ 0");
  if (!(relaxedMuscleModulus >= 0) || !std::isfinite(relaxedMuscleModulus))
    bad("the relaxed muscles' modulus must be ≥ 0 dyn/cm² (0: muscles hold the skin)");
  if (!(contactStiffness > 0) || !std::isfinite(contactStiffness))
    bad("the contact stiffness must be > 0 1/s² (per unit vertex mass)");
  if (!(contactDamping >= 0) || !std::isfinite(contactDamping)) bad("the contact damping must be ≥ 0 s");
}

ShellMaterial anatomicalSkinMaterial(const AnatomicalSettings& s, double meanEdge) {
  const double Eh = s.skinYoungModulus * s.skinThickness;
  ShellMaterial m;
  m.kA = Eh / 6.0;
  m.kL = 0.385 * Eh * meanEdge;
  m.kB = s.skinYoungModulus * std::pow(s.skinThickness, 3) / (12.0 * (1.0 - 0.25));
  m.density = s.attachment.tissueDensity;
  m.thickness = s.skinThickness;
  return m;
}

Vec3 gravityForPose(const FaceFrame& frame, const Vec3& pyr, double gravity) {
  const double d = M_PI / 180.0;
  // Rotation of the head in face-frame coordinates, x then y then z: R = R_z R_y R_x.
  const Mat3 Rf = (Eigen::AngleAxisd(pyr.z() * d, Vec3::UnitZ()) * Eigen::AngleAxisd(pyr.y() * d, Vec3::UnitY()) *
                   Eigen::AngleAxisd(pyr.x() * d, Vec3::UnitX()))
                      .toRotationMatrix();
  const Mat3 R = frame.axes * Rf * frame.axes.transpose();  // in head space
  return -gravity * (R.transpose() * Vec3::UnitY());
}

}  // namespace myo
