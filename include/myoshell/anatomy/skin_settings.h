// The anatomical skin's settings (docs/anatomical_model.md; scene keys in docs/scene_format.md):
// the skin's material, the tissue attachment, the muscles' coupling and release, damping, the step
// and contact; the skin material they describe and gravity for a head pose.
#pragma once

#include <vector>

#include "myoshell/core/types.h"
#include "myoshell/head/face_frame.h"
#include "myoshell/muscles/muscle_coupling.h"
#include "myoshell/muscles/tissue_attachment.h"
#include "myoshell/shell/shell_material.h"

namespace myo {

// How gravity loads the warped skin, relative to the rest pose (METHOD.md §9). The rest mesh is in
// equilibrium under M g_rest (upright); both readings give zero load upright.
enum class GravityReading {
  RotatedPrestress,  // (a): Φᵀ Rᵀ M g(t) − Φᵀ M g_rest (the rest pre-stress turns with the tissue)
  ChangeOnly,        // (b): Φᵀ Rᵀ M (g(t) − g_rest) (only the change of gravity is a load)
};

// What a muscle's strength rule holds to its shortening σ at a = 1, alone among the relaxed others
// (docs/anatomical_model.md, "Strength").
enum class StrengthRule {
  MuscleShortens,  // the muscle's own coordinate: q_m = 1 (the skin over it lags behind)
  SkinFollows,     // the skin it is tied to: its coupling-weighted motion along the shape, cᵀu/s = 1
};

// How the skin answers the muscles' activations in time (docs/live.md, "Lag"; the scene's
// numerics.response, drive --response).
enum class SkinResponse {
  Dynamic,  // each level follows its target (critically damped at the muscle's frequency), the skin
            // its modal dynamics under the levels' loads: the skin trails a step by tens of ms
  Follow,   // levels = targets, and the skin's linear quasi-static response to them taken at once;
            // only the rest (gravity and head turns, drags, contact, the warp) steps dynamically.
            // Settles where Dynamic does.
};

struct AnatomicalSettings {
  // Skin (dermis) as a membrane + bending shell from a Young's modulus and thickness (ν = 0.5):
  // k_A = E h/6, k_L = 0.385 E h ℓ̄ (ℓ̄ the mean edge length), k_B = E h³/(12(1 − ν²))
  // (docs/anatomical_model.md derives the factors for an equilateral mesh).
  double skinYoungModulus = 1.0e6;  // dyn/cm² (0.1 MPa)
  double skinThickness = 0.15;      // cm
  AttachmentSettings attachment;
  std::vector<AttachmentOverride> attachmentOverrides;
  MuscleCouplingSettings coupling;
  int skinModes = 30;               // d lowest modes in the Ritz basis
  double gravity = 981.0;           // cm/s²; the rest pose is upright: g_rest = −gravity·ŷ (head space)
  GravityReading gravityReading = GravityReading::ChangeOnly;
  // Linear modes: against the full-space nonlinear reference (zygomaticus, a = 1) they err 15.0 %,
  // modal warping 17.5 %, and warping stretches a mouth-corner edge by 140 % where the reference
  // stretches it by 29 % (docs/anatomical_model.md, "Warping or linear modes").
  bool warping = false;
  double dampingMass = 8.0;         // ξ, 1/s (Rayleigh)
  double dampingStiffness = 2e-4;   // ζ, s
  double dt = 1.0 / 240.0;          // s
  SkinResponse response = SkinResponse::Dynamic;  // not in the basis key: the basis is the same
  // Relaxed muscles follow the skin (docs/anatomical_model.md, "Relaxed muscles follow the skin"):
  // each muscle's coordinate along its shape is condensed out with the passive stiffness
  // κ_m = E_p A_m σ_m² L_m of its belly (A_m its cross-section, L_m its length, σ_m its shortening at
  // a = 1), E_p this modulus along the fibres of a muscle at rest. 0: every muscle holds the skin
  // over it at its rest place whatever its activation (the couplings fed forward only).
  double relaxedMuscleModulus = 1.0e5;  // dyn/cm² (10 kPa, passive skeletal muscle at rest length)
  // Release each relaxed muscle across its fibres too: besides its shape, the muscle moves with the
  // skin in the three directions (its motion weighted as its shape's, S-orthogonal to the shape), with
  // the same passive stiffness per unit of coupling energy (docs/anatomical_model.md, "Released
  // across"). false: only along the shape, the model of the first release.
  bool releaseAcross = true;
  // Release a ring muscle in its two halves, each with its own coordinates (along and across) and
  // half the belly: the mouth's upper and lower parts into their right and left quadrants, the eye's
  // rings into their upper and lower arcs between the canthi (docs/anatomical_model.md, "A ring is
  // released in halves"). false: one release for the whole ring, which ties the two mouth corners.
  bool releaseRingHalves = true;
  // The fibres insert into the dermis: at a = 1 the skin over the insertion moves with the muscle end.
  StrengthRule strength = StrengthRule::SkinFollows;
  // Contact (docs/mouth_contact.md, docs/eyelids.md): on a head with eyeballs or teeth proxies, the
  // penalty forces in the step and the settle (for loads with SkinLoads::contact) and the projection
  // out of the proxies when a shape is placed. false: neither (the shape without contact; the basis
  // is the same, so the switch costs no rebuild). The scene's "contact": "on" | "off".
  bool contact = true;
  // κ (1/s²): the penalty stiffness per unit vertex mass, k_i = κ m_i (contact_penalty.h). The
  // penalty's reduced stiffness is at most about κ, so the explicit penalty in the step is stable for
  // κ below the limit docs/mouth_contact.md ("Penalty forces") measures.
  double contactStiffness = 1.0e9;
  // β (s): each violated constraint also has a normal dashpot c_t = β k_t in the step, taken with
  // the step's own motion (Δ/h), so the step's force is f_c − (1 + β/h) K_c Δ. Without it the
  // linearly implicit penalty sends a vertex that met a constraint back out as fast as it came in
  // (a bounce with restitution 1), and the bounces of the lips on the teeth rang through the reduced
  // modes: the built-in head's smile (demo.json) stepped to 0.29–0.41 cm mean displacement where its
  // settle has 0.239. β = 1/240 s (66 times the critical c = 2√(k m)): soft tissue meeting teeth does
  // not bounce. A face at rest in contact (Δ = 0) settles where the static solve does, whatever β
  // (docs/mouth_contact.md, "Penalty forces").
  double contactDamping = 1.0 / 240.0;
  void validate() const;            // InputError naming the field
};

// The skin material AnatomicalSettings describes, for a mesh of mean edge length ℓ̄ (cm).
ShellMaterial anatomicalSkinMaterial(const AnatomicalSettings& s, double meanEdgeLength);

// Gravity in the head's space (cm/s²) for a head pose [pitch, yaw, roll] in degrees about the face
// frame's x, y, z (applied in that order): g = −|g|·R(pose)ᵀ ŷ_world with the world's up = the head's
// +y at rest. Face-down is +90° pitch (gravity along the face frame's +z, out of the face).
Vec3 gravityForPose(const FaceFrame& frame, const Vec3& pitchYawRollDeg, double gravity);

}  // namespace myo
