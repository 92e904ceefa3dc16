#include "job_report.h"

#include <fmt/core.h>
#include <sys/resource.h>

#include <cmath>

#include "head_landmarks.h"
#include "resources.h"

namespace myo::cli {

double peakRssMb() {
  rusage u{};
  if (::getrusage(RUSAGE_SELF, &u) != 0) return 0.0;
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: KiB
}

void addJobReport(nlohmann::json& j) {
  j["peak_rss_mb"] = std::round(peakRssMb() * 10.0) / 10.0;
  const BasisCacheActivity& a = basisCacheActivity();
  const char* status = !a.requested       ? "unused"
                       : !a.enabled       ? "off"
                       : a.computed > 0   ? "computed"
                       : a.waited > 0     ? "waited"
                       : a.hits > 0       ? "hit"
                                          : "unused";
  j["basis_cache"] = status;
  j["basis_cache_counts"] = {{"hits", a.hits},         {"waited", a.waited},     {"computed", a.computed},
                             {"stored", a.stored},     {"rejected", a.rejected}, {"read_only", a.readOnly}};
  j["basis_cache_computed"] = a.computedKeys;
  if (!autoLandmarkFileUsed().empty()) j["auto_landmarks"] = autoLandmarkFileUsed();
}

void printJsonReport(nlohmann::json j) {
  addJobReport(j);
  fmt::print("{}\n", j.dump(2));
}

}  // namespace myo::cli
