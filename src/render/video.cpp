// MP4 and GIF output through an ffmpeg child process (see video.h).
#include "myoshell/render/video.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <system_error>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"

extern char** environ;

namespace myo {
namespace {

namespace fs = std::filesystem;

constexpr int kLogLines = 8;  // ffmpeg's last stderr lines quoted in an error

// ffmpeg reads "file:PATH" as exactly PATH: no protocol ("a:b.mp4"), no option ("-x.mp4").
std::string ffmpegFile(const std::string& path) { return "file:" + path; }

std::string formatNumber(double x) {
  std::ostringstream os;
  os << std::setprecision(12) << x;
  return os.str();
}

// A temporary log file for a child's standard error (close-on-exec in this process). Returns its
// path and sets fd, or returns "" with fd = -1 when none can be made (stderr then goes nowhere).
std::string makeLogFile(int& fd) {
  std::error_code ec;
  std::string pattern = (fs::temp_directory_path(ec) / "myo_ffmpeg_XXXXXX").string();
  if (ec) pattern = "/tmp/myo_ffmpeg_XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd = ::mkostemp(name.data(), O_CLOEXEC);
  return fd < 0 ? std::string() : std::string(name.data());
}



// Starts `args` (args[0] looked up on PATH) with standard input from stdinFd (/dev/null when -1),
// standard output to /dev/null and standard error to stderrFd (/dev/null when -1); SIGPIPE at its
// default and no signal blocked in the child. Returns the child's pid, or -1 with `error` set.
pid_t spawn(const std::vector<std::string>& args, int stdinFd, int stderrFd, int& error) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdinFd >= 0)
    posix_spawn_file_actions_adddup2(&actions, stdinFd, STDIN_FILENO);
  else
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (stderrFd >= 0)
    posix_spawn_file_actions_adddup2(&actions, stderrFd, STDERR_FILENO);
  else
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);

  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, pipeOnly;
  sigemptyset(&none);
  sigemptyset(&pipeOnly);
  sigaddset(&pipeOnly, SIGPIPE);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &pipeOnly);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  pid_t pid = -1;
  error = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// waitpid, retried on EINTR; returns the raw status (or -1 when the child cannot be waited for).
int waitChild(pid_t pid) noexcept {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return status;
}

bool succeeded(int status) { return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0; }

std::string describeStatus(int status) {
  if (status == -1) return "could not be waited for";
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("was killed by signal ") + ::strsignal(WTERMSIG(status));
  return "ended abnormally";
}

// The last `count` non-empty lines of a log file, joined by " | ", or "no output".
std::string lastLines(const std::string& path, int count = kLogLines) {
  std::vector<std::string> lines;
  if (!path.empty()) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (!line.empty()) lines.push_back(line);
    }
  }
  if (lines.empty()) return "ffmpeg printed nothing";
  std::string out;
  for (size_t i = lines.size() > size_t(count) ? lines.size() - count : 0; i < lines.size(); ++i)
    out += (out.empty() ? "" : " | ") + lines[i];
  return "ffmpeg said: " + out;
}

// Writes all n bytes to a pipe. SIGPIPE is blocked around the writes and, if the reader has gone
// (EPIPE), the signal this raised is consumed before unblocking, so a dead ffmpeg never kills the
// calling process. Returns false with `error` set (an errno value) on failure.
bool writeAll(int fd, const std::uint8_t* data, size_t n, int& error) {
  sigset_t pipeSet, old, pending;
  sigemptyset(&pipeSet);
  sigaddset(&pipeSet, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipeSet, &old);
  sigpending(&pending);
  const bool wasPending = sigismember(&pending, SIGPIPE) == 1;
  bool ok = true;
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      error = errno;
      ok = false;
      break;
    }
    data += w;
    n -= static_cast<size_t>(w);
  }
  if (!ok && error == EPIPE && !wasPending) {
    const timespec zero{0, 0};
    while (::sigtimedwait(&pipeSet, nullptr, &zero) < 0 && errno == EINTR) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}

// Runs ffmpeg with `args` (after "ffmpeg") to completion. Returns "" on success, otherwise how it
// failed with its last stderr lines.
std::string runFfmpeg(const std::vector<std::string>& args) {
  std::vector<std::string> all{"ffmpeg", "-hide_banner", "-nostdin", "-nostats", "-loglevel", "error", "-y"};
  all.insert(all.end(), args.begin(), args.end());
  int logFd = -1;
  const std::string log = makeLogFile(logFd);
  int error = 0;
  const pid_t pid = spawn(all, -1, logFd, error);
  if (logFd >= 0) ::close(logFd);
  if (pid < 0) {
    removeQuietly(log);
    return std::string("cannot start ffmpeg (") + std::strerror(error) + ")";
  }
  const int status = waitChild(pid);
  std::string result;
  if (!succeeded(status)) result = "ffmpeg " + describeStatus(status) + "; " + lastLines(log);
  removeQuietly(log);
  return result;
}

