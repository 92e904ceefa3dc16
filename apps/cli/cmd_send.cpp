// `myoshell send FILE --to vmc|livelink [HOST:PORT] [--rate HZ] [--lockstep] [--input …] [--json]`:
// replays a recorded performance of ARKit weights (Live Link Face CSV, MediaPipe JSON Lines) as a
// tracker's packets, in real time, to HOST:PORT (default 127.0.0.1 and the protocol's port) — a
// stand-in for a phone or VSeeFace in tests and demos (docs/live.md). OpenFace action units are
// refused: neither protocol can carry them.
#include <fmt/core.h>

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "command.h"
#include "common_options.h"
#include "interrupt.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/live_source.h"
#include "myoshell/io/performance_file.h"
#include "option_checks.h"

namespace myo::cli {
namespace {

struct SendArgs {
  std::string file;
  std::string to;
  std::string address;  // HOST:PORT
  std::string input;
  double rate = 0.0;
  bool lockstep = false;
  double acknowledgementTimeout = 5.0;
  bool json = false;
};

// "HOST:PORT", "HOST" or ":PORT"; the missing part is 127.0.0.1 or the protocol's port.
std::pair<std::string, int> hostAndPort(const std::string& address, LiveProtocol protocol) {
  std::string host = "127.0.0.1";
  int port = defaultLivePort(protocol);
  if (address.empty()) return {host, port};
  const size_t colon = address.rfind(':');
  if (colon != 0) host = address.substr(0, colon == std::string::npos ? address.size() : colon);
  if (colon != std::string::npos) {
    const std::string digits = address.substr(colon + 1);
    char* end = nullptr;
    const long p = std::strtol(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || p < 1 || p > 65535)
      throw InputError("'" + address + "': expected HOST:PORT with a port in 1–65535");
    port = static_cast<int>(p);
  }
  return {host, port};
}

int runSend(const SendArgs& a) {
  const LiveProtocol protocol = liveProtocolFromString(a.to);
  const auto [host, port] = hostAndPort(a.address, protocol);
  PerformanceOptions read;
  if (!a.input.empty()) read.input = performanceInputFromString(a.input);
  const Performance performance = readPerformanceFile(a.file, read);
  std::vector<double> times;
  const std::vector<LiveFrame> frames = liveFramesOfPerformance(performance, a.rate, times, a.file);
  for (const std::string& w : performance.warnings) fmt::print(stderr, "warning: {}: {}\n", a.file, w);
  if (protocol == LiveProtocol::Vmc && !performance.gaze.empty())
    fmt::print(stderr, "warning: VMC carries the eyes as eyeLook* weights only: the file's eye angles are not sent\n");

  LiveSender sender(host, port);
  const std::atomic<bool>& interrupted = installInterruptHandlers();
  const double fps = a.rate > 0 ? a.rate : performance.fps;
  const auto start = std::chrono::steady_clock::now();
  long sent = 0;
  for (size_t i = 0; i < frames.size() && !interrupted.load(); ++i) {
    // Real time: each packet at its frame's time, unless lockstep waits for the receiver instead.
    if (!a.lockstep) std::this_thread::sleep_until(start + std::chrono::duration<double>(times[i]));
    const std::vector<std::uint8_t> packet =
        protocol == LiveProtocol::Vmc
            ? encodeVmcPacket(frames[i])
            : encodeLiveLinkPacket(frames[i], {static_cast<std::int32_t>(i), 0.0f, static_cast<std::int32_t>(std::lround(fps)), 1});
    sender.send(packet);
    ++sent;
    if (a.lockstep) {
      // The first frame may wait for the receiver's face to build (an ICT head: tens of seconds),
      // and a packet sent before it listened is lost: sent again every half second meanwhile.
      const double timeout = i == 0 ? 120.0 : a.acknowledgementTimeout;
      const auto giveUp = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
      while (!interrupted.load() && !sender.waitForAcknowledgement(0.5)) {
        if (std::chrono::steady_clock::now() > giveUp)
          throw std::runtime_error(fmt::format(
              "no acknowledgement from {}:{} for frame {} within {} s (--lockstep needs a receiver that "
              "acknowledges each frame it takes: myoshell live --lockstep)",
              host, port, i, timeout));
        sender.send(packet);
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (a.json) {
    nlohmann::ordered_json j;
    j["to"] = toString(protocol);
    j["host"] = host;
    j["port"] = port;
    j["packets"] = sent;
    j["frames"] = frames.size();
    j["duration"] = times.empty() ? 0.0 : times.back();
    j["seconds"] = seconds;
    j["lockstep"] = a.lockstep;
    j["interrupted"] = interrupted.load();
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("sent {} {} packets to {}:{} in {:.2f} s\n", sent, toString(protocol), host, port, seconds);
  }
  if (interrupted.load()) return 128 + interruptSignal();
  return kExitOk;
}

static CommandRegistrar registerSend("send", [](CLI::App& app) -> std::function<int()> {
  auto a = std::make_shared<SendArgs>();
  CLI::App* sub = app.add_subcommand(
      "send", "Replay a recorded performance of ARKit weights (Live Link Face CSV, MediaPipe) as VMC or Live Link "
              "Face packets, in real time (docs/live.md)");
  sub->add_option("performance", a->file, "the performance file (Live Link Face CSV, MediaPipe JSON Lines)")
      ->required();
  sub->add_option("address", a->address, "where to send, HOST:PORT (default 127.0.0.1 and 39539 for vmc, 11111 for livelink)");
  sub->add_option("--to", a->to, "the protocol: vmc or livelink")->required();
  sub->add_option("--rate", a->rate, "packets per second, resampling the take (default: its own frames)")
      ->check(numberAbove(0));
  sub->add_flag("--lockstep", a->lockstep,
                "Send each packet when the receiver has acknowledged the last, not in real time (for tests)");
  sub->add_option("--input", a->input, "livelink or mediapipe (default: from the file's header)");
  addJsonFlag(*sub, a->json);
  return [a] { return runSend(*a); };
});

}  // namespace
}  // namespace myo::cli
