#include "myoshell/anim/scene_playback.h"

namespace myo {

void applySceneTimeline(const SceneDesc& scene, Simulator& sim, double t) {
  const FaceModel& model = sim.model();
  for (const auto& [name, track] : scene.activations) sim.setActivation(model.muscleIndex(name), track.at(t));
  if (model.gravityChannel() >= 0 && !scene.gravity.empty()) sim.setGravity(scene.gravity.at(t));
  for (size_t d = 0; d < scene.drags.size(); ++d) {
    auto it = scene.dragForces.find(scene.drags[d].name);
    if (it != scene.dragForces.end()) sim.setDragForce(static_cast<int>(d), it->second.at(t));
  }
}

void playSceneTo(const SceneDesc& scene, Simulator& sim, double t) {
  const double dt = sim.model().settings().dt;
  while (sim.time() < t - 0.5 * dt) {
    applySceneTimeline(scene, sim, sim.time());
    sim.step();
  }
}

}  // namespace myo
