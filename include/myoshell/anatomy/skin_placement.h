// Placing a shape on its head (docs/jaw.md, docs/eyelids.md, docs/mouth_contact.md): the skin's
// residual u (the physics' displacement, in the rest frame) becomes positions by the jaw, the lids
// and the contact projections. Built once per head and muscle list, it is the one placement every
// path uses: the playing face (AnatomicalFace::placeSkin), fits (fitActivations), rigs
// (settleArkitRig) and Python.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "myoshell/anatomy/contact_report.h"
#include "myoshell/anatomy/eyelids.h"
#include "myoshell/anatomy/mouth_contact.h"
#include "myoshell/core/types.h"
#include "myoshell/head/head.h"
#include "myoshell/head/jaw.h"

namespace myo {

class SkinPlacement {
 public:
  // The jaw and the mouth's contact of a head with the 68 landmarks; the lids of a head with open
  // eyes (hasOpenEyes), driven by the lid muscles among `muscleNames` (the activations' order).
  // `contact` false: place() turns with the jaw and the lids but projects nothing (it still reports
  // the deepest violation): the shape without contact (the scene's "contact": "off", pose --contact).
  SkinPlacement(const Head& head, const std::vector<std::string>& muscleNames, bool contact = true);

  const JawRig* jaw() const { return jaw_ ? &*jaw_ : nullptr; }
  const LidRig* lids() const { return lids_ ? &*lids_ : nullptr; }
  const MouthContact* mouth() const { return mouth_ ? &*mouth_ : nullptr; }
  // The lids' pose at these activations (lidDrivers); zero where the muscles are absent.
  LidPose lidPose(const VecX& activations) const { return drivers_.pose(activations); }
  // Whether placing is only rest + u (no jaw, no lids, no contact: a head without the 68 landmarks).
  bool isPlain() const { return !jaw_ && !lids_ && !mouth_; }
  // Whether place() projects out of the proxies (the contact switch).
  bool contact() const { return contact_; }
  // Whether the head has anything to touch (eyeballs or teeth).
  bool hasContact() const { return lids_ || mouth_; }
  // Whether muscle m (an index of `muscleNames`) turns a lid of this head.
  bool turnsALid(int m) const { return lids_ && drivers_.drives(m); }

  // Positions (n×3, cm) for the residual u: the jawed rest + u turned with the jaw (jawedPositions;
  // rest + u bit for bit at a zero jaw), then the lids turned by these activations and every orbit
  // vertex kept out of its eyeball proxy (applyLids), then the lips kept out of the teeth and of
  // each other (applyMouthContact). Returns what the contact projections did. InputError-free: a
  // nonzero jaw on a head without one is a CheckError (callers validate the pose first).
  ContactReport place(const MatX3& u, const JawPose& jaw, const VecX& activations, MatX3& out) const {
    return place(u, jaw, activations, out, contact_);
  }
  // The same with the projection on or off whatever the switch says (`project`), and the lids
  // following the eyes' turn `gaze` (eyelids.h; nothing on a head without lids).
  ContactReport place(const MatX3& u, const JawPose& jaw, const VecX& activations, MatX3& out, bool project,
                      const EyeGaze& gaze = {}) const;

 private:
  MatX3 rest_;
  std::optional<JawRig> jaw_;
  std::optional<LidRig> lids_;
  std::optional<MouthContact> mouth_;
  LidDrivers drivers_;
  bool contact_ = true;
};

}  // namespace myo
