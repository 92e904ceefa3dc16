// The thesis's face (sections IV–VI): four layers — skin, subcutaneous springs, muscles, skull
// anchors — and force decomposition: one skin system ("channel") per muscle and per external force,
// each with its own pins and modal basis, their displacement fields summed (eq. 20–25).
//
// A FaceModel is built once (all eigen-solves, ROIs and springs; bases cached on disk when a
// BasisCache is given) and is immutable; a Simulator (simulator.h) steps it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "myoshell/head/face_system.h"
#include "myoshell/head/head.h"
#include "myoshell/muscles/muscle.h"
#include "myoshell/reduce/basis_cache.h"
#include "myoshell/reduce/modal_basis.h"
#include "myoshell/reduce/modal_warping.h"
#include "myoshell/shell/discrete_shell.h"

namespace myo {

// How a subcutaneous spring turns a muscle node's displacement u_m into a force on its skin node.
enum class SpringModel {
  // Thesis eq. 14–16 as written: |F| = k·| |S_d| − |S_init| | / |S_init|, along (S_d − S_ud)/|S_d − S_ud|,
  // i.e. along u_m. Its magnitude is second order when the muscle slides tangentially under the skin.
  Thesis,
  // Named variant ("displacement"): F = k·u_m/|S_init|, linear in the muscle's motion, so a small
  // contraction already moves the skin (docs/face_model.md compares the two).
  Displacement,
};

struct FaceModelSettings {
  // Skin material (cm–g–s). The bending stiffness matters beyond looks: modal warping rotates the
  // springs' tangential pull with the skin's tilt and has no geometric stiffness, so a skin that
  // bends too easily under a strong pull runs away (docs/face_model.md measures the threshold).
  ShellMaterial skin = [] {
    ShellMaterial m;
    m.kA = 2.0e3;
    m.kL = 2.0e2;
    m.kB = 3.0e2;
    m.density = 1.1;     // g/cm³
    m.thickness = 0.15;  // cm: epidermis and dermis; the tissue below is the springs' layer
    return m;
  }();
  // Muscle material: bending stiff against stretch (k_B/k_A = 100 cm²), so that, as in the thesis,
  // the stretch mode is among the lowest modes of a pinned muscle (docs/muscles.md).
  ShellMaterial muscle = [] {
    ShellMaterial m;
    m.kA = 1.0e3;
    m.kL = 1.0e2;
    m.kB = 1.0e5;
    m.density = 1.06;
    m.thickness = 0.2;
    return m;
  }();
  int skinModes = 30;                 // d of every skin channel
  int muscleModes = 4;                // d of a muscle's modal analysis (thesis: 4); one mode is kept
  double roiAlpha = 6.0;              // α of eq. 19 (> 1) unless a muscle sets its own
  double springStiffness = 300.0;     // k_spring of eq. 14, dyn, unless a muscle sets its own
  SpringModel springModel = SpringModel::Thesis;
  double dt = 1.0 / 240.0;            // s, the fixed step of every channel
  ModalStepper stepper = ModalStepper::Exact;
  bool warping = true;
  double skinDampingMass = 8.0;       // ξ, 1/s (Rayleigh, eq. 6)
  double skinDampingStiffness = 2e-4; // ζ, s
  double muscleDampingRatio = 1.0;    // of the muscle's single mode (1 = critically damped)
  bool gravity = true;                // build the gravity channel
  double gravityAcceleration = 981.0; // cm/s², along −y of the head's space
  // The gravity channel pins the head's gravity pins and, as the thesis does (Fig. 21: "the
  // backside of the head and feature points of the face were fixed"), every landmark vertex.
  bool gravityPinsLandmarks = true;
  // Report each skin channel's load participation (SkinChannel::loadParticipation): a diagnostic
  // costing one sparse factorization per channel at build time, cached bases or not (75 % of a
  // cached start). Off by default: channels then report −1. `myoshell run --diagnostics` and
  // `myoshell bench --diagnostics` turn it on (docs/PERFORMANCE.md, "Start-up").
  bool measureLoadParticipation = false;
  std::vector<DragDef> drags;         // drag channels
  ModalPrecision precision = ModalPrecision::Float;

