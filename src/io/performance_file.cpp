#include "myoshell/io/performance_file.h"

#include "myoshell/core/whole_file.h"

namespace myo {

Performance readPerformanceFile(const std::string& path, const PerformanceOptions& options) {
  return parsePerformance(readWholeFile(path, "cannot open performance file"), path, options);
}

}  // namespace myo
