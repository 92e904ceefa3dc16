// Eyelids for the anatomical model (docs/eyelids.md; issue 17): kinematic lids that turn about the
// eyeball's centre, driven by the muscles that move them, and eyeball proxies they cannot enter.
//
// Each eye has an eyeball proxy, a sphere placed from the eye's landmarks (radius
// LidSettings::eyeballRadius face-frame units ≈ 1.2 cm, an adult eyeball being about 2.4 cm
// across), its centre behind the lids so that the mid-lid landmarks lie on the sphere: the lid
// margins rest on the globe. A lid vertex i turns about the axis through the centre along the face
// frame's x by the angle
//   θ_i = c·α_i + r·(1 − c)·β_i          (radians; + lowers a point: elevation φ = atan2(y, z) − θ)
// with c the closure (the activation of orbicularis_oculi_palpebral_<side>, whose pretarsal part
// closes the lid) and r the raise (the activation of levator_palpebrae_superioris_<side>, AU5).
// With Δ(x) the palpebral fissure's angular height at x (the upper margin's elevation minus the
// lower's, both margins being the shortest edge paths through the eye's landmarks), f the lower
// lid's share of a blink and w the lid's weight (1 over the tarsal plate, falling to 0 at the
// orbital rim):
//   upper lid: α_i = (1 − f)·Δ(x_i)·w_i,   β_i = −k·Δ(x_i)·w_i     (k = LidSettings::raiseFraction)
//   lower lid: α_i = −f·Δ(x_i)·w_i,        β_i = 0
// so at c = 1 both margins reach the elevation φ_lo + f·Δ: they meet. Δ vanishes at the canthi
// (both margins end there), where the canthal tendons hold the lids. A closure also turns every lid
// vertex about the vertical axis through the centre, towards the inner canthus, by
//   γ_i = c·(s/R)·|w_i|·Δ(x_i)/Δmax      (s = LidSettings::nasalSlide, R the proxy's radius)
// the pars palpebralis shortening towards its fixed medial attachment: the lower lid's travel in a
// blink is mostly this horizontal, nasal slide (Doane 1980), and both margins take it, so they meet
// where they stood above each other. The slide fades with the fissure's height to nothing at the
// canthi, as the turn does: the canthal tendons hold the lids' ends (a full slide there tore the skin
// beside the inner canthus into a dark crack; docs/eyelids.md).
// The lids follow the eye's turn (EyeGaze: pitch φ_g, yaw ψ_g): a lid vertex also turns by
//   −κ·φ_g·|w_i|·Δ(x_i)/Δmax about the horizontal axis (κ = upperGazeFollow or lowerGazeFollow)
//   κ_s·ψ_g·|w_i|·Δ(x_i)/Δmax about the vertical axis (κ_s = sideGazeFollow)
// fading at the canthi as the nasal slide does; the eyeball itself is not part of the skin. The
// closure then closes the fissure the gaze leaves: α_i takes Δ(x) + (κ_u − κ_l)·φ_g·Δ(x)/Δmax
// (not below 0) for Δ(x), so at c = 1 the margins meet wherever the eye looks.
//
// As the jaw (jaw.h), the rest rides with the lid and the physics acts on the residual: a lid vertex
// is placed at c + R(θ_i)(x_i − c), x_i its (jawed) position rest + u, so the residual turns with the
// lid and a closure never passes through the modal basis. Contact: a rotation about the centre keeps
// a vertex's distance to it, so only the residual can push skin into the eyeball; every vertex of the
// orbit is then projected radially out of the proxy (the per-vertex projection at output).
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "myoshell/anatomy/contact_report.h"
#include "myoshell/core/types.h"
#include "myoshell/head/eye_gaze.h"  // EyeGaze, kGazeMaxDeg
#include "myoshell/head/landmarks.h"
#include "myoshell/mesh/tri_mesh.h"

