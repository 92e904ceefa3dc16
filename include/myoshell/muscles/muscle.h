// A muscle as the thesis builds it (section IV.B, V.A): a closed thin shell placed under the skin,
// its origin ring pinned to the skull (static position constraints), contracted or relaxed by a
// tangential force on its central nodes (Figure 12).
#pragma once

#include <array>
#include <vector>

#include "myoshell/head/head.h"
#include "myoshell/mesh/closest_point.h"
#include "myoshell/mesh/tri_mesh.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {

struct Muscle {
  MuscleDef def;
  // The closed shell: stations × ringNodes vertices (station-major: vertex s·ringNodes + k), cm, in
  // the head's space; 2·V − 4 triangles (36 nodes → 68 triangles, 102 edges, as the thesis's Table 1).
  TriMesh mesh;
  std::vector<int> originNodes;   // pinned: the whole origin ring (two non-collinear rows, top and bottom)
  std::vector<int> centralNodes;  // where the activation force acts: the ring's top and bottom middle nodes
  std::vector<int> insertionNodes;  // the moving end (the last ring), whose motion calibrates the force
  // Per central node, the unit direction of a contracting force (along the muscle's centre line,
  // towards the origin), cm-free; relaxation pushes the other way.
  MatX3 contractDirection;
  Vec3 originPoint = Vec3::Zero();     // centre of the origin ring, cm
  Vec3 insertionPoint = Vec3::Zero();  // centre of the insertion ring, cm
  double restLength = 0.0;             // length of the centre line, cm (a loop's all round)
  Vec3 ringCentre = Vec3::Zero();      // a ring muscle's centre (its anchors' midpoint under the skin), cm
  Vec3 pushPoint = Vec3::Zero();       // def.pushes's point on the skin, cm (MuscleDef::pushes)
  Vec3 continuePoint = Vec3::Zero();   // def.continuesInto's point under the skin, cm (MuscleDef::continuesInto)
  Vec3 hoopCentre = Vec3::Zero();      // a hoop ring's arch centre of curvature, cm (MuscleDef::Ring::hoop)
  // A hoop ring's two anchors on the skin (the modioli its band's ends are held at), cm.
  std::array<Vec3, 2> hoopEnds{Vec3::Zero(), Vec3::Zero()};
  // The station (ring of the tube) of a generated muscle's node: node s·ringNodes + k.
  int stationOf(int node) const { return node / def.ringNodes; }
  int insertionCentre(int k = 0) const;  // a vertex of the insertion ring (k in [0, ringNodes))
};

// Builds a muscle on a head from its definition. An imported muscle takes its shell (def.shell, read
// by io) as it is, with its node sets; the contraction direction of a central node points to the origin nodes' centroid.
// A generated muscle: the centre line runs from the origin anchor to the
// insertion anchor, each station is pushed under the skin along the skin normal at an interpolated
// depth, and a flat elliptic ring (width × thickness) is placed across it; the ends are closed
// with fans. Throws InputError naming the muscle when a landmark is missing or the anchors coincide.
// TubeOrientation::MirrorRightSide: a right-side muscle's rings run the other way round, so that its tube is the
// exact mirror image of its left twin's, node for node and triangle for triangle (the anatomical
// model: pairs act symmetrically on a symmetric head); false keeps the thesis model's tubes.
// `skin`, when given, is a SurfaceLocator over head.mesh (with its vertex normals) that answers the
// closest-point queries: the same muscle, built faster when many muscles share one locator.
enum class TubeOrientation { Thesis, MirrorRightSide };
Muscle buildMuscle(const MuscleDef& def, const Head& head, TubeOrientation orientation = TubeOrientation::Thesis,
                   const SurfaceLocator* skin = nullptr);

}  // namespace myo
