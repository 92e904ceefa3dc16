// Vertex sets from JSON, with errors that point at the offending line.
#include "myoshell/mesh/vertex_set.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "myoshell/core/errors.h"

namespace myo {

namespace {

// 1-based line and column of byte offset `pos` (0-based) in text.
std::pair<int, int> lineColumn(const std::string& text, size_t pos) {
  pos = std::min(pos, text.size());
  int line = 1, col = 1;
  for (size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

size_t skipSpace(const std::string& s, size_t i) {
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
  return i;
}

// Index just past the JSON string starting at s[i] == '"'.
size_t skipString(const std::string& s, size_t i) {
  for (++i; i < s.size(); ++i) {
    if (s[i] == '\\') ++i;
    else if (s[i] == '"') return i + 1;
  }
  return s.size();
}

// Offset of the index list's value: the top-level value, or the value of the top-level
// "vertices" key. npos when not found (the caller then reports no line).
size_t findListStart(const std::string& s) {
  size_t i = skipSpace(s, 0);
  if (i < s.size() && s[i] != '{') return i;
  int depth = 0;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"') {
      const size_t end = skipString(s, i);
      if (depth == 1 && s.compare(i, end - i, "\"vertices\"") == 0) {
        size_t j = skipSpace(s, end);
        if (j < s.size() && s[j] == ':') {
          j = skipSpace(s, j + 1);
          if (j < s.size()) return j;
        }
      }
      i = end - 1;
    } else if (c == '{' || c == '[') {
      ++depth;
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return std::string::npos;
}

// Offset of element k of the array starting at s[open] == '['.
size_t findElement(const std::string& s, size_t open, size_t k) {
  if (open == std::string::npos || s[open] != '[') return std::string::npos;
  size_t i = skipSpace(s, open + 1), seen = 0;
  int depth = 0;
  if (k == 0) return i;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"') {
      i = skipString(s, i) - 1;
    } else if (c == '{' || c == '[') {
      ++depth;
    } else if (c == '}' || c == ']') {
      if (depth-- == 0) return std::string::npos;
    } else if (c == ',' && depth == 0 && ++seen == k) {
      return skipSpace(s, i + 1);
    }
  }
  return std::string::npos;
}

// Where the number quoted in nlohmann's "number overflow parsing '1e400'" first occurs (npos if not).
size_t numberPosition(const std::string& text, const std::string& what) {
  const size_t q1 = what.find('\''), q2 = what.rfind('\'');
  if (q1 == std::string::npos || q2 <= q1) return std::string::npos;
  return text.find(what.substr(q1 + 1, q2 - q1 - 1));
}

[[noreturn]] void fail(const std::string& text, const std::string& name, size_t pos,
                       const std::string& message) {
  if (pos == std::string::npos) throw InputError(message, name);
  auto [line, col] = lineColumn(text, pos);
  throw InputError(message, name, line, col);
}

}  // namespace

std::vector<int> parseVertexSet(const std::string& jsonText, int vertexCount, const std::string& name) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(jsonText);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based position of the last character read.
    std::string what = e.what();
    const size_t colon = what.find(": ", what.find("parse error"));
    if (colon != std::string::npos) what = what.substr(colon + 2);
    fail(jsonText, name, e.byte > 0 ? e.byte - 1 : 0, "invalid JSON: " + what);
  } catch (const nlohmann::json::exception& e) {
    // A number beyond double's range ("number overflow parsing '1e400'") comes without a position.
    std::string what = e.what();
    if (const size_t bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
    fail(jsonText, name, numberPosition(jsonText, what), "invalid JSON: " + what);
  }
  const nlohmann::json* list = &doc;
  if (doc.is_object()) {
    auto it = doc.find("vertices");
    if (it == doc.end())
      throw InputError("expected a list of integer vertex indices or an object with a \"vertices\" list",
                       name, 1);
    list = &*it;
  }
  const size_t listStart = findListStart(jsonText);
  if (!list->is_array())
    fail(jsonText, name, listStart, "expected a list of integer vertex indices");
  std::vector<int> out;
  out.reserve(list->size());
  for (size_t k = 0; k < list->size(); ++k) {
    const nlohmann::json& v = (*list)[k];
    if (!v.is_number_integer())
      fail(jsonText, name, findElement(jsonText, listStart, k),
           "expected a list of integer vertex indices (element " + std::to_string(k) + " is " +
               v.dump().substr(0, 40) + ")");
    // An unsigned integer above INT64_MAX would wrap to a negative long long: compare it unsigned.
    const bool inRange = v.is_number_unsigned()
                             ? v.get<unsigned long long>() < static_cast<unsigned long long>(std::max(vertexCount, 0))
                             : v.get<long long>() >= 0 && v.get<long long>() < vertexCount;
    if (!inRange)
      fail(jsonText, name, findElement(jsonText, listStart, k),
           "index " + v.dump() + " out of range [0, " + std::to_string(vertexCount) + ")");
    out.push_back(static_cast<int>(v.get<long long>()));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace myo
