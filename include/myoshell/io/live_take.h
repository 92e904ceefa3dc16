// A live take (`myoshell live`, docs/live.md): the frames a tracker streams, mapped onto a scene's
// muscles by the same path a recorded take goes (anim/performance_map.h's mapPerformance with the
// scene's maps, io/scene_face.h), and recorded as they arrive to a Live Link Face CSV that `drive`
// replays.
#pragma once

#include <array>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "myoshell/anim/one_euro_filter.h"
#include "myoshell/anim/performance_map.h"
#include "myoshell/anim/scene.h"
#include "myoshell/head/face_system.h"
#include "myoshell/io/live_packets.h"
#include "myoshell/io/scene_face.h"

namespace myo {

// Maps one live frame at a time: each input curve (the weights, the head's and the eyes' angles)
// through its own One-Euro filter (OneEuroStream: drive's formula, sample by sample), then through
// mapPerformance as a one-frame take, so the maps, the FACS fallback, the clamps and the eyes' rule
// are drive's own.
class LiveFaceMapper {
 public:
  // `scene`: its muscles and scene.performance.map (scenePerformanceMapping); `filter`: drive's.
  LiveFaceMapper(const SceneDesc& scene, const OneEuroSettings& filter);
  // The frame at time t (s, increasing), mapped: activations[m][0] per muscle of muscles(), the jaw,
  // the gaze and the head pose each with one entry or none.
  MappedPerformance map(double t, const LiveFrame& frame);
  const std::vector<std::string>& muscles() const { return mapping_.muscles; }
  // Each of muscles()' index in `model` (−1 for one the model lacks): apply()'s `muscleIndex`.
  std::vector<int> muscleIndex(const FaceSystem& model) const;
  // Applies a mapped frame to a stepper as the scene player applies a timeline: every muscle's
  // activation (by name), the jaw, the gaze, the head's rotation (which turns gravity).
  static void apply(const MappedPerformance& mapped, const std::vector<int>& muscleIndex, FaceStepper& stepper);

 private:
  ScenePerformanceMapping mapping_;
  OneEuroSettings filter_;
  std::array<OneEuroStream, kArkitWeightCount> weightFilters_;
  std::array<OneEuroStream, 3> headFilters_;
  std::array<OneEuroStream, 4> gazeFilters_;
  double lastTime_ = -1e300;
};

// A live take's frames as the face played them, written as they are played: a Live Link Face CSV
// (Timecode at `fps` frames per second with a six-digit sub-frame, BlendShapeCount 61, the 52
// weights in Live Link's order, the head's and, when `eyes`, the eyes' angles as degrees / 180).
// Each row is flushed, so a take cut short (Ctrl-C, a crash) keeps every frame played. IoError
// when the file cannot be written.
class LiveTakeRecorder {
 public:
  LiveTakeRecorder(const std::string& path, bool eyes, double fps);
  // Writes the frame at t s after the take's start (increasing) and returns it as the file holds
  // it, read back as `drive` reads it (nine significant digits, weights clamped, a head pose of 0
  // when the frame had none, the eyes' when `eyes`): what the face plays, so a replay is exact.
  LiveFrame write(double t, const LiveFrame& frame);
  int rows() const { return rows_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
  bool eyes_;
  double fps_;
  std::array<size_t, kArkitWeightCount> arkitOfColumn_{};  // Live Link's weight column → ARKit index
  int rows_ = 0;
};

// The scene that replays a live take (DIR/replay.json, `myoshell run` plays it): the live scene
// (head, muscles, map, response) with the recording `recording` (relative to the scene's folder)
// as its performance: Live Link at `fps` (the recorder's timecode rate), the live `filter`, each
// frame held until the next (Interpolation::Step), as the live loop played it.
SceneDesc liveReplayScene(const SceneDesc& live, const std::string& recording, double fps, const OneEuroSettings& filter);

}  // namespace myo
