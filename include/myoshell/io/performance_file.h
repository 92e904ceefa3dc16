// Performance files (`myoshell drive PERFORMANCE`): OpenFace CSV, Live Link Face CSV or MediaPipe
// JSON Lines; the anim layer parses the text (anim/performance.h, docs/performance_input.md).
#pragma once

#include <string>

#include "myoshell/anim/performance.h"

namespace myo {

// Reads the performance at `path` (parsePerformance's layouts and errors, naming `path`; InputError
// "cannot open performance file" when unreadable, "cannot open: is a directory" for a folder).
Performance readPerformanceFile(const std::string& path, const PerformanceOptions& options = {});

}  // namespace myo
