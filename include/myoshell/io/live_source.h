// A tracker's live stream (docs/live.md): a UDP socket, a receiver thread that decodes each packet
// (io/live_packets.h) and keeps only the newest complete frame, time-stamped on arrival; the frame
// loop takes the newest once per step. No queue: a consumer that is slower than the sender skips
// to the present (the frames it never saw are counted as superseded), it never falls behind.
//
// LiveFaceInput turns what was taken into the weights to play: dropped packets hold the last
// frame; after `timeout` s of silence the face eases to neutral over `easeSeconds`; a neutral
// calibration subtracts the performer's resting weights (their mean over the first seconds).
// Every time comes from an injectable clock (s), so tests never sleep.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "myoshell/anim/performance.h"
#include "myoshell/io/live_packets.h"

namespace myo {

enum class LiveProtocol { Vmc, LiveLink };

// "vmc", "livelink"; InputError naming both otherwise.
LiveProtocol liveProtocolFromString(const std::string& name);
const char* toString(LiveProtocol protocol);
int defaultLivePort(LiveProtocol protocol);  // VMC 39539, Live Link Face 11111

using LiveClock = std::function<double()>;  // s, monotonic
LiveClock steadyLiveClock();

struct LiveSourceOptions {
  LiveProtocol protocol = LiveProtocol::Vmc;
  std::string address = "127.0.0.1";  // the interface to listen on: 127.0.0.1, 0.0.0.0 (any), …
  int port = 0;                       // 0: an ephemeral port (ask port() which)
  LiveClock clock;                    // stamps arrivals; empty: steadyLiveClock()
  // Lockstep (`myoshell send --lockstep`): after each frame taken, a one-byte datagram back to its
  // sender, which waits for it before sending the next; so no frame is superseded.
  bool acknowledge = false;
};

struct LiveCounters {
  long packets = 0;     // datagrams received
  long frames = 0;      // complete frames decoded
  long malformed = 0;   // dropped: could not be decoded (the last reason in LiveSource::lastMalformed)
  long dropped = 0;     // Live Link: frames the sender numbered that never arrived (a gap in its frame numbers)
  long superseded = 0;  // complete frames replaced by a newer one before the consumer took them
  long taken = 0;       // frames the consumer took
  long ignored = 0;     // well-formed packets nothing uses (unknown OSC addresses, other bones)
};

struct LiveSample {
  LiveFrame frame;
  double arrival = 0.0;  // s on the source's clock
  long sequence = 0;     // 1, 2, … in order of arrival of complete frames
};

class LiveSource {
 public:
  // Binds the socket and starts the receiver thread. InputError "port P on ADDRESS is in use
  // (another receiver is listening; choose another port)" or naming the address that cannot be
  // bound.
  explicit LiveSource(LiveSourceOptions options);
  ~LiveSource();
  LiveSource(const LiveSource&) = delete;
  LiveSource& operator=(const LiveSource&) = delete;

  int port() const { return port_; }  // the bound port (the ephemeral one when asked for 0)
  LiveProtocol protocol() const { return options_.protocol; }

  // The newest complete frame not yet taken, or nothing (no new frame since the last take).
  std::optional<LiveSample> takeNewest();
  LiveCounters counters() const;
  std::string lastMalformed() const;           // the reason the last malformed packet was dropped
  std::vector<std::string> unknownNames() const;  // VMC blend names that mean nothing (warned once)

  // Waits until `packets` datagrams have been received (or any complete frame is waiting, when
  // `frame`) or `timeoutSeconds` of wall time pass; true when reached. For tests and lockstep,
  // which must not sleep a fixed time.
  bool waitForPackets(long packets, double timeoutSeconds) const;
  bool waitForFrame(double timeoutSeconds) const;

  void stop();  // ends the thread (the destructor does too)

 private:
  void receive();
  LiveSourceOptions options_;
  int socket_ = -1;
  int port_ = 0;
  std::thread thread_;
  std::atomic<bool> stopping_{false};
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  LiveCounters counters_;
  std::optional<LiveSample> newest_;
  std::string lastMalformed_;
  std::vector<std::string> unknownNames_;
  std::optional<std::int32_t> lastSenderFrame_;
  // Where the newest frame came from (for the lockstep acknowledgement).
  std::vector<std::uint8_t> newestSender_;
};

struct LiveFaceSettings {
  double timeout = 0.5;      // s without a new frame before the face eases to neutral
  double easeSeconds = 0.5;  // s the ease to neutral takes (smoothstep)
  double calibrateSeconds = 0.0;  // s from the first frame whose mean weights are the resting face
};

// What the face plays at time `now` (s, the source's clock): the last frame taken (minus the
// resting weights, clamped at 0), eased towards neutral (weights 0, head level, eyes ahead) once
// the stream is silent for longer than the timeout. Neutral before the first frame and during the
// calibration.
class LiveFaceInput {
 public:
  explicit LiveFaceInput(LiveFaceSettings settings = {});
  // A frame taken from the source (its arrival time on the same clock as `now`).
  void receive(const LiveSample& sample);
  LiveFrame at(double now) const;
  bool calibrating(double now) const;
  // The resting weights (ARKit order); zero until the calibration ends.
  const std::array<double, kArkitWeightCount>& rest() const { return rest_; }
  // 1 while the stream is live, falling to 0 over the ease after the timeout.
  double liveness(double now) const;
  // Captures the resting face again, now (the viewer's "Calibrate neutral"): the frames arriving
  // in [now, now + seconds] are the new resting weights (their mean; zero when none arrives); the
  // face is neutral meanwhile, as during the first calibration. InputError for seconds not > 0.
  void startCalibration(double now, double seconds);

 private:
  LiveFaceSettings settings_;
  std::optional<LiveSample> last_;
  // When the calibration's window opens (s): the first arrival, or startCalibration's `now`.
  std::optional<double> calibrationStart_;
  std::array<double, kArkitWeightCount> restSum_{};
  long restCount_ = 0;
  std::array<double, kArkitWeightCount> rest_{};
  bool restDone_ = false;
};

// A recorded performance of ARKit weights (Live Link CSV, MediaPipe) as the frames a tracker would
// stream, at `rate` frames per second (linear between the recording's frames: weights, head angles,
// eye angles), or at the recording's own frames when `rate` is 0. `times` gets each frame's time
// (s from 0). InputError naming `what` for OpenFace input: these protocols carry ARKit weights,
// not FACS action units.
std::vector<LiveFrame> liveFramesOfPerformance(const Performance& performance, double rate, std::vector<double>& times,
                                               const std::string& what);

// The sending end (`myoshell send`): a UDP socket to HOST:PORT. InputError naming the host when it
// does not resolve.
class LiveSender {
 public:
  LiveSender(const std::string& host, int port);
  ~LiveSender();
  LiveSender(const LiveSender&) = delete;
  LiveSender& operator=(const LiveSender&) = delete;
  void send(const std::vector<std::uint8_t>& packet);
  // Waits for the receiver's lockstep acknowledgement; false after `timeoutSeconds`.
  bool waitForAcknowledgement(double timeoutSeconds);

 private:
  int socket_ = -1;
  std::string where_;
};

}  // namespace myo