// Throws InputError naming `path` unless it can become a file: its folder exists, it is no folder,
// and a file can be created beside it (tried with `probe`, which is removed again).
void checkWritable(const std::string& path, const std::string& probe, const std::string& what) {
  const fs::path p(path);
  std::error_code ec;
  if (p.filename().empty() || fs::is_directory(p, ec)) throw InputError("cannot write " + what + ": it is a folder", path);
  const fs::path parent = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError("cannot write " + what + ": the folder " + parent.string() + " does not exist", path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;  // a full disk is the system's failure, no permission the path's
    if (isRunTimeIoFailure(error)) throw IoError("cannot write " + what + " (" + std::strerror(error) + ")", path);
    throw InputError("cannot write " + what + " (" + std::strerror(error) + ")", path);
  }
  ::close(fd);
  removeQuietly(probe);
}

}  // namespace

bool ffmpegAvailable() {
  int error = 0;
  const pid_t pid = spawn({"ffmpeg", "-version"}, -1, -1, error);
  return pid > 0 && succeeded(waitChild(pid));
}

VideoWriter::VideoWriter(std::string path, int width, int height, const VideoOptions& options)
    : path_(std::move(path)), width_(width), height_(height) {
  MYO_CHECK_GE(width, 1);
  MYO_CHECK_GE(height, 1);
  MYO_CHECK(std::isfinite(options.fps) && options.fps > 0, "fps must be positive, not " << options.fps);
  MYO_CHECK(options.crf >= 0 && options.crf <= 51, "crf must lie in [0, 51], not " << options.crf);
  tmpPath_ = temporaryPathBeside(path_, ".mp4");
  checkWritable(path_, tmpPath_, "video");
  if (!ffmpegAvailable())
    throw InputError("cannot write video: ffmpeg not found on PATH (install the Debian package ffmpeg)", path_);

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw IoError(std::string("cannot write video: pipe (") + std::strerror(errno) + ")", path_);
  int logFd = -1;
  logPath_ = makeLogFile(logFd);
  const int evenWidth = width_ + (width_ & 1), evenHeight = height_ + (height_ & 1);
  const std::vector<std::string> args{
      "ffmpeg", "-hide_banner", "-nostats", "-loglevel", "error", "-y",
      // input: raw 8-bit RGB frames on standard input
      "-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size",
      std::to_string(evenWidth) + "x" + std::to_string(evenHeight), "-framerate", formatNumber(options.fps),
      "-i", "pipe:0",
      // output: H.264 in yuv420p (what browsers and players decode), moov atom first
      "-c:v", "libx264", "-preset", "medium", "-crf", std::to_string(options.crf), "-pix_fmt", "yuv420p",
      "-movflags", "+faststart", "-f", "mp4", ffmpegFile(tmpPath_)};
  int error = 0;
  pid_ = spawn(args, fds[0], logFd, error);
  ::close(fds[0]);
  if (logFd >= 0) ::close(logFd);
  if (pid_ < 0) {
    ::close(fds[1]);
    removeQuietly(logPath_);
    removeQuietly(tmpPath_);
    throw IoError(std::string("cannot write video: cannot start ffmpeg (") + std::strerror(error) + ")", path_);
  }
  stdinFd_ = fds[1];
}

VideoWriter::~VideoWriter() {
  if (!done_) discard();
}

void VideoWriter::abort() noexcept {
  if (!done_) discard();
}

void VideoWriter::discard() noexcept {
  if (stdinFd_ >= 0) ::close(stdinFd_);
  stdinFd_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    waitChild(pid_);
  }
  pid_ = -1;
  removeQuietly(tmpPath_);
  removeQuietly(logPath_);
  done_ = true;
}

void VideoWriter::fail(const std::string& why) {
  discard();
  // The path was checked writable: ffmpeg failing now is a run-time failure (a full disk, EFBIG).
  throw IoError("cannot write video: " + why, path_);
}

