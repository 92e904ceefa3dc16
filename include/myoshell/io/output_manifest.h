// What a run wrote into its output folder: DIR/.myoshell-manifest.json lists the files (paths
// relative to DIR, '/'-separated). A rerun into the same folder removes the files the previous
// manifest names and the new run did not write — stale frames, an old GLB, PC2 or MP4 — and nothing
// else: a file of the user's in DIR is never in a manifest, so it survives.
//
// Format: {"myoshell_manifest": 1, "files": ["obj/smile_0000.obj", "smile.glb", …]}.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace myo {

inline constexpr const char* kOutputManifestName = ".myoshell-manifest.json";

// The files the previous run listed in DIR's manifest; empty when there is none. Entries that are
// not plain relative paths inside DIR (absolute, with "..", empty) are dropped, so a tampered
// manifest cannot reach outside DIR. Throws InputError naming the manifest when it is not one.
std::vector<std::string> readOutputManifest(const std::filesystem::path& dir);

// Writes DIR's manifest listing `files` (atomically).
void writeOutputManifest(const std::filesystem::path& dir, const std::vector<std::string>& files);

// Removes every file of `previous` that `current` does not hold (regular files only; a folder left
// empty by that, inside DIR, goes too). Returns the relative paths removed. Never throws.
std::vector<std::string> removeStaleOutputs(const std::filesystem::path& dir, const std::vector<std::string>& previous,
                                            const std::vector<std::string>& current);

}  // namespace myo
