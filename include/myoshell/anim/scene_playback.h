// Playing a scene's timeline on a simulator: what `myoshell run`, `bench` and `figures` share.
#pragma once

#include "myoshell/anim/scene.h"
#include "myoshell/face/simulator.h"

namespace myo {

// Applies the scene's timeline at time t (s): every activation track, the gravity scale (when the
// model has a gravity channel and the scene a gravity track) and every drag force track.
void applySceneTimeline(const SceneDesc& scene, Simulator& sim, double t);

// Steps `sim`, applying the timeline before every step, until its time reaches t (s) to within
// half a step.
void playSceneTo(const SceneDesc& scene, Simulator& sim, double t);

}  // namespace myo
