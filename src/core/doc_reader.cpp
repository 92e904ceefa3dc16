#include "myoshell/core/doc_reader.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "myoshell/core/close_names.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/whole_file.h"

namespace myo {

namespace {
std::string fmtValue(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// Strict UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), as JSON
// writers require: yaml-cpp passes stray bytes and "\uD800" escapes through into scalars.
bool isUtf8(const std::string& s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = 0;
    unsigned lo = 0x80, hi = 0xBF;  // allowed range of the first continuation byte
    if (c < 0x80) extra = 0;
    else if (c >= 0xC2 && c <= 0xDF) extra = 1;
    else if (c == 0xE0) { extra = 2; lo = 0xA0; }
    else if (c == 0xED) { extra = 2; hi = 0x9F; }
    else if (c >= 0xE1 && c <= 0xEF) extra = 2;
    else if (c == 0xF0) { extra = 3; lo = 0x90; }
    else if (c == 0xF4) { extra = 3; hi = 0x8F; }
    else if (c >= 0xF1 && c <= 0xF3) extra = 3;
    else return false;
    if (i + static_cast<size_t>(extra) >= s.size() && extra > 0) return false;  // cut short
    for (int k = 1; k <= extra; ++k) {
      const auto b = static_cast<unsigned char>(s[i + static_cast<size_t>(k)]);
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return false;
    }
    i += static_cast<size_t>(extra) + 1;
  }
  return true;
}
}  // namespace

YAML::Node loadDocument(const std::string& text, const std::string& file) {
  // YAML accepts much that JSON does not (a stray comma becomes an empty key): a document that looks
  // like JSON is checked as JSON first, so its syntax errors read as such.
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && (text[first] == '{' || text[first] == '[')) {
    try {
      [[maybe_unused]] const nlohmann::json checked = nlohmann::json::parse(text);  // only its errors matter
    } catch (const nlohmann::json::parse_error& e) {
      const size_t at = std::min(e.byte > 0 ? e.byte - 1 : 0, text.size());
      const size_t lineStart = text.rfind('\n', at == 0 ? 0 : at - 1);
      const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
      const int column = static_cast<int>(at - (lineStart == std::string::npos ? 0 : lineStart + 1)) + 1;
      std::string what = e.what();
      const size_t colon = what.find("syntax error");
      throw InputError("JSON " + (colon == std::string::npos ? what : what.substr(colon)), file, line, column);
    } catch (const nlohmann::json::exception& e) {
      // A number beyond double's range ("number overflow parsing '1e400'", out_of_range.406) comes
      // without a position: find the number in the text.
      std::string what = e.what();
      if (const size_t bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
      const size_t q1 = what.find('\''), q2 = what.rfind('\'');
      const size_t at = q1 != std::string::npos && q2 > q1 ? text.find(what.substr(q1 + 1, q2 - q1 - 1)) : std::string::npos;
      if (at == std::string::npos) throw InputError("JSON " + what, file);
      const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
      const size_t lineStart = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
      const int column = static_cast<int>(at - (lineStart == std::string::npos ? 0 : lineStart + 1)) + 1;
      throw InputError("JSON " + what, file, line, column);
    }
  }
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError("syntax error: " + e.msg, file, e.mark.line + 1, e.mark.column + 1);
  }
}

YAML::Node loadDocumentFile(const std::string& path) {
  const std::string text = readWholeFile(path, "cannot open file");
  if (text.empty()) throw InputError("file is empty", path);
  return loadDocument(text, path);
}

DocReader::DocReader(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (!node_.IsMap()) failAt(node_, path_.empty() ? "(document)" : path_, "must be an object");
}

void DocReader::failAt(const YAML::Node& at, const std::string& keyPath, const std::string& what) const {
  const YAML::Mark m = at.Mark();
  const bool known = m.line >= 0 && m.pos >= 0;
  throw InputError("key '" + keyPath + "': " + what, file_, known ? m.line + 1 : 0, known ? m.column + 1 : 0);
}

void DocReader::fail(const std::string& key, const std::string& what) const {
  if (has(key)) failAt(node_[key], keyPath(key), what);
  failAt(node_, keyPath(key), what);
}

