#include "myoshell/io/live_source.h"

#include <arpa/inet.h>
#include <fmt/core.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

#include "myoshell/core/errors.h"
#include "myoshell/fit/arkit_names.h"

namespace myo {

LiveProtocol liveProtocolFromString(const std::string& name) {
  if (name == "vmc") return LiveProtocol::Vmc;
  if (name == "livelink") return LiveProtocol::LiveLink;
  throw InputError("unknown live input '" + name + "' (use vmc or livelink)");
}

const char* toString(LiveProtocol protocol) { return protocol == LiveProtocol::Vmc ? "vmc" : "livelink"; }

int defaultLivePort(LiveProtocol protocol) { return protocol == LiveProtocol::Vmc ? 39539 : 11111; }

LiveClock steadyLiveClock() {
  return [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
}

namespace {

// An IPv4 address for `address` ("any" and "localhost" too); InputError otherwise.
in_addr ipv4Address(const std::string& address) {
  in_addr out{};
  const std::string a = address == "any" ? "0.0.0.0" : address == "localhost" ? "127.0.0.1" : address;
  if (inet_pton(AF_INET, a.c_str(), &out) != 1)
    throw InputError("cannot listen on '" + address + "' (give an IPv4 address such as 127.0.0.1, or 0.0.0.0 for any)");
  return out;
}

constexpr std::size_t kMaxDatagram = 65536;

}  // namespace

LiveSource::LiveSource(LiveSourceOptions options) : options_(std::move(options)) {
  if (!options_.clock) options_.clock = steadyLiveClock();
  if (options_.port < 0 || options_.port > 65535)
    throw InputError(fmt::format("port {} is outside 0–65535", options_.port));
  sockaddr_in at{};
  at.sin_family = AF_INET;
  at.sin_addr = ipv4Address(options_.address);
  at.sin_port = htons(static_cast<std::uint16_t>(options_.port));
  socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (socket_ < 0) throw InputError(std::string("cannot open a UDP socket: ") + std::strerror(errno));
  // A larger buffer rides out a burst while the consumer steps (the kernel caps it at rmem_max).
  const int buffer = 4 << 20;
  ::setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
  if (::bind(socket_, reinterpret_cast<sockaddr*>(&at), sizeof at) != 0) {
    const int error = errno;
    ::close(socket_);
    socket_ = -1;
    if (error == EADDRINUSE)
      throw InputError(fmt::format("port {} on {} is in use (another receiver is listening; choose another port)",
                                   options_.port, options_.address));
    throw InputError(fmt::format("cannot listen on {}:{}: {}", options_.address, options_.port, std::strerror(error)));
  }
  socklen_t length = sizeof at;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&at), &length);
  port_ = ntohs(at.sin_port);
  thread_ = std::thread([this] { receive(); });
}

LiveSource::~LiveSource() { stop(); }

void LiveSource::stop() {
  stopping_.store(true);
  if (thread_.joinable()) thread_.join();
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
}

void LiveSource::receive() {
  std::vector<std::uint8_t> buffer(kMaxDatagram);
  VmcDecoder vmc;
  while (!stopping_.load()) {
    pollfd wait{socket_, POLLIN, 0};
    // A short poll so stop() is seen promptly without a wake-up pipe.
    if (::poll(&wait, 1, 20) <= 0) continue;
    sockaddr_storage from{};
    socklen_t fromLength = sizeof from;
    const ssize_t n =
        ::recvfrom(socket_, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &fromLength);
    if (n < 0) continue;
    const double arrival = options_.clock();
    const DecodedPacket packet = options_.protocol == LiveProtocol::Vmc
                                     ? vmc.decode(buffer.data(), static_cast<std::size_t>(n))
                                     : decodeLiveLinkPacket(buffer.data(), static_cast<std::size_t>(n));
    {
      std::lock_guard lock(mutex_);
      ++counters_.packets;
      switch (packet.status) {
        case PacketStatus::Malformed:
          ++counters_.malformed;
          lastMalformed_ = packet.reason;
          break;
        case PacketStatus::Ignored: ++counters_.ignored; break;
        case PacketStatus::Incomplete: break;
        case PacketStatus::Frame: {
          ++counters_.frames;
          if (packet.senderFrame) {
            if (lastSenderFrame_ && *packet.senderFrame > *lastSenderFrame_)
              counters_.dropped += *packet.senderFrame - *lastSenderFrame_ - 1;
            lastSenderFrame_ = packet.senderFrame;
          }
          if (newest_) ++counters_.superseded;
          newest_ = LiveSample{packet.frame, arrival, counters_.frames};
          newestSender_.assign(reinterpret_cast<const std::uint8_t*>(&from),
                               reinterpret_cast<const std::uint8_t*>(&from) + fromLength);
          break;
        }
      }
      if (options_.protocol == LiveProtocol::Vmc && vmc.unknownNames().size() != unknownNames_.size())
        unknownNames_ = vmc.unknownNames();
    }
    arrived_.notify_all();
  }
}

