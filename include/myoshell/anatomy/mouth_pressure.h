// Air in the mouth (ARKit's cheekPuff, FACS AU34 "puff"; docs/anatomical_model.md, "Air in the
// mouth"): the pressure p of air held in the oral vestibule by the sealed lips pushes the cheeks and
// lips outward from inside. The skin carries no cavity, so the load is placed on the skin over the
// vestibule: at vertex i
//   f_i = p · A_i · w_i · n_i        (dyn; p in dyn/cm² = 10 × Pa, A_i the lumped vertex area, n_i the
//                                     outward unit normal)
// with w_i the vestibule's footprint in the face frame (1 over the cheeks beside the teeth and over
// both lips, falling smoothly to 0 at its edges): laterally to 0.2 frame units (≈ 2 cm) beyond the
// mouth corners, up to the nose's base, down to the labiomental fold above the chin. The response
// is the skin's full-space one to that load with the shell's large deflection (nonlinearFullResponse,
// anatomy/nonlinear_settle.h): the mouth's pressure is no pattern of the reduced basis, and at a
// puff's size the cheek's stretch stiffens it (the linear response overshoots the cheeks by 19 % on
// the built-in head and 30 % on ICT at 2 kPa).
#pragma once

#include "myoshell/core/types.h"
#include "myoshell/head/head.h"

namespace myo {

// The cheeks' inner pressure of a full cheek puff, kPa: between speech's plosives (0.5–1 kPa) and
// the maximal mouth pressures of blowing (8 kPa and more), a choice (docs/anatomical_model.md).
constexpr double kCheekPuffPressureKpa = 2.0;
// A map or a FACS map may ask for at most this much (above it the lips no longer seal).
constexpr double kMouthPressureMaxKpa = 10.0;

// The vestibule's footprint w_i in [0, 1] per vertex of `head` (from its mouth corners, upper lip's
// top, nose tip and menton landmarks).
VecX mouthVestibuleWeights(const Head& head);

// The load (n×3, dyn) of air at `pressureKpa` kPa in the mouth of `head`.
MatX3 mouthPressureLoad(const Head& head, double pressureKpa);

// How far a shape `delta` (n×3, cm) moves the cheeks out (cm): the largest δ_i·n_i (n_i the rest
// outward unit normal, as the load's) over the cheeks, the vestibule's footprint (w_i ≥ 0.5)
// lateral of the mouth corners (|x| beyond the corners' mean |x| in the face frame).
double cheekOutwardMoveCm(const Head& head, const MatX3& delta);

}  // namespace myo
