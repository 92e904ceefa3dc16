// `myoshell muscles [--library face|builtin|FILE] [--head default|DIR|OBJ --landmarks F] [--units u]
// [--json]`: the muscles of a library — name, side, FACS action units, kind (linear or ring) — and,
// with a head, each one placed on it (its length in cm), so a library or a head whose landmarks do
// not fit it fails here, naming the muscle. docs/muscles.md.
#include <fmt/core.h>

#include <cctype>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "head_landmarks.h"
#include "myoshell/core/errors.h"
#include "myoshell/io/fit_head.h"
#include "myoshell/muscles/muscle.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo::cli {
namespace {

struct MusclesArgs {
  HeadOptions head;
  std::string library = defaultMuscleLibrary();
  bool json = false;
};

// "AU20 AU21" → {20, 21}; the numbers a muscle's `facs` field names, in its order.
std::vector<int> actionUnits(const std::string& facs) {
  std::vector<int> out;
  for (size_t i = 0; i + 2 < facs.size(); ++i)
    if (facs.compare(i, 2, "AU") == 0 && std::isdigit(static_cast<unsigned char>(facs[i + 2]))) {
      size_t end = i + 2;
      int value = 0;
      while (end < facs.size() && std::isdigit(static_cast<unsigned char>(facs[end])) && value < 1000)
        value = 10 * value + (facs[end++] - '0');
      out.push_back(value);
      i = end - 1;
    }
  return out;
}

int runMuscles(MusclesArgs& a) {
  const SceneInputs inputs = fitHeadInputs(fitHeadOptions(a.head, a.library), nullptr, "muscles");
  const bool placed = a.head.headGiven();
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const MuscleDef& d : inputs.muscles) {
    nlohmann::ordered_json m;
    m["name"] = d.name;
    m["side"] = d.side;
    m["aus"] = actionUnits(d.facs);
    m["kind"] = toString(d.kind);
    if (placed) m["length_cm"] = buildMuscle(d, inputs.head, TubeOrientation::MirrorRightSide).restLength;
    list.push_back(m);
  }
  if (a.json) {
    nlohmann::ordered_json j;
    j["library"] = a.library;
    if (placed) j["head"] = inputs.head.name;
    j["muscles"] = list;
    printJsonReport(j);
    return kExitOk;
  }
  fmt::print("{} muscles in library {}{}\n", list.size(), a.library,
             placed ? " placed on " + inputs.head.name : std::string());
  for (const auto& m : list) {
    std::string aus;
    for (const auto& au : m["aus"]) aus += fmt::format("{}AU{}", aus.empty() ? "" : " ", au.get<int>());
    fmt::print("  {:<44} {:<7} {:<6} {:<26}{}\n", m["name"].get<std::string>(), m["side"].get<std::string>(),
               m["kind"].get<std::string>(), aus,
               placed ? fmt::format(" {:.2f} cm", m["length_cm"].get<double>()) : std::string());
  }
  return kExitOk;
}

static CommandRegistrar registerMuscles("muscles", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<MusclesArgs>();
  CLI::App* sub = app.add_subcommand(
      "muscles", "List a muscle library (name, side, FACS action units, linear or ring) and, with --head, place each "
                 "muscle on that head (docs/muscles.md)");
  addLibraryOption(*sub, args->library);
  HeadHelp help;
  help.head = ": every muscle is placed on it";
  help.headDefault = "none (the muscles listed, not placed)";
  addHeadOptions(*sub, args->head, help);
  addJsonFlag(*sub, args->json);
  return [args] {
    resolveHeadLandmarks(args->head, "");
    return runMuscles(*args);
  };
});

}  // namespace
}  // namespace myo::cli