std::optional<LiveSample> LiveSource::takeNewest() {
  std::optional<LiveSample> out;
  std::vector<std::uint8_t> sender;
  {
    std::lock_guard lock(mutex_);
    if (!newest_) return out;
    out.swap(newest_);
    ++counters_.taken;
    sender.swap(newestSender_);
  }
  if (options_.acknowledge && !sender.empty()) {
    const std::uint8_t ack = 1;
    ::sendto(socket_, &ack, 1, 0, reinterpret_cast<const sockaddr*>(sender.data()),
             static_cast<socklen_t>(sender.size()));
  }
  return out;
}

LiveCounters LiveSource::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

std::string LiveSource::lastMalformed() const {
  std::lock_guard lock(mutex_);
  return lastMalformed_;
}

std::vector<std::string> LiveSource::unknownNames() const {
  std::lock_guard lock(mutex_);
  return unknownNames_;
}

bool LiveSource::waitForPackets(long packets, double timeoutSeconds) const {
  std::unique_lock lock(mutex_);
  return arrived_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds),
                           [&] { return counters_.packets >= packets; });
}

bool LiveSource::waitForFrame(double timeoutSeconds) const {
  std::unique_lock lock(mutex_);
  return arrived_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds), [&] { return newest_.has_value(); });
}

// ---- LiveFaceInput ----

LiveFaceInput::LiveFaceInput(LiveFaceSettings settings) : settings_(settings) {
  if (!(settings_.timeout >= 0) || !(settings_.easeSeconds >= 0) || !(settings_.calibrateSeconds >= 0))
    throw InputError("live input: the timeout, the ease and the calibration must be finite and ≥ 0 s");
  restDone_ = settings_.calibrateSeconds == 0.0;
}

void LiveFaceInput::receive(const LiveSample& sample) {
  if (!calibrationStart_) calibrationStart_ = sample.arrival;
  if (!restDone_) {
    if (sample.arrival - *calibrationStart_ <= settings_.calibrateSeconds) {
      for (int k = 0; k < kArkitWeightCount; ++k) restSum_[k] += sample.frame.weights[k];
      ++restCount_;
    } else {
      for (int k = 0; k < kArkitWeightCount; ++k) rest_[k] = restCount_ ? restSum_[k] / restCount_ : 0.0;
      restDone_ = true;
    }
  }
  last_ = sample;
}

bool LiveFaceInput::calibrating(double now) const {
  return !restDone_ && (!calibrationStart_ || now - *calibrationStart_ <= settings_.calibrateSeconds);
}

void LiveFaceInput::startCalibration(double now, double seconds) {
  if (!(std::isfinite(seconds) && seconds > 0))
    throw InputError("live input: the calibration must last a finite time > 0 s");
  settings_.calibrateSeconds = seconds;
  calibrationStart_ = now;
  restSum_.fill(0.0);
  restCount_ = 0;
  restDone_ = false;  // the old rest is kept until the new one is known; the face is neutral meanwhile
}

double LiveFaceInput::liveness(double now) const {
  if (!last_) return 0.0;
  const double silent = now - last_->arrival - settings_.timeout;
  if (silent <= 0) return 1.0;
  if (settings_.easeSeconds <= 0 || silent >= settings_.easeSeconds) return 0.0;
  const double s = silent / settings_.easeSeconds;
  return 1.0 - s * s * (3.0 - 2.0 * s);  // smoothstep: no jolt when the ease starts or ends
}

LiveFrame LiveFaceInput::at(double now) const {
  LiveFrame out;
  if (!last_ || !restDone_) return out;
  const double live = liveness(now);
  for (int k = 0; k < kArkitWeightCount; ++k)
    out.weights[k] = live * std::max(0.0, last_->frame.weights[k] - rest_[k]);
  if (last_->frame.headPose) out.headPose = live * *last_->frame.headPose;
  if (last_->frame.gaze) {
    EyeGaze g = *last_->frame.gaze;
    for (size_t e = 0; e < 2; ++e) {
      g.pitchDeg[e] *= live;
      g.yawDeg[e] *= live;
    }
    out.gaze = g;
  }
  return out;
}

