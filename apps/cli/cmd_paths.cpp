// `myoshell paths [--cache DIR] [--data DIR] [--json]`: where the shipped scenes, the data folder
// and the basis cache resolve to from here, and which rule chose each (resources.h; docs/paths.md).
#include <fmt/core.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "command.h"
#include "common_options.h"
#include "resources.h"

namespace myo::cli {
namespace {

struct PathsArgs {
  std::string cache, data;
  bool json = false;
};

const CommandRegistrar pathsRegistrar("paths", [](CLI::App& app) {
  auto args = std::make_shared<PathsArgs>();
  CLI::App* sub = app.add_subcommand("paths", "Print where the scenes, the data folder and the basis cache are");
  addCacheOption(*sub, args->cache);
  addDataOption(*sub, args->data);
  addJsonFlag(*sub, args->json);
  return std::function<int()>([args] {
    const ResolvedPath scenes = shippedScenesDir(), data = dataDir(args->data), cache = cacheDir(args->cache);
    if (args->json) {
      nlohmann::ordered_json j;
      for (const auto& [key, p] : {std::pair{"scenes", scenes}, {"data", data}, {"cache", cache}})
        j[key] = {{"path", p.dir.string()}, {"source", p.source}, {"exists", !p.dir.empty() && std::filesystem::is_directory(p.dir)}};
      fmt::print("{}\n", j.dump(2));
    } else {
      for (const auto& [key, p] : {std::pair{"scenes", scenes}, {"data", data}, {"cache", cache}})
        fmt::print("{:7} {} ({})\n", key, p.dir.empty() ? "-" : p.dir.string(), p.source);
    }
    return kExitOk;
  });
});

}  // namespace
}  // namespace myo::cli
