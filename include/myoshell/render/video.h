// Video output through the `ffmpeg` program (Debian's ffmpeg): rendered frames streamed into an
// MP4 (H.264, yuv420p, +faststart, plays in browsers and slides), and a GIF made from that MP4.
//
// ffmpeg runs as a child process started with posix_spawn (no shell, so any path is safe: spaces,
// quotes, colons, a leading '-'), reading raw rgb24 frames on its standard input; its standard
// error goes to a temporary log whose last lines are quoted in errors. The output is written to a
// temporary file next to the final one (core/atomic_file.h: ".NAME.PID.N.tmp.mp4") that is renamed into place only when
// ffmpeg has succeeded, so a reader never sees a half-written video and a failure leaves nothing.
//
// yuv420p needs even sizes: a frame of odd width (height) gets one more column (row) repeating its
// last one, so the video is (width rounded up to even) × (height rounded up to even) pixels.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

#include "myoshell/render/image.h"

namespace myo {

struct VideoOptions {
  double fps = 30;  // frames per second of the video, > 0; frame k shows at time k / fps, s
  int crf = 20;     // H.264 constant rate factor in [0, 51]: 0 lossless, 18–23 visually good, 51 worst
};

// True when an `ffmpeg` program is on PATH and `ffmpeg -version` runs and exits 0.
bool ffmpegAvailable();

// Streams frames, all width × height, into the MP4 `path`. The constructor starts ffmpeg; frames
// go to it as they come (memory stays at one frame); finish() completes the file.
class VideoWriter {
 public:
  // Starts ffmpeg writing to a temporary file beside `path`. Throws InputError naming `path` when
  // ffmpeg is missing, the folder is missing or unwritable, or `path` is a folder; IoError when the
  // system fails (no space to create the file, no pipe, ffmpeg cannot be started); CheckError when
  // width or height < 1, fps ≤ 0 or crf is outside [0, 51].
  VideoWriter(std::string path, int width, int height, const VideoOptions& options = {});
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  // If finish() has not succeeded: kills ffmpeg and removes the temporary file. Never throws.
  ~VideoWriter();

  // Sends one frame. Throws InputError when its size is not width × height (nothing is sent and
  // the writer stays usable); IoError when ffmpeg has died (a full disk, a file-size limit; the
  // message quotes ffmpeg's last error lines; the writer is then failed and the temporary file
  // removed). CheckError after finish().
  void addFrame(const Image& frame);

  // Closes ffmpeg's input, waits for it, checks its exit status and renames the temporary file to
  // `path`. Throws IoError naming `path` with ffmpeg's last error lines when ffmpeg failed or the
  // rename failed (no file is left then), CheckError when no frame was added or when called twice.
  void finish();

  // Stops without a video (an interrupted run): kills ffmpeg, waits for it (no zombie) and removes
  // the temporary files. Never throws; the writer is then done.
  void abort() noexcept;

  int frameCount() const { return frameCount_; }  // frames sent so far
  const std::string& path() const { return path_; }

 private:
  void discard() noexcept;                          // kills ffmpeg, removes the temporary files
  [[noreturn]] void fail(const std::string& why);  // discard() and throw IoError naming path_

  std::string path_;         // final MP4
  std::string tmpPath_;      // what ffmpeg writes, renamed to path_ by finish()
  std::string logPath_;      // ffmpeg's standard error
  int width_ = 0, height_ = 0;
  int frameCount_ = 0;
  pid_t pid_ = -1;           // the ffmpeg child; -1 once reaped
  int stdinFd_ = -1;         // write end of ffmpeg's standard input
  bool done_ = false;        // finish() succeeded, or the writer failed
  std::vector<std::uint8_t> padded_;  // a frame padded to even sizes (odd sizes only)
};

// Makes a GIF from an MP4 with ffmpeg's two-pass palette: pass 1 computes a 256-colour palette
// over the whole clip (palettegen), pass 2 maps every frame to it (paletteuse, dithered). The GIF
// is `width` pixels wide (height keeps the aspect ratio) at `fps` frames per second, written through
// a temporary file renamed into place. Throws InputError naming the file at fault when the MP4 is
// missing or unreadable, ffmpeg is missing or fails, or the GIF cannot be written (nothing is left
// behind); CheckError when width < 2 or fps ≤ 0.
void makeGif(const std::string& mp4Path, const std::string& gifPath, int width = 480, double fps = 15);

}  // namespace myo
