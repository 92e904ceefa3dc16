// What the eyelid tests measure on any head (eyelids_test.cpp on ICT, eyelids_default_head_test.cpp
// on the built-in head): a settled, placed shape at a few activations, how deep skin lies inside an
// eyeball, and how far a right-eye motion is from the mirror image of the left one.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <memory>

#include "myoshell/anatomy/anatomical_face.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/muscles/muscle_def.h"
#include "support/basis_cache.h"

namespace myo::test {

// The static shape of `face` at these activations (the rest zero), gravity as at rest, settled as
// the skin's settings say (warped or not) and placed with AnatomicalFace::placeSkin (the jaw at
// rest, then the lids and the eyeballs' contact): positions n×3, cm. `converged` and `contact`, when
// given, get whether the settle converged and what the contact did.
inline MatX3 settledPlacedShape(const AnatomicalFace& face, const std::vector<std::pair<std::string, double>>& acts,
                                bool* converged = nullptr, ContactReport* contact = nullptr) {
  const AnatomicalSkin& skin = face.skin();
  SkinLoads loads;
  loads.activations = VecX::Zero(face.muscleCount());
  for (const auto& [name, a] : acts) loads.activations(skin.muscleIndex(name)) = a;
  loads.gravity = skin.restGravity();
  const SettledSkin s = skin.settle(loads, skin.settings().warping);
  if (converged) *converged = s.converged;
  MatX3 out;
  const ContactReport c = face.placeSkin(s.u, JawPose{}, loads.activations, out);
  if (contact) *contact = c;
  return out;
}

// The eye's muscles swept for contact: palpebral 0 / 0.5 / 1 × levator 0 / 1 × the orbital part and
// the corrugator together 0 / 1, both sides alike (12 sets of activations).
inline std::vector<std::vector<std::pair<std::string, double>>> eyeMuscleSweep() {
  std::vector<std::vector<std::pair<std::string, double>>> sweep;
  for (double palpebral : {0.0, 0.5, 1.0})
    for (double levator : {0.0, 1.0})
      for (double orbital : {0.0, 1.0})
        sweep.push_back({{"orbicularis_oculi_palpebral_left", palpebral},
                         {"orbicularis_oculi_palpebral_right", palpebral},
                         {"levator_palpebrae_superioris_left", levator},
                         {"levator_palpebrae_superioris_right", levator},
                         {"orbicularis_oculi_orbital_left", orbital},
                         {"orbicularis_oculi_orbital_right", orbital},
                         {"corrugator_supercilii_left", orbital},
                         {"corrugator_supercilii_right", orbital}});
  return sweep;
}

// The deepest an orbit vertex of P (n×3, cm) lies inside its eyeball's contact sphere (cm; ≤ 0 outside).
inline double deepestInsideEyeball(const LidRig& rig, const MatX3& P) {
  double worst = -1.0;
  for (const EyeLids& e : rig.eyes)
    for (int i : e.orbitVertices) worst = std::max(worst, e.contactRadius - (P.row(i).transpose() - e.centre).norm());
  return worst;
}

// For a head symmetric about x = 0: each vertex's mirror image, the vertex nearest (−x, y, z), and
// the largest distance (cm) from such an image to its nearest vertex (round-off on a symmetric mesh).
struct MirrorMap {
  std::vector<int> mirror;
  double worstDistance = 0.0;
};
inline MirrorMap mirrorMap(const MatX3& V) {
  MirrorMap m;
  m.mirror.resize(static_cast<size_t>(V.rows()));
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::RowVector3d image(-V(i, 0), V(i, 1), V(i, 2));
    Eigen::Index j = 0;
    const double d2 = (V.rowwise() - image).rowwise().squaredNorm().minCoeff(&j);
    m.mirror[static_cast<size_t>(i)] = static_cast<int>(j);
    m.worstDistance = std::max(m.worstDistance, std::sqrt(d2));
  }
  return m;
}

// The largest difference (cm) between the displacement uL (n×3) and the mirror image of uR.
inline double mirrorMismatch(const MirrorMap& m, const MatX3& uL, const MatX3& uR) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < uL.rows(); ++i) {
    const Eigen::RowVector3d r = uR.row(m.mirror[static_cast<size_t>(i)]);
    worst = std::max(worst, (uL.row(i) - Eigen::RowVector3d(-r(0), r(1), r(2))).norm());
  }
  return worst;
}

// `face`'s rest placed at `gaze` (no muscle acting): positions n×3, cm.
inline MatX3 gazedPlacement(const AnatomicalFace& face, const EyeGaze& gaze) {
  MatX3 out;
  face.placeSkin(MatX3::Zero(face.head().mesh.vertexCount(), 3), JawPose{}, VecX::Zero(face.muscleCount()), out, gaze);
  return out;
}

// A suite's one whole-face model (every muscle of faceMuscleDefs(), gravity off) on the head
// `makeHead` returns, built once for all its tests (bases through the shared cache; the suite runs in
// one process: tests/CMakeLists.txt, ONE_PROCESS), and the placed shapes the tests measure. A suite
// derives from it and calls build() from its SetUp (after skipping when its data is absent).
template <Head (*makeHead)()>
class WholeFaceSuite : public ::testing::Test {
 protected:
  static void build() {
    if (!face_)
      face_ = std::make_shared<const AnatomicalFace>(makeHead(), faceMuscleDefs(), AnatomicalSettings{},
                                                     std::vector<DragDef>{}, false, sharedBasisCache());
  }
  static void TearDownTestSuite() { face_.reset(); }
  // The settled, placed shape at these activations (settledPlacedShape), the settle asserted converged.
  static MatX3 pose(const std::vector<std::pair<std::string, double>>& acts, ContactReport* contact = nullptr) {
    bool converged = false;
    MatX3 P = settledPlacedShape(*face_, acts, &converged, contact);
    EXPECT_TRUE(converged);
    return P;
  }
  static const MatX3& rest() { return face_->head().mesh.V; }
  static const LidRig& lids() { return *face_->lidRig(); }
  static inline std::shared_ptr<const AnatomicalFace> face_;
};

}  // namespace myo::test
