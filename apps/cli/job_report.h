// What every working command adds to its --json object, so a batch user can size a job array and
// see what the shared basis cache did (docs/batch.md):
//   peak_rss_mb           this process's peak resident memory (getrusage(RUSAGE_SELF).ru_maxrss, MiB;
//                         child processes such as ffmpeg are not counted)
//   basis_cache           "computed" (this process computed at least one basis), else "waited" (it
//                         read a basis another process was computing), else "hit" (every basis read
//                         from the cache), "unused" (no basis asked for: a command without a cache,
//                         such as modes), "off" (no usable cache folder)
//   basis_cache_counts    {hits, waited, computed, stored, rejected, read_only}
//   basis_cache_computed  the keys (hex, the cache file names) of the bases it computed
//   auto_landmarks        the landmark file found automatically for an OBJ head given without
//                         landmarks (head_landmarks.h); absent otherwise
#pragma once

#include <nlohmann/json.hpp>

namespace myo::cli {

double peakRssMb();
// Adds the keys above to `j`.
void addJobReport(nlohmann::json& j);
// Adds them and prints `j` (indented) to stdout: the --json output of a command.
void printJsonReport(nlohmann::json j);

}  // namespace myo::cli
