// Reading structured documents (scene files, muscle libraries) as YAML 1.2 — which reads JSON too —
// with yaml-cpp, so that every error names `file:line:col`, the key path and what is wrong, and
// unknown keys are errors (DESIGN.md: parse → describe → build, with locations).
#pragma once

#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "myoshell/core/types.h"

namespace myo {

// Parses a document; a syntax error throws InputError at its line and column.
YAML::Node loadDocument(const std::string& text, const std::string& file);
YAML::Node loadDocumentFile(const std::string& path);  // "cannot open" InputError when unreadable

// A mapping node being read: typed getters that record which keys were used, so finish() can
// reject the rest.
class DocReader {
 public:
  // node must be a mapping (else InputError at node, "key PATH: must be an object").
  DocReader(YAML::Node node, std::string file, std::string path = "");

  bool has(const std::string& key) const;
  // A required key's node (InputError "missing required key" at this mapping).
  YAML::Node node(const std::string& key);
  // A nested mapping, read with the same file and a longer path.
  DocReader child(const std::string& key);

  double number(const std::string& key, double fallback);
  double requiredNumber(const std::string& key);
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key, const std::string& fallback);
  std::string requiredString(const std::string& key);
  std::vector<std::string> strings(const std::string& key);  // list of strings; empty if absent
  Vec3 vec3(const std::string& key, const Vec3& fallback);

  // Range checks on a value just read (the message names the key and the value).
  void requireAbove(const std::string& key, double value, double lower) const;      // value > lower
  void requireAtLeast(const std::string& key, double value, double lower) const;    // value ≥ lower
  void requireWithin(const std::string& key, double value, double lo, double hi) const;  // lo ≤ v ≤ hi

  // Throws InputError at the first key never read: "key 'PATH.KEY': unknown key", with "(did you
  // mean 'PATH.K2'?)" when a key this reader read or asked about (has) is a few edits away.
  void finish() const;

  // InputError at `at` (or at this mapping) naming the key path.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void failAt(const YAML::Node& at, const std::string& keyPath, const std::string& what) const;

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const YAML::Node& self() const { return node_; }

  // Typed reading of any node (for list elements): a number that is not a quoted string.
  double asNumber(const YAML::Node& n, const std::string& keyPath) const;
  std::string asString(const YAML::Node& n, const std::string& keyPath) const;

 private:
  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
  mutable std::set<std::string> asked_;  // keys has() was asked about (known to the reader)
};

}  // namespace myo
