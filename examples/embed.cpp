// Using Myoshell from another program: load the built-in head, contract a muscle, step, read the
// skin's positions. Built against an installed Myoshell (find_package(Myoshell)).
#include <cstdio>
#include <memory>

#include "myoshell/thesis/face_model.h"
#include "myoshell/thesis/simulator.h"

int main() {
  using namespace myo;
  FaceModelSettings settings;
  settings.skinModes = 10;   // a small basis: this is a demonstration
  settings.gravity = false;
  std::vector<MuscleDef> muscles;
  for (const MuscleDef& def : thesisMuscleDefs())
    if (def.name == "zygomaticus_major_left") muscles.push_back(def);
  auto model = std::make_shared<const FaceModel>(loadDefaultHead(), muscles, settings);

  Simulator sim(model);
  sim.setActivation("zygomaticus_major_left", 1.0);  // a smile on the subject's left
  sim.advance(0.5);                                   // seconds, in steps of settings.dt

  const MatX3 x = sim.skinPositions();  // n×3, cm, the head's own vertex order
  const int corner = model->head().landmarks.vertex("mouth_corner_left");
  const Vec3 moved = x.row(corner) - model->head().mesh.V.row(corner);
  std::printf("mouth corner moved %.3f cm (up %.3f cm) after %lld steps\n", moved.norm(),
              moved.dot(model->head().frame().axes.col(1)), sim.stepCount());
  return moved.norm() > 0.05 ? 0 : 1;
}