// ---- a recording as a stream ----

std::vector<LiveFrame> liveFramesOfPerformance(const Performance& p, double rate, std::vector<double>& times,
                                               const std::string& what) {
  if (p.input == PerformanceInput::OpenFace)
    throw InputError("OpenFace action units cannot be sent: VMC and Live Link Face carry ARKit blendshape weights, "
                     "not FACS action units (play the file with `myoshell drive`)",
                     what);
  if (!(rate >= 0) || !std::isfinite(rate)) throw InputError("--rate must be a finite number ≥ 0");
  const auto& names = arkitNames();
  std::vector<int> index;  // per channel, its ARKit index
  for (const PerformanceChannel& c : p.channels)
    index.push_back(static_cast<int>(std::find(names.begin(), names.end(), c.name) - names.begin()));
  auto frameAt = [&](size_t i) {
    LiveFrame f;
    for (size_t c = 0; c < p.channels.size(); ++c)
      if (index[c] < kArkitWeightCount) f.weights[index[c]] = p.channels[c].values[i];
    if (!p.headPose.empty()) f.headPose = p.headPose[i];
    if (!p.gaze.empty()) f.gaze = p.gaze[i];
    return f;
  };
  std::vector<LiveFrame> frames;
  times.clear();
  if (rate == 0.0) {
    for (size_t i = 0; i < p.times.size(); ++i) {
      frames.push_back(frameAt(i));
      times.push_back(p.times[i]);
    }
    return frames;
  }
  const long count = static_cast<long>(std::floor(p.duration() * rate + 1e-9)) + 1;
  size_t i = 0;
  for (long k = 0; k < count; ++k) {
    const double t = k / rate;
    while (i + 2 < p.times.size() && p.times[i + 1] <= t) ++i;
    const double s = std::clamp((t - p.times[i]) / (p.times[i + 1] - p.times[i]), 0.0, 1.0);
    const LiveFrame a = frameAt(i), b = frameAt(i + 1);
    LiveFrame f = a;
    for (int w = 0; w < kArkitWeightCount; ++w) f.weights[w] = (1 - s) * a.weights[w] + s * b.weights[w];
    if (a.headPose) f.headPose = (1 - s) * *a.headPose + s * *b.headPose;
    if (a.gaze)
      for (size_t e = 0; e < 2; ++e) {
        f.gaze->pitchDeg[e] = (1 - s) * a.gaze->pitchDeg[e] + s * b.gaze->pitchDeg[e];
        f.gaze->yawDeg[e] = (1 - s) * a.gaze->yawDeg[e] + s * b.gaze->yawDeg[e];
      }
    frames.push_back(f);
    times.push_back(t);
  }
  return frames;
}

// ---- LiveSender ----

LiveSender::LiveSender(const std::string& host, int port) : where_(fmt::format("{}:{}", host, port)) {
  if (port <= 0 || port > 65535) throw InputError(fmt::format("port {} is outside 1–65535", port));
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  if (::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0 || !found)
    throw InputError("cannot resolve host '" + host + "'");
  socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  const bool connected = socket_ >= 0 && ::connect(socket_, found->ai_addr, found->ai_addrlen) == 0;
  ::freeaddrinfo(found);
  if (!connected) throw InputError("cannot send to " + where_ + ": " + std::strerror(errno));
}

LiveSender::~LiveSender() {
  if (socket_ >= 0) ::close(socket_);
}

void LiveSender::send(const std::vector<std::uint8_t>& packet) {
  // A refused datagram (nobody listening yet: ECONNREFUSED from an earlier one) is the network's
  // loss, as with any UDP sender; the stream goes on.
  (void)::send(socket_, packet.data(), packet.size(), 0);
}

bool LiveSender::waitForAcknowledgement(double timeoutSeconds) {
  pollfd wait{socket_, POLLIN, 0};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    if (::poll(&wait, 1, static_cast<int>(left.count())) > 0) {
      std::uint8_t ack = 0;
      if (::recv(socket_, &ack, 1, 0) == 1) return true;
    }
  }
}

}  // namespace myo