namespace myo {

// The model's constants (face-frame units are fractions of the outer-canthal distance, 9.7 cm on
// ICT): anatomical estimates, not fitted (docs/eyelids.md lists their sources).
struct LidSettings {
  double eyeballRadius = 0.125;  // ≈ 1.2 cm: the eyeball's axial length is about 2.4 cm
  double lowerShare = 0.1;       // f: in a blink the upper lid travels ~9 mm, the lower ~1 mm up (and nasally)
  double nasalSlide = 0.02;      // s: a blink slides the lids ~2 mm towards the nose over the globe (below)
  double raiseFraction = 0.3;    // k: a full AU5 lifts the upper margin by ~30 % of the fissure (≈ 3 mm)
  double upperTarsus = 0.03;     // w = 1 within this of the upper margin: the visible pretarsal skin, ~3 mm
  double upperFalloff = 0.06;    // then w falls to 0 at the lid crease (~8 mm above the margin)
  double lowerTarsus = 0.02;     // the lower lid's pretarsal skin, ~2 mm
  double lowerFalloff = 0.05;    // to the lower lid crease (~6 mm below the margin)
  double orbitReach = 2.0;       // vertices within this many eyeball radii of the centre are projected
  // Lid–gaze coupling (docs/eyelids.md, "The lids follow the gaze"): the share of the eye's vertical
  // turn each lid takes. The upper lid follows the eye nearly one for one: in 30° of downgaze the
  // upper margin to corneal reflex distance falls by only 1.0 mm of the cornea's ~6.3 mm travel
  // (1 − 1.0/6.3 = 0.84); the fissure narrows from 9.7 to 6.4 mm in 40° of downgaze (Read et al.
  // 2006), so the lower lid takes 0.84 − 3.3/8.4 = 0.45 of the turn.
  double upperGazeFollow = 0.84;
  double lowerGazeFollow = 0.45;
  // The share of the eye's sideways turn the lids take, riding on the cornea's bulge: a choice (no
  // measurement found), ICT's artist shapes only reported against it.
  double sideGazeFollow = 0.25;
};

// One eye's lids and eyeball proxy (head space, cm).
struct EyeLids {
  std::string side;                  // "right" or "left" (the subject's)
  Vec3 centre = Vec3::Zero();        // the eyeball proxy's centre
  double radius = 0.0;               // the proxy's radius
  // The radius contact keeps vertices out of: the proxy's, or less where the rest mesh already
  // lies inside it (the nearest orbit vertex's distance), so the rest is contact-free.
  double contactRadius = 0.0;
  Vec3 axis = Vec3::UnitX();         // the face frame's x
  Vec3 up = Vec3::UnitY();           // the face frame's y (elevation is measured from its z, towards y)
  std::vector<int> lidVertices;      // vertices a lid moves (α or β nonzero)
  std::vector<double> lidWeights;    // w per lid vertex, in (0, 1] on the upper lid, [−1, 0) on the lower
  std::vector<double> raiseAngle;    // β per lid vertex, radians (from the rest fissure)
  double lowerShare = 0.1;           // f (LidSettings::lowerShare)
  double nasalTurn = 0.0;            // radians: the lids' nasal turn about `up` at c = 1 and |w| = 1
  double upperGazeFollow = 0.84, lowerGazeFollow = 0.45, sideGazeFollow = 0.25;  // (LidSettings)
  std::vector<int> orbitVertices;    // vertices projected out of the proxy
  std::vector<int> upperMargin, lowerMargin;  // the margin paths, inner corner to outer corner
  // The mid-lid landmark pairs whose distance is the lid gap (upper, lower): 37/41 and 38/40 on the
  // right eye, 43/47 and 44/46 on the left.
  std::array<std::array<int, 2>, 2> gapPairs{};
};

// The two eyes: eyes[0] the subject's right, eyes[1] the left.
struct LidRig {
  std::array<EyeLids, 2> eyes;
};

// How far each lid is driven, in [0, 1]: close (orbicularis oculi, pars palpebralis) and raise
// (levator palpebrae superioris), index 0 the subject's right eye, 1 the left.
struct LidPose {
  std::array<double, 2> close{0.0, 0.0};
  std::array<double, 2> raise{0.0, 0.0};
  EyeGaze gaze;  // the lids follow the eyes' turn (LidSettings' gaze follows)
  bool isZero() const { return close[0] == 0.0 && close[1] == 0.0 && raise[0] == 0.0 && raise[1] == 0.0 && gaze.isZero(); }
};

// The muscles that drive the lids, by side index (0 right, 1 left).
std::string lidCloserName(int eye);  // orbicularis_oculi_palpebral_right / _left
std::string lidRaiserName(int eye);  // levator_palpebrae_superioris_right / _left

// Where the lid muscles sit in a muscle list (−1 for a muscle it does not have).
struct LidDrivers {
  std::array<int, 2> closers{-1, -1}, raisers{-1, -1};
  bool any() const { return closers[0] >= 0 || closers[1] >= 0 || raisers[0] >= 0 || raisers[1] >= 0; }
  bool drives(int muscle) const;
  // The pose at these activations (one per muscle of the list); 0 for an absent muscle.
  LidPose pose(const VecX& activations) const;
};
LidDrivers lidDrivers(const std::vector<std::string>& muscleNames);

// Whether both eyes are open: a boundary loop of the mesh (an eye opening) lies between each eye's
// corner landmarks. Needs the 68 landmarks (false without them).
bool hasOpenEyes(const TriMesh& skin, const Landmarks& landmarks);

// The lids of a head with open eyes. InputError naming the landmark file when the landmarks have
// no 68 points or an eye is closed (no opening between its corners).
LidRig lidRig(const TriMesh& skin, const Landmarks& landmarks, const LidSettings& settings = {});

// Turns the lid vertices of `positions` (n×3, the skin's jawed rest + residual) about their eye's
// centre by θ_i (above), then projects every orbit vertex out of its proxy. The turn is skipped for
// a zero pose; the projection always runs (at rest it moves nothing).
// `project` false (contact off, docs/scene_format.md): the turn alone; the report then measures the
// deepest vertex (after = before) and moves nothing.
ContactReport applyLids(const LidRig& rig, const LidPose& pose, MatX3& positions, bool project = true);

// The turn of applyLids alone (no contact). It reads the rows of `positions` at the margins and the
// lid vertices and writes only the lid vertices'. `turns`, when given, receives per eye the rotation
// (about the centre) each lid vertex turned by, in lidVertices' order (identities for an eye at rest);
// the change of ρ a closure adds is not in it.
// `scratch`, when given, holds the fissure's curves between calls, so a warm call allocates nothing
// (the step's contact penalty turns the lids at every step).
struct LidMarginCurve {
  std::vector<int> byX;                                    // the margin's vertices sorted by x
  std::vector<std::pair<double, double>> elevation, distance;  // (x, φ) and (x, ρ)
};
struct LidFissure {
  LidMarginCurve upper, lower;
  double xLow = 0.0, xHigh = 0.0;  // the canthi's x
};
void turnLids(const LidRig& rig, const LidPose& pose, MatX3& positions, std::array<std::vector<Mat3>, 2>* turns = nullptr,
              LidFissure* scratch = nullptr);

// turnLids's two parts, for one eye (e: 0 right, 1 left), so that the step's contact stiffness can
// differentiate a lid vertex's place through the margins it depends on (contact_penalty.h):
// measureClosure reads the margins' rows of `positions` into `fissure` and returns what turns the
// lids; turnLidVertex places lid vertex k (lidVertices' order) from its jawed position p, *turn
// receiving the rotation. An eye at rest (`moves` false) turns nothing.
struct EyeClosure {
  bool moves = false, gazing = false;
  double close = 0.0, raise = 0.0;             // c and r
  double gazePitch = 0.0, gazeYaw = 0.0;       // φ_g and ψ_g (radians)
  double towardsNose = 1.0, gapMax = 0.0;      // the nasal slide's sign along x; Δmax (radians)
  size_t gapTop = 0;                           // the upper margin's entry (by x) Δmax is read at
};
EyeClosure measureClosure(const EyeLids& eye, const LidPose& pose, size_t e, const MatX3& positions, LidFissure& fissure);
Vec3 turnLidVertex(const EyeLids& eye, const EyeClosure& closure, const LidFissure& fissure, size_t k, const Vec3& p,
                   Mat3* turn = nullptr);
// The gradient of g · turnLidVertex(…) with respect to the jawed positions of the rows it reads:
// the vertex's own and the margins' the fissure's readings at its x and Δmax come from (entries of
// `out`: vertex, ∂(g·x')/∂p_vertex). Analytic through the margin curves' linear interpolation and
// the margins' (x, φ, ρ); the turn's own dependence on its readings and on p by forward differences
// (a few evaluations, no fissure measured). The canthi's x and the slide's sign only switch, so they
// have none. For the contact penalty's chain (contact_penalty.h).
void turnLidVertexGradient(const EyeLids& eye, const EyeClosure& closure, const LidFissure& fissure, size_t k, const Vec3& p,
                           const Vec3& g, std::vector<std::pair<int, Vec3>>& out);

// The lid gap of eye `eye` (0 right, 1 left) in `positions`: the mean distance of its two mid-lid
// landmark pairs, cm.
double lidGap(const LidRig& rig, int eye, const MatX3& positions);

}  // namespace myo
