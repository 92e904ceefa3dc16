#include "myoshell/fit/arkit_names.h"

#include <map>
#include <nlohmann/json.hpp>
#include <utility>

#include "myoshell/core/check.h"
#include "myoshell/core/close_names.h"
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
  std::map<std::string, ArkitFacs> facs;                  // ARKit name → its action units and side
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
      ArkitFacs& f = out.facs[a];
      for (const auto& au : row.at("aus")) f.aus.push_back(au.get<int>());
      f.side = row.value("side", "");
    }
    MYO_CHECK(out.arkit.size() == 52, "assets/retarget/arkit_names.json must list the 52 ARKit names");
    return out;
  }();
  return t;
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
  std::vector<std::string> spellings;
  for (const auto& entry : table().canonical) spellings.push_back(entry.first);
  std::string list;
  for (const std::string& n : closeNames(spelling, spellings)) list += (list.empty() ? "" : ", ") + n;
  if (!list.empty()) throw InputError("unknown blendshape name '" + spelling + "' (did you mean " + list + "?)");
  for (const std::string& a : table().arkit) list += (list.empty() ? "" : ", ") + a;
  throw InputError("unknown blendshape name '" + spelling + "' (use one of the 52 ARKit names: " + list + ")");
}

std::optional<std::string> mirroredArkitName(const std::string& spelling) {
  const std::string name = canonicalArkitName(spelling);
  // Every sided ARKit name ends in Left or Right, and its twin is the other (the table's 52).
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"Left", "Right"}, {"Right", "Left"}}) {
    if (!name.ends_with(from)) continue;
    const std::string twin = name.substr(0, name.size() - from.size()) + to;
    MYO_CHECK(table().canonical.count(twin) > 0, "assets/retarget/arkit_names.json: " + name + " has no " + twin);
    return twin;
  }
  return std::nullopt;
}

const ArkitFacs& arkitFacs(const std::string& spelling) { return table().facs.at(canonicalArkitName(spelling)); }

const std::vector<std::string>& ictNamesOf(const std::string& spelling) {
  return table().ict.at(canonicalArkitName(spelling));
}

}  // namespace myo
