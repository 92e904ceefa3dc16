// `myoshell validate [--json] [--quick] [--modes D]`: the accuracy cases of validation.h — the
// reduced solutions (modal warping, linear modal) against the full-space nonlinear reference and
// beam theory on a clamped strip. Exit 0 when every case holds its bound, 1 otherwise.
#include <fmt/core.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "job_report.h"
#include "command.h"
#include "common_options.h"
#include "myoshell/core/errors.h"
#include "myoshell/verify/validation.h"

namespace myo::cli {

namespace {

struct ValidateArgs {
  bool json = false;
  bool quick = false;
  bool noDynamic = false;
  int modes = 20;
};

nlohmann::ordered_json toJson(const AccuracyCase& c) {
  nlohmann::ordered_json j;
  j["name"] = c.name;
  j["description"] = c.description;
  j["d"] = c.d;
  j["quantity"] = c.quantity;
  j["reference"] = c.reference;
  j["warped"] = c.warped;
  j["linear"] = c.linear;
  j["metric"] = c.metric;
  j["error_warped"] = c.errorWarped;
  j["error_linear"] = c.errorLinear;
  j["bound"] = c.bound;
  j["passed"] = c.passed;
  j["details"] = nlohmann::ordered_json::object();
  for (const auto& [k, v] : c.extra) j["details"][k] = v;
  return j;
}

int runValidate(const ValidateArgs& args) {
  if (args.modes < 1) throw InputError("--modes must be ≥ 1, got " + std::to_string(args.modes));
  ValidationSettings settings;
  settings.modes = args.modes;
  settings.dynamic = !args.noDynamic;
  if (args.quick) {  // coarse strip only for the fine-mesh cases, one period of dynamics
    settings.fine = settings.coarse;
    settings.dynamicPeriods = 1.0;
    settings.stepsPerPeriod = 100;
  }
  const ValidationReport report = runValidation(settings);
  if (args.json) {
    nlohmann::ordered_json j;
    j["cases"] = nlohmann::ordered_json::array();
    for (const auto& c : report.cases) j["cases"].push_back(toJson(c));
    j["all_passed"] = report.allPassed();
    j["seconds"] = report.seconds;
    printJsonReport(j);
  } else {
    for (const auto& c : report.cases) {
      fmt::print("{}  [{}]  d = {}\n  {}\n", c.name, c.passed ? "pass" : "FAIL", c.d, c.description);
      fmt::print("  {:<40}{:>14}{:>14}{:>14}\n", c.quantity, "reference", "warped", "linear");
      fmt::print("  {:<40}{:>14.6g}{:>14.6g}{:>14.6g}\n", "", c.reference, c.warped, c.linear);
      fmt::print("  relative error ({}): warped {:.3g}, linear {:.3g}\n", c.metric, c.errorWarped, c.errorLinear);
      for (const auto& [k, v] : c.extra) fmt::print("    {:<34}{:.6g}\n", k, v);
      fmt::print("  bound: {}\n\n", c.bound);
    }
    fmt::print("{} of {} cases passed in {:.1f} s\n",
               std::count_if(report.cases.begin(), report.cases.end(), [](const auto& c) { return c.passed; }),
               report.cases.size(), report.seconds);
  }
  return report.allPassed() ? kExitOk : kExitFailure;
}

}  // namespace

static CommandRegistrar registerValidate("validate", [](CLI::App& app) {
  auto* sub = app.add_subcommand(
      "validate", "Accuracy cases: modal warping and linear modal vs the full-space nonlinear reference and beam theory");
  auto args = std::make_shared<ValidateArgs>();
  addJsonFlag(*sub, args->json);
  sub->add_flag("--quick", args->quick, "Coarse mesh only and one period of dynamics (a few seconds)");
  sub->add_flag("--no-dynamic", args->noDynamic, "Skip the released-tip dynamic case (the slowest)");
  sub->add_option("--modes", args->modes, "Modes d of the reduced bases (default 20)");
  return std::function<int()>([args] { return runValidate(*args); });
});

}  // namespace myo::cli