  void validate() const;              // InputError naming the field
};

// One muscle with everything precomputed for it.
struct MuscleUnit {
  Muscle muscle;
  std::shared_ptr<const DiscreteShell> shell;  // the muscle shell (rest state, K, M)
  std::shared_ptr<const ModalBasis> basis;   // its single stretch mode over the non-origin nodes
  // Which of the muscleModes modes was kept (eq. 12), and the share of the activation load's static
  // compliance that mode carries (METHOD.md §2.5); index −1 = the static-shape variant was used
  // because no low mode carried the load.
  int stretchModeIndex = -1;
  double stretchParticipation = 0.0;
  std::vector<double> modeParticipation;     // per computed mode
  double maxForce = 0.0;                     // dyn per central node at a = 1 (calibrated)
  double fullAmplitude = 0.0;                // its static modal amplitude q_m at a = 1 (linear)
  std::vector<int> centralFreeRows;          // rows of the central nodes in the basis's free fields
  // Springs (eq. 14–16): muscle node → its nearest skin node.
  struct Spring {
    int muscleNode = -1;       // vertex of the muscle mesh
    int muscleFreeRow = -1;    // its row in the muscle basis's free fields (−1: an origin node)
    int skinVertex = -1;       // nearest skin vertex
    int skinFreeRow = -1;      // its row in the skin channel's free fields
    Vec3 restVector = Vec3::Zero();  // S_init: from the skin node to the muscle node at rest, cm
  };
  std::vector<Spring> springs;
  double springStiffness = 0.0;  // dyn
  double roiAlpha = 0.0;
  std::vector<int> roi;          // skin vertices of the ROI (sorted): the skin channel's free set
  int skinChannel = -1;          // index into FaceModel::channels()
};

// The subcutaneous springs' pull (thesis eq. 14–16) of one muscle on its skin channel: adds, for each
// spring, the force on its skin node to `channelForce` (the channel's free f×3 field, dyn), given
// the muscle's free displacement `muscleU` (its basis's f×3, cm). Returns whether any force was
// added. Allocates nothing.
bool addSpringForces(const MuscleUnit& unit, const MatX3& muscleU, SpringModel model, MatX3& channelForce);

enum class ChannelKind { Muscle, Gravity, Drag };

// One independent skin system of the force decomposition (thesis eq. 20–25).
struct SkinChannel {
  std::string name;
  ChannelKind kind = ChannelKind::Muscle;
  int source = -1;                          // muscle index or drag index
  std::shared_ptr<const ModalBasis> basis;  // over this channel's free skin vertices
  double loadParticipation = 0.0;           // of its typical load (springs / gravity / drag); −1: not measured
  std::vector<int> dragRows;                // Drag: free rows that share the force
};

class FaceModel : public FaceSystem {
 public:
  // Builds everything: muscles from `muscles` on `head`, their modes and springs, ROIs, and the
  // skin channels (one per muscle, gravity if enabled, one per drag). Throws InputError for bad
  // settings or muscles, NumericalError if an eigen-solve fails.
  FaceModel(Head head, const std::vector<MuscleDef>& muscles, const FaceModelSettings& settings,
            BasisCache* cache = nullptr);

  const Head& head() const override { return head_; }
  const FaceModelSettings& settings() const { return settings_; }
  const DiscreteShell& skin() const { return skin_; }
  const std::vector<MuscleUnit>& muscles() const { return muscles_; }
  const std::vector<SkinChannel>& channels() const { return channels_; }
  int muscleIndex(const std::string& name) const override;  // throws InputError naming the unknown muscle
  int gravityChannel() const { return gravityChannel_; }  // −1 when disabled
  // The gravity channel's pins (and the default pins of drag channels), sorted.
  std::vector<int> gravityPins() const;
  double buildSeconds() const override { return buildSeconds_; }
  int cacheHits() const override { return cacheHits_; }

  // FaceSystem: the thesis model.
  FaceModelKind kind() const override { return FaceModelKind::Thesis; }
  double dt() const override { return settings_.dt; }
  int muscleCount() const override { return static_cast<int>(muscles_.size()); }
  const std::string& muscleName(int m) const override { return muscles_[static_cast<size_t>(m)].muscle.def.name; }
  const TriMesh& muscleMesh(int m) const override { return muscles_[static_cast<size_t>(m)].muscle.mesh; }
  double minActivation() const override { return -1.0; }
  std::vector<std::string> channelNames() const override;
  bool hasGravity() const override { return gravityChannel_ >= 0; }
  const std::vector<DragDef>& drags() const override { return settings_.drags; }
  std::vector<int> pinnedVertices() const override { return gravityPins(); }
  std::unique_ptr<FaceStepper> makeStepper(std::shared_ptr<const FaceSystem> self) const override;

 private:
  Head head_;
  FaceModelSettings settings_;
  DiscreteShell skin_;
  std::vector<MuscleUnit> muscles_;
  std::vector<SkinChannel> channels_;
  int gravityChannel_ = -1;
  double buildSeconds_ = 0.0;
  int cacheHits_ = 0;
};

}  // namespace myo
