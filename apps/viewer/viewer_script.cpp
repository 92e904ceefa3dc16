#include "viewer_script.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"

namespace myo::viewer {
namespace {

// Argument kinds of each command: 'n' a number, 'b' on/off, 'w' a word, 'v' a view name.
const std::map<std::string, std::string>& grammar() {
  static const std::map<std::string, std::string> g = {
      {"set", "wn"},     {"link", "b"},    {"gravity", "b"}, {"stiffness", "n"}, {"play", ""},
      {"pause", ""},     {"seek", "n"},    {"reset", ""},    {"grab", "w"},      {"pull", "nnn"},
      {"release", ""},   {"key", ""},      {"save", "w"},    {"export", "w"},    {"screenshot", "w"},
      {"advance", "n"},  {"show", "wb"},   {"select", "w"},  {"view", "v"},      {"orbit", "nn"},
      {"zoom", "n"},     {"jaw", "nnn"},   {"blink", ""},
      {"probe", "w"},    {"sliders", ""},  {"calibrate", "n"}};
  return g;
}

bool parseNumber(const std::string& word, double& value) {
  std::istringstream in(word);
  in >> value;
  return in && in.peek() == std::char_traits<char>::eof() && std::isfinite(value);
}

}  // namespace

double ScriptCommand::number(size_t i) const { return std::stod(args.at(i)); }

std::vector<ScriptCommand> parseViewerScript(const std::string& text, const std::string& path) {
  std::vector<ScriptCommand> commands;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    ScriptCommand cmd;
    cmd.line = number;
    if (!(words >> cmd.verb)) continue;
    for (std::string w; words >> w;) cmd.args.push_back(w);
    const auto it = grammar().find(cmd.verb);
    if (it == grammar().end()) {
      std::string known;
      for (const auto& [verb, kinds] : grammar()) known += (known.empty() ? "" : ", ") + verb;
      throw InputError("unknown command '" + cmd.verb + "' (known: " + known + ")", path, number);
    }
    const std::string& kinds = it->second;
    if (cmd.args.size() != kinds.size())
      throw InputError("'" + cmd.verb + "' takes " + std::to_string(kinds.size()) + " argument" +
                           (kinds.size() == 1 ? "" : "s") + ", got " + std::to_string(cmd.args.size()),
                       path, number);
    for (size_t i = 0; i < kinds.size(); ++i) {
      const std::string& a = cmd.args[i];
      double value = 0.0;
      if (kinds[i] == 'n' && !parseNumber(a, value))
        throw InputError("'" + cmd.verb + "': '" + a + "' is not a finite number", path, number);
      if (kinds[i] == 'b' && a != "on" && a != "off")
        throw InputError("'" + cmd.verb + "': expected on or off, got '" + a + "'", path, number);
      if (kinds[i] == 'v' && a != "front" && a != "three-quarter" && a != "profile")
        throw InputError("'" + cmd.verb + "': unknown view '" + a + "' (use front, three-quarter or profile)", path,
                         number);
    }
    commands.push_back(std::move(cmd));
  }
  return commands;
}

std::vector<ScriptCommand> readViewerScript(const std::string& path) {
  return parseViewerScript(readWholeFile(path, "cannot open the script"), path);
}

}  // namespace myo::viewer