void VideoWriter::addFrame(const Image& frame) {
  MYO_CHECK(!done_, "addFrame() after finish() or after a failure");
  if (frame.width != width_ || frame.height != height_)
    throw InputError("cannot write video: frame " + std::to_string(frameCount_) + " is " + std::to_string(frame.width) +
                         "×" + std::to_string(frame.height) + " pixels, the video " + std::to_string(width_) + "×" +
                         std::to_string(height_),
                     path_);
  MYO_CHECK_EQ(frame.pixels.size(), static_cast<size_t>(width_) * height_ * 3);

  const std::uint8_t* data = frame.pixels.data();
  size_t bytes = frame.pixels.size();
  if ((width_ | height_) & 1) {  // pad to even sizes, repeating the last column and row
    const int W = width_ + (width_ & 1), H = height_ + (height_ & 1);
    padded_.resize(static_cast<size_t>(W) * H * 3);
    for (int y = 0; y < H; ++y) {
      const std::uint8_t* src = frame.pixels.data() + static_cast<size_t>(std::min(y, height_ - 1)) * width_ * 3;
      std::uint8_t* dst = padded_.data() + static_cast<size_t>(y) * W * 3;
      std::memcpy(dst, src, static_cast<size_t>(width_) * 3);
      if (W != width_) std::memcpy(dst + width_ * 3, src + (width_ - 1) * 3, 3);
    }
    data = padded_.data();
    bytes = padded_.size();
  }

  int error = 0;
  if (!writeAll(stdinFd_, data, bytes, error)) {
    // ffmpeg has stopped reading (it exited, usually): collect its status and words.
    ::close(stdinFd_);
    stdinFd_ = -1;
    const int status = waitChild(pid_);
    pid_ = -1;
    fail("ffmpeg stopped reading at frame " + std::to_string(frameCount_) + " (" + std::strerror(error) + "): ffmpeg " +
         describeStatus(status) + "; " + lastLines(logPath_));
  }
  ++frameCount_;
}

void VideoWriter::finish() {
  MYO_CHECK(!done_, "finish() called twice, or after a failure");
  if (frameCount_ == 0) discard();
  MYO_CHECK(frameCount_ > 0, "a video needs at least one frame");
  ::close(stdinFd_);
  stdinFd_ = -1;
  const int status = waitChild(pid_);
  pid_ = -1;
  if (!succeeded(status)) fail("ffmpeg " + describeStatus(status) + "; " + lastLines(logPath_));
  try {
    renameIntoPlace(tmpPath_, path_, "cannot write video");
  } catch (...) {
    discard();
    throw;
  }
  removeQuietly(logPath_);
  done_ = true;
}

void makeGif(const std::string& mp4Path, const std::string& gifPath, int width, double fps) {
  MYO_CHECK_GE(width, 2);
  MYO_CHECK(std::isfinite(fps) && fps > 0, "fps must be positive, not " << fps);
  std::error_code ec;
  if (!fs::is_regular_file(mp4Path, ec)) throw InputError("cannot make a GIF: no such video", mp4Path);
  const std::string tmpGif = temporaryPathBeside(gifPath, ".gif");
  const std::string palette = temporaryPathBeside(gifPath, ".palette.png");
  checkWritable(gifPath, tmpGif, "GIF");
  if (!ffmpegAvailable())
    throw InputError("cannot make a GIF: ffmpeg not found on PATH (install the Debian package ffmpeg)", gifPath);

  const std::string filters = "fps=" + formatNumber(fps) + ",scale=" + std::to_string(width) + ":-1:flags=lanczos";
  auto failWith = [&](const std::string& why) {
    removeQuietly(palette);
    removeQuietly(tmpGif);
    throw InputError("cannot make a GIF from " + mp4Path + ": " + why, gifPath);
  };
  // Pass 1: one 256-colour palette for the whole clip.
  std::string why = runFfmpeg({"-i", ffmpegFile(mp4Path), "-vf", filters + ",palettegen", "-frames:v", "1", "-update",
                               "1", "-f", "image2", "-c:v", "png", ffmpegFile(palette)});
  if (!why.empty()) failWith(why);
  // Pass 2: every frame mapped to that palette (dithered), looping forever.
  why = runFfmpeg({"-i", ffmpegFile(mp4Path), "-i", ffmpegFile(palette), "-lavfi", filters + "[x];[x][1:v]paletteuse",
                   "-loop", "0", "-f", "gif", ffmpegFile(tmpGif)});
  if (!why.empty()) failWith(why);
  removeQuietly(palette);
  renameIntoPlace(tmpGif, gifPath, "cannot make a GIF from " + mp4Path);
}

}  // namespace myo
