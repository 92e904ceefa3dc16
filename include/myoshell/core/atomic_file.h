// Writing a whole file so that no reader ever sees half of it: the bytes go to a temporary file
// beside the target (same folder, so the rename is atomic), flushed to disk and renamed into place
// only once complete. Every file Myoshell writes goes through here (OBJ, PNG, video, GLB, PC2, the
// basis cache, stats.json, saved scenes).
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

namespace myo {

// Writes `bytes` to `path` through a temporary file renamed into place. On failure nothing is left
// behind (no temporary, no half-written `path`) and the error names `path`, "<what> (<reason>)",
// the reason being the OS's (strerror):
// - InputError when `path` cannot be a file (a folder at `path`, a missing folder, no permission):
//   the user's choice of path (exit 2);
// - IoError when the system fails (isRunTimeIoFailure at creation; any failure to write, flush,
//   sync, close or rename once the file is open: a full disk, EFBIG under RLIMIT_FSIZE, EIO) (exit 1).
void writeFileAtomically(const std::string& path, std::string_view bytes,
                         const std::string& what = "cannot write file");

// The same with the bytes produced by `write`, which writes to the open temporary file (binary
// mode). A write error on the stream (std::ferror), on fflush, fsync or close fails as above.
// Exceptions thrown by `write` remove the temporary file and propagate.
void writeFileAtomically(const std::string& path, const std::function<void(std::FILE*)>& write,
                         const std::string& what = "cannot write file");

// The pieces, for writers whose bytes come from elsewhere (ffmpeg writing a video):
// a fresh temporary name beside `target`: ".<target's name>.<pid>.<n>.tmp<suffix>" in its folder;
std::string temporaryPathBeside(const std::string& target, const std::string& suffix = "");
// renames `tmp` onto `target`; on failure removes `tmp` and throws as writeFileAtomically does;
void renameIntoPlace(const std::string& tmp, const std::string& target, const std::string& what);
// removes a file if it exists, ignoring every error (cleanup on failure paths).
void removeQuietly(const std::string& path) noexcept;

// Whether an errno met while creating a file or folder is the system's run-time failure (no space,
// quota, file too large, I/O error, out of file descriptors or memory: IoError) rather than a fault
// of the path itself (missing, not a folder, no permission: InputError).
bool isRunTimeIoFailure(int error);

}  // namespace myo
