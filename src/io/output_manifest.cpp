#include "myoshell/io/output_manifest.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"

namespace myo {

namespace fs = std::filesystem;

namespace {

// A plain relative path that stays inside its folder.
bool insideFolder(const std::string& rel) {
  if (rel.empty()) return false;
  const fs::path p(rel);
  if (p.is_absolute() || p.has_root_name() || p.has_root_directory()) return false;
  for (const fs::path& part : p)
    if (part == ".." || part == ".") return false;
  return true;
}

}  // namespace

std::vector<std::string> readOutputManifest(const fs::path& dir) {
  const fs::path path = dir / kOutputManifestName;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return {};
  const nlohmann::json j = nlohmann::json::parse(readWholeFile(path.string()), nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("files") || !j["files"].is_array())
    throw InputError("not a myoshell output manifest (expected {\"files\": [...]}); remove it to start afresh",
                     path.string());
  std::vector<std::string> files;
  for (const auto& f : j["files"])
    if (f.is_string() && insideFolder(f.get<std::string>())) files.push_back(f.get<std::string>());
  return files;
}

void writeOutputManifest(const fs::path& dir, const std::vector<std::string>& files) {
  nlohmann::json j;
  j["myoshell_manifest"] = 1;
  j["files"] = files;
  writeFileAtomically((dir / kOutputManifestName).string(), j.dump(1) + "\n", "cannot write the output manifest");
}

std::vector<std::string> removeStaleOutputs(const fs::path& dir, const std::vector<std::string>& previous,
                                            const std::vector<std::string>& current) {
  const std::set<std::string> keep(current.begin(), current.end());
  std::vector<std::string> removed;
  std::set<fs::path> folders;
  for (const std::string& rel : previous) {
    if (keep.count(rel) || !insideFolder(rel)) continue;
    const fs::path p = dir / rel;
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(p, ec))) continue;
    if (fs::remove(p, ec)) {
      removed.push_back(rel);
      if (fs::path(rel).has_parent_path()) folders.insert(dir / fs::path(rel).parent_path());
    }
  }
  for (const fs::path& f : folders) {
    std::error_code ec;
    if (fs::is_empty(f, ec)) fs::remove(f, ec);  // only an empty folder: remove() refuses others
  }
  return removed;
}

}  // namespace myo