bool DocReader::has(const std::string& key) const {
  asked_.insert(key);  // a key the reader knows, present or not: a suggestion for a misspelt one
  return node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node DocReader::node(const std::string& key) {
  used_.insert(key);
  if (!has(key)) failAt(node_, keyPath(key), "missing required key");
  return node_[key];
}

DocReader DocReader::child(const std::string& key) { return DocReader(node(key), file_, keyPath(key)); }

double DocReader::asNumber(const YAML::Node& n, const std::string& keyPath) const {
  // A quoted scalar ("1.0") has the non-specific tag "!": a string, not a number.
  if (!n.IsScalar() || n.Tag() == "!") failAt(n, keyPath, "must be a number");
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    failAt(n, keyPath, "must be a number (got '" + n.Scalar() + "')");
  }
  if (!std::isfinite(v)) failAt(n, keyPath, "must be a finite number (got '" + n.Scalar() + "')");
  return v;
}

std::string DocReader::asString(const YAML::Node& n, const std::string& keyPath) const {
  if (!n.IsScalar()) failAt(n, keyPath, "must be a string");
  if (!isUtf8(n.Scalar())) failAt(n, keyPath, "must be UTF-8 text");
  return n.Scalar();
}

double DocReader::number(const std::string& key, double fallback) {
  used_.insert(key);
  return has(key) ? asNumber(node_[key], keyPath(key)) : fallback;
}

double DocReader::requiredNumber(const std::string& key) { return asNumber(node(key), keyPath(key)); }

int DocReader::integer(const std::string& key, int fallback) {
  used_.insert(key);
  if (!has(key)) return fallback;
  const double v = asNumber(node_[key], keyPath(key));
  if (v != std::floor(v) || std::abs(v) > 1e9) failAt(node_[key], keyPath(key), "must be an integer (got " + fmtValue(v) + ")");
  return static_cast<int>(v);
}

bool DocReader::boolean(const std::string& key, bool fallback) {
  used_.insert(key);
  if (!has(key)) return fallback;
  const YAML::Node n = node_[key];
  if (!n.IsScalar() || n.Tag() == "!" || (n.Scalar() != "true" && n.Scalar() != "false"))
    failAt(n, keyPath(key), "must be true or false");
  return n.Scalar() == "true";
}

std::string DocReader::string(const std::string& key, const std::string& fallback) {
  used_.insert(key);
  return has(key) ? asString(node_[key], keyPath(key)) : fallback;
}

std::string DocReader::requiredString(const std::string& key) { return asString(node(key), keyPath(key)); }

std::vector<std::string> DocReader::strings(const std::string& key) {
  used_.insert(key);
  std::vector<std::string> out;
  if (!has(key)) return out;
  const YAML::Node n = node_[key];
  if (!n.IsSequence()) failAt(n, keyPath(key), "must be a list of strings");
  for (size_t i = 0; i < n.size(); ++i) out.push_back(asString(n[i], keyPath(key) + "[" + std::to_string(i) + "]"));
  return out;
}

Vec3 DocReader::vec3(const std::string& key, const Vec3& fallback) {
  used_.insert(key);
  if (!has(key)) return fallback;
  const YAML::Node n = node_[key];
  if (!n.IsSequence() || n.size() != 3) failAt(n, keyPath(key), "must be a list of 3 numbers");
  Vec3 v;
  for (int i = 0; i < 3; ++i) v(i) = asNumber(n[i], keyPath(key) + "[" + std::to_string(i) + "]");
  return v;
}

void DocReader::requireAbove(const std::string& key, double value, double lower) const {
  if (!(value > lower)) fail(key, "must be > " + fmtValue(lower) + " (got " + fmtValue(value) + ")");
}

void DocReader::requireAtLeast(const std::string& key, double value, double lower) const {
  if (!(value >= lower)) fail(key, "must be ≥ " + fmtValue(lower) + " (got " + fmtValue(value) + ")");
}

void DocReader::requireWithin(const std::string& key, double value, double lo, double hi) const {
  if (!(value >= lo && value <= hi))
    fail(key, "must lie in [" + fmtValue(lo) + ", " + fmtValue(hi) + "] (got " + fmtValue(value) + ")");
}

void DocReader::finish() const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (used_.count(key)) continue;
    std::set<std::string> known = asked_;
    known.insert(used_.begin(), used_.end());
    const std::vector<std::string> close = closeNames(key, std::vector<std::string>(known.begin(), known.end()));
    std::string hint;
    for (const std::string& c : close) hint += (hint.empty() ? " (did you mean '" : "' or '") + keyPath(c);
    failAt(it->first, keyPath(key), "unknown key" + (hint.empty() ? hint : hint + "'?)"));
  }
}

}  // namespace myo
