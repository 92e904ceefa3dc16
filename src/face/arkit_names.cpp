#include "myoshell/face/arkit_names.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <nlohmann/json.hpp>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"

namespace myo {
namespace detail {
extern const char kArkitNamesJson[];
}  // namespace detail

namespace {

struct Table {
  std::vector<std::string> arkit;                         // 52, in order
  std::map<std::string, std::vector<std::string>> ict;    // ARKit name → ICT names
  std::map<std::string, std::string> canonical;           // any spelling → ARKit name
};

const Table& table() {
  static const Table t = [] {
    Table out;
    const nlohmann::json j = nlohmann::json::parse(detail::kArkitNamesJson);  // shipped data: a bug if bad
    for (const auto& row : j.at("names")) {
      const std::string a = row.at("arkit").get<std::string>();
      out.arkit.push_back(a);
      out.canonical[a] = a;
      for (const auto& i : row.at("ict")) {
        out.ict[a].push_back(i.get<std::string>());
        out.canonical[i.get<std::string>()] = a;
      }
    }
    MYO_CHECK(out.arkit.size() == 52, "assets/retarget/arkit_names.json must list the 52 ARKit names");
    return out;
  }();
  return t;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Levenshtein distance, case-insensitive: how a misspelt name finds its neighbours.
std::size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

const std::vector<std::string>& arkitNames() { return table().arkit; }

std::optional<std::string> findArkitName(const std::string& spelling) {
  const auto it = table().canonical.find(spelling);
  if (it == table().canonical.end()) return std::nullopt;
  return it->second;
}

std::string canonicalArkitName(const std::string& spelling) {
  if (auto name = findArkitName(spelling)) return *name;
  // Close: within a third of the name's length in edits (case ignored).
  std::vector<std::pair<std::size_t, std::string>> close;
  const std::string key = lower(spelling);
  for (const auto& entry : table().canonical) {
    const std::size_t d = distance(key, lower(entry.first));
    if (d <= std::max<std::size_t>(1, entry.first.size() / 3)) close.emplace_back(d, entry.first);
  }
  std::sort(close.begin(), close.end());
  std::string list;  // the closest, and those one edit further (mouthSmile_l: _L and _R), at most 3
  for (std::size_t i = 0; i < close.size() && i < 3 && close[i].first <= close[0].first + 1; ++i)
    list += (i ? ", " : "") + close[i].second;
  if (!list.empty()) throw InputError("unknown blendshape name '" + spelling + "' (did you mean " + list + "?)");
  for (const std::string& a : table().arkit) list += (list.empty() ? "" : ", ") + a;
  throw InputError("unknown blendshape name '" + spelling + "' (use one of the 52 ARKit names: " + list + ")");
}

const std::vector<std::string>& ictNamesOf(const std::string& spelling) {
  return table().ict.at(canonicalArkitName(spelling));
}

}  // namespace myo
