#include <array>
// OBJ reading: a line scan that validates every line (so faults name their line), then
// tinyobjloader over the sanitised text for the actual values, then triangulation and the
// mesh-level checks (degenerate triangles, non-manifold edges, orientation).
#include "myoshell/mesh/obj_reader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "myoshell/core/check.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/text_lines.h"
#include "myoshell/core/whole_file.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/geometry.h"
#include "myoshell/mesh/mesh_stats.h"

namespace myo {

int MeshReport::count(const std::string& kind) const {
  return static_cast<int>(std::count_if(faults.begin(), faults.end(),
                                        [&](const MeshFault& f) { return f.kind == kind; }));
}

namespace {


struct Corner {
  int v = -1, vt = -1, vn = -1;  // 0-based; -1 when absent
};

// One face line of the file that passed the line checks.
struct ScannedFace {
  int line = 0;
  std::vector<Corner> corners;
  std::vector<std::string> groups;  // active `g` names and `o` name
};

enum class LineKind { kOther, kVertex, kTexcoord, kNormal, kFace };

// What the line scan learns about the file, before tinyobjloader reads it.
struct ObjScan {
  std::vector<std::string_view> lines;
  std::vector<LineKind> kinds;
  std::vector<char> drop;           // per line: replace by a placeholder (bad v/vt/vn) or blank (bad f)
  std::vector<ScannedFace> faces;   // faces that passed the line checks, file order
  std::vector<MeshFault> faults;
  int vCount = 0, vtCount = 0, vnCount = 0;
  // Our own correctly rounded values (tinyobjloader's parser can be off by an ulp, which would
  // break exact round trips); NaN where a line was unreadable. tinyobjloader's are cross-checked.
  std::vector<Vec3> positions;
  std::vector<Vec2> texcoords;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> tokens(std::string_view s) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// The whole token must be a number; from_chars accepts "nan"/"inf", which the caller reports.
bool parseDouble(std::string_view t, double& out) {
  // One optional sign: from_chars takes '-' but not '+', so a leading '+' is dropped here; "+-4"
  // is not a number.
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && t.front() == '-') return false;
  }
  if (t.empty()) return false;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  if (ec == std::errc::result_out_of_range) {
    // Overflow ("1e400") reads as ±inf, which the caller reports; underflow ("1e-400") as the
    // nearest double (0 or subnormal), as strtod rounds it.
    out = std::strtod(std::string(t).c_str(), nullptr);
    return p == t.data() + t.size();
  }
  return ec == std::errc() && p == t.data() + t.size();
}

bool parseInt(std::string_view t, int& out) {
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && t.front() == '-') return false;
  }
  if (t.empty()) return false;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
  return ec == std::errc() && p == t.data() + t.size();
}

std::string quoted(std::string_view s) {
  constexpr size_t kMax = 40;
  return "'" + std::string(s.substr(0, kMax)) + (s.size() > kMax ? "…'" : "'");
}

// Resolves one OBJ index (1-based, or negative = relative to the elements read so far).
// Positive indices may point forward (some exporters write faces first); they are range-checked
// once the whole file is scanned.
bool resolveIndex(int raw, int countSoFar, int& out) {
  if (raw > 0) {
    out = raw - 1;
    return true;
  }
  if (raw < 0 && countSoFar + raw >= 0) {
    out = countSoFar + raw;
    return true;
  }
  return false;
}

ObjScan scanObj(const std::string& text, const std::string& name) {
  ObjScan scan;
  // Split as tinyobjloader splits (core/text_lines.h): the two must agree on every line, since
  // tinyobjloader reads our sanitised text and we cross-check it.
  scan.lines = splitLines(text, name);
  const size_t nLines = scan.lines.size();
  scan.kinds.assign(nLines, LineKind::kOther);
  scan.drop.assign(nLines, 0);
  std::vector<std::string> groupNames, objectName;
  auto fault = [&](const char* kind, int line, std::string msg) {
    scan.faults.push_back({kind, std::move(msg), line});
  };

  for (size_t li = 0; li < nLines; ++li) {
    const int line = static_cast<int>(li + 1);
    // Comments run to the end of the line; tinyobjloader then sees the stripped line too.
    std::string_view s = scan.lines[li];
    if (const size_t hash = s.find('#'); hash != std::string_view::npos) s = s.substr(0, hash);
    s = trim(s);
    scan.lines[li] = s;
    if (s.empty()) continue;
    auto tok = tokens(s);
    const std::string_view key = tok[0];
    if (key == "v" || key == "vt" || key == "vn") {
      const bool isV = key == "v", isVt = key == "vt";
      scan.kinds[li] = isV ? LineKind::kVertex : isVt ? LineKind::kTexcoord : LineKind::kNormal;
      const size_t need = isVt ? 1 : 3;
      const int index = isV ? scan.vCount++ : isVt ? scan.vtCount++ : scan.vnCount++;
      Vec3 value = Vec3::Zero();  // a "vt u" line has v = 0, as tinyobjloader reads it
      bool ok = true;
      if (tok.size() - 1 < need) {
        fault("unreadable_number", line,
              std::string(key) + " line has " + std::to_string(tok.size() - 1) +
                  " numbers, expected at least " + std::to_string(need));
        ok = false;
      }
      for (size_t k = 1; ok && k < tok.size(); ++k) {
        double x;
        if (!parseDouble(tok[k], x)) {
          fault("unreadable_number", line, "unreadable number " + quoted(tok[k]));
          ok = false;
        } else if (k <= 3) {
          value[static_cast<int>(k - 1)] = x;
        }
      }
      if (!ok) value.setConstant(std::numeric_limits<double>::quiet_NaN());
      if (isV) scan.positions.push_back(value);  // kept even when bad (NaN): order must not shift
      if (isVt) scan.texcoords.push_back(value.head<2>());
      if (ok && isV && !value.allFinite()) {
        fault("non_finite_coordinate", line,
              "vertex " + std::to_string(index) + " has a non-finite coordinate");
        scan.drop[li] = 1;
      } else if (!ok) {
        scan.drop[li] = 1;
      }
    } else if (key == "f") {
      scan.kinds[li] = LineKind::kFace;
      ScannedFace face;
      face.line = line;
      bool ok = true;
      for (size_t k = 1; ok && k < tok.size(); ++k) {
        std::string_view t = tok[k];
        std::string_view parts[3];
        int nParts = 0;
        size_t start = 0;
        while (nParts < 3) {
          size_t slash = t.find('/', start);
          parts[nParts++] = t.substr(start, slash == std::string_view::npos ? t.npos : slash - start);
          if (slash == std::string_view::npos) break;
          start = slash + 1;
          if (nParts == 3) {  // a fourth part
            ok = false;
          }
        }
        if (!ok || parts[0].empty()) {
          fault("unreadable_number", line, "unreadable face corner " + quoted(t));
          ok = false;
          break;
        }
        Corner c;
        const int counts[3] = {scan.vCount, scan.vtCount, scan.vnCount};
        int* slots[3] = {&c.v, &c.vt, &c.vn};
        static const char* const kWhat[3] = {"vertex", "texture coordinate", "normal"};
        for (int p = 0; ok && p < nParts; ++p) {
          if (parts[p].empty()) continue;  // "1//3"
          int raw;
          if (!parseInt(parts[p], raw)) {
            fault("unreadable_number", line, "unreadable index " + quoted(parts[p]) + " in face corner " + quoted(t));
            ok = false;
          } else if (raw == 0) {
            fault("index_out_of_range", line,
                  std::string(kWhat[p]) + " index 0 is out of range (OBJ indices start at 1)");
            ok = false;
          } else if (!resolveIndex(raw, counts[p], *slots[p])) {
            fault("index_out_of_range", line,
                  std::string(kWhat[p]) + " index " + std::to_string(raw) + " is out of range: only " +
                      std::to_string(counts[p]) + " precede this line");
            ok = false;
          }
        }
        face.corners.push_back(c);
      }
      if (ok && face.corners.size() < 3) {
        fault("too_few_vertices", line,
              "face has " + std::to_string(face.corners.size()) + " vertices, at least 3 are needed");
        ok = false;
      }
      if (ok) {
        face.groups = groupNames;
        face.groups.insert(face.groups.end(), objectName.begin(), objectName.end());
        scan.faces.push_back(std::move(face));
      } else {
        scan.drop[li] = 1;
      }
    } else if (key == "g") {
      groupNames.assign(tok.begin() + 1, tok.end());
    } else if (key == "o") {
      groupNames.clear();  // a new object starts outside any group
      objectName.clear();
      if (tok.size() > 1) objectName.emplace_back(s.substr(tok[1].data() - s.data()));
    }
  }

  // Forward references are checked now that the totals are known.
  std::vector<ScannedFace> kept;
  kept.reserve(scan.faces.size());
  for (ScannedFace& face : scan.faces) {
    bool ok = true;
    for (const Corner& c : face.corners) {
      const int idx[3] = {c.v, c.vt, c.vn}, totals[3] = {scan.vCount, scan.vtCount, scan.vnCount};
      static const char* const kWhat[3] = {"vertex", "texture coordinate", "normal"};
      static const char* const kPlural[3] = {"vertices", "texture coordinates", "normals"};
      for (int p = 0; ok && p < 3; ++p) {
        if (idx[p] >= totals[p]) {
          scan.faults.push_back({"index_out_of_range",
                                 std::string(kWhat[p]) + " index " + std::to_string(idx[p] + 1) +
                                     " is out of range: the file has " + std::to_string(totals[p]) +
                                     " " + kPlural[p],
                                 face.line});
          ok = false;
        }
      }
      if (!ok) break;
    }
    if (ok) kept.push_back(std::move(face));
    else scan.drop[static_cast<size_t>(face.line - 1)] = 1;
  }
  scan.faces = std::move(kept);
  std::stable_sort(scan.faults.begin(), scan.faults.end(),
                   [](const MeshFault& a, const MeshFault& b) { return a.line < b.line; });
  return scan;
}

// The file as tinyobjloader should see it: faulty element lines become harmless placeholders
// (so indices do not shift) and faulty faces become blank lines. Good positions, texture
// coordinates and faces are rewritten from the scan, in one canonical spelling (shortest
// round-trip numbers; absolute indices "v", "v/vt", "v//vn", "v/vt/vn"): tinyobjloader reads some
// spellings differently from us ("+-4" as 0; in "f 1 2/ 7" it takes 7 as the texture coordinate
// of "2/"), and a user's odd file must give an InputError or a mesh, never a failed cross-check.
std::string sanitisedText(const ObjScan& scan) {
  std::string out;
  size_t total = 0;
  for (auto l : scan.lines) total += l.size() + 1;
  out.reserve(total);
  std::vector<const ScannedFace*> faceOnLine(scan.lines.size(), nullptr);
  for (const ScannedFace& face : scan.faces) faceOnLine[static_cast<size_t>(face.line - 1)] = &face;
  auto number = [&out](double x) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    out += ' ';
    out.append(buf, r.ptr);
  };
  size_t vertex = 0, texcoord = 0;  // ordinal of the next v / vt line (bad ones included)
  for (size_t i = 0; i < scan.lines.size(); ++i) {
    if (scan.kinds[i] == LineKind::kVertex) {
      const Vec3& p = scan.positions[vertex++];
      if (!scan.drop[i]) {
        out += 'v';
        for (int k = 0; k < 3; ++k) number(p[k]);
        out += '\n';
        continue;
      }
    } else if (scan.kinds[i] == LineKind::kTexcoord) {
      const Vec2& t = scan.texcoords[texcoord++];
      if (!scan.drop[i]) {
        out += "vt";
        for (int k = 0; k < 2; ++k) number(t[k]);
        out += '\n';
        continue;
      }
    }
    if (!scan.drop[i] && scan.kinds[i] == LineKind::kFace) {
      MYO_CHECK(faceOnLine[i] != nullptr, "a kept face line without its scanned face, line " << i + 1);
      out += 'f';
      for (const Corner& c : faceOnLine[i]->corners) {
        out += ' ';
        out += std::to_string(c.v + 1);
        if (c.vt >= 0 || c.vn >= 0) out += '/';
        if (c.vt >= 0) out += std::to_string(c.vt + 1);
        if (c.vn >= 0) out += '/' + std::to_string(c.vn + 1);
      }
    } else if (!scan.drop[i]) {
      out.append(scan.lines[i]);
    } else {
      switch (scan.kinds[i]) {
        case LineKind::kVertex: out += "v 0 0 0"; break;
        case LineKind::kTexcoord: out += "vt 0 0"; break;
        case LineKind::kNormal: out += "vn 0 0 1"; break;
        default: break;
      }
    }
    out += '\n';
  }
  return out;
}

// Everything read from an OBJ, before triangulation.
struct ParsedObj {
  MatX3 V;
  MatX2 UV;
  std::vector<std::vector<int>> polygons;
  // Per polygon corner, the 0-based texture coordinate index (-1 when the corner has none), and
  // the texture coordinates they index; the triangulation turns them into TriMesh::cornerUV.
  std::vector<std::vector<int>> polygonTexcoords;
  std::vector<Vec2> texcoords;
  std::vector<int> polygonLine;
  std::map<std::string, std::vector<int>> groups;
  std::vector<MeshFault> faults;  // line faults, file order
};

ParsedObj parseObj(const std::string& text, const std::string& name) {
  ObjScan scan = scanObj(text, name);
  ParsedObj out;
  out.faults = std::move(scan.faults);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream in(sanitisedText(scan));
  // triangulate = false: we triangulate ourselves (shorter diagonal), and need the polygons.
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, nullptr,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok) throw InputError("cannot parse OBJ: " + err, name);

  const int n = static_cast<int>(attrib.vertices.size() / 3);
  MYO_CHECK_EQ(n, scan.vCount);
  out.V.resize(n, 3);
  auto agree = [](double ours, double theirs) {
    return std::abs(ours - theirs) <= 1e-12 * std::max(1.0, std::abs(ours));
  };
  for (int i = 0; i < n; ++i) {
    out.V.row(i) = scan.positions[static_cast<size_t>(i)].transpose();
    for (int k = 0; k < 3 && out.V.row(i).allFinite(); ++k)  // bad lines reach it as "v 0 0 0"
      MYO_CHECK(agree(out.V(i, k), static_cast<double>(attrib.vertices[3 * i + k])),
                "vertex " << i << ": tinyobjloader read " << attrib.vertices[3 * i + k] << ", we read "
                          << out.V(i, k));
  }

  // tinyobjloader keeps shapes and their faces in file order: concatenated they are our faces.
  size_t f = 0;
  for (const auto& shape : shapes) {
    size_t offset = 0;
    for (size_t k = 0; k < shape.mesh.num_face_vertices.size(); ++k, ++f) {
      const size_t nv = shape.mesh.num_face_vertices[k];
      MYO_CHECK(f < scan.faces.size(), "tinyobjloader returned more faces than the scan found");
      const ScannedFace& face = scan.faces[f];
      MYO_CHECK_EQ(nv, face.corners.size());
      for (size_t c = 0; c < nv; ++c) {
        const auto& idx = shape.mesh.indices[offset + c];
        MYO_CHECK_EQ(idx.vertex_index, face.corners[c].v);
        MYO_CHECK_EQ(idx.texcoord_index, face.corners[c].vt);
      }
      offset += nv;
    }
  }
  MYO_CHECK_EQ(f, scan.faces.size());

  // UV per vertex: the texture coordinate of the first face corner that references the vertex.
  const int nvt = static_cast<int>(attrib.texcoords.size() / 2);
  MYO_CHECK_EQ(nvt, static_cast<int>(scan.texcoords.size()));
  bool anyUv = false;
  std::vector<char> assigned(static_cast<size_t>(n), 0);
  MatX2 uv = MatX2::Zero(n, 2);
  out.polygons.reserve(scan.faces.size());
  out.polygonTexcoords.reserve(scan.faces.size());
  out.polygonLine.reserve(scan.faces.size());
  for (const ScannedFace& face : scan.faces) {
    std::vector<int> poly, polyTexcoords;
    poly.reserve(face.corners.size());
    polyTexcoords.reserve(face.corners.size());
    for (const Corner& c : face.corners) {
      poly.push_back(c.v);
      polyTexcoords.push_back(c.vt >= 0 && c.vt < nvt ? c.vt : -1);
      if (c.vt >= 0 && c.vt < nvt && !assigned[c.v]) {
        assigned[c.v] = 1;
        anyUv = true;
        uv.row(c.v) = scan.texcoords[static_cast<size_t>(c.vt)].transpose();
      }
    }
    for (const std::string& g : face.groups) {
      auto& set = out.groups[g];
      set.insert(set.end(), poly.begin(), poly.end());
    }
    out.polygons.push_back(std::move(poly));
    out.polygonTexcoords.push_back(std::move(polyTexcoords));
    out.polygonLine.push_back(face.line);
  }
  if (anyUv) {
    out.UV = std::move(uv);
    out.texcoords = std::move(scan.texcoords);
  }
  for (auto& [g, set] : out.groups) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  return out;
}

// Triangles of the polygons over rest positions: quads along the shorter diagonal (ties: v0–v2),
// larger polygons as a fan from their first vertex. polygonCorner (3m) receives, for corner c of
// triangle t, the position within its polygon of the corner it came from (row 3t + c), so that
// per-corner data (texture coordinates) follows the triangulation.
void triangulate(const MatX3& Vrest, const std::vector<std::vector<int>>& polygons, MatX3i& F,
                 std::vector<int>& source, std::vector<int>& polygonCorner) {
  size_t m = 0;
  for (const auto& p : polygons) m += p.size() - 2;
  F.resize(static_cast<Eigen::Index>(m), 3);
  source.clear();
  source.reserve(m);
  polygonCorner.clear();
  polygonCorner.reserve(3 * m);
  Eigen::Index t = 0;
  for (size_t pi = 0; pi < polygons.size(); ++pi) {
    const auto& p = polygons[pi];
    auto add = [&](size_t a, size_t b, size_t c) {
      F.row(t++) << p[a], p[b], p[c];
      source.push_back(static_cast<int>(pi));
      for (size_t k : {a, b, c}) polygonCorner.push_back(static_cast<int>(k));
    };
    if (p.size() == 4) {
      const double d02 = (Vrest.row(p[0]) - Vrest.row(p[2])).squaredNorm();
      const double d13 = (Vrest.row(p[1]) - Vrest.row(p[3])).squaredNorm();
      if (!(d13 < d02)) {  // ties (and NaN) take v0–v2
        add(0, 1, 2);
        add(0, 2, 3);
      } else {
        add(0, 1, 3);
        add(1, 2, 3);
      }
    } else {
      for (size_t k = 1; k + 1 < p.size(); ++k) add(0, k, k + 1);
    }
  }
}

// TriMesh::cornerUV from the polygons' texture coordinate indices: a corner without one (a file
// that gives `vt` on some faces only) takes its vertex's UV, so that a mesh with texture
// coordinates has them on every corner. Empty when the file has no texture coordinates.
MatX2 cornerTexcoords(const ParsedObj& parsed, const MatX2& vertexUV, const std::vector<int>& source,
                      const std::vector<int>& polygonCorner, const MatX3i& F) {
  if (vertexUV.rows() == 0) return MatX2(0, 2);
  MatX2 out(3 * F.rows(), 2);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const size_t row = static_cast<size_t>(3 * t + c);
      const int vt = parsed.polygonTexcoords[static_cast<size_t>(source[static_cast<size_t>(t)])]
                                            [static_cast<size_t>(polygonCorner[row])];
      if (vt >= 0)
        out.row(static_cast<Eigen::Index>(row)) = parsed.texcoords[static_cast<size_t>(vt)].transpose();
      else
        out.row(static_cast<Eigen::Index>(row)) = vertexUV.row(F(t, c));
    }
  return out;
}

std::string faceWhere(const TriMesh& mesh, const std::vector<int>* polygonLine, int t, int& line) {
  line = 0;
  std::string s = "triangle " + std::to_string(t);
  if (polygonLine && t < static_cast<int>(mesh.sourcePolygon.size())) {
    line = (*polygonLine)[static_cast<size_t>(mesh.sourcePolygon[static_cast<size_t>(t)])];
    s += " (face on line " + std::to_string(line) + ")";
  }
  return s;
}

// Mesh-level faults: non-finite positions (when asked), no faces, degenerate triangles,
// non-manifold edges, inconsistent orientation. polygonLine (optional) maps polygons to lines.
std::vector<MeshFault> meshFaults(const TriMesh& mesh, const std::vector<int>* polygonLine,
                                  bool checkFinite) {
  std::vector<MeshFault> faults;
  if (checkFinite)
    for (int i = 0; i < mesh.vertexCount(); ++i)
      if (!mesh.V.row(i).allFinite())
        faults.push_back({"non_finite_coordinate",
                          "vertex " + std::to_string(i) + " has a non-finite coordinate", 0});
  if (mesh.triangleCount() == 0) {
    faults.push_back({"no_faces", "the mesh has no faces", 0});
    return faults;
  }
  for (int t : degenerateTriangles(mesh.V, mesh.F)) {
    int line;
    std::string where = faceWhere(mesh, polygonLine, t, line);
    std::ostringstream os;
    os << where << " is degenerate (area "
       << triangleArea(mesh.V.row(mesh.F(t, 0)), mesh.V.row(mesh.F(t, 1)), mesh.V.row(mesh.F(t, 2)))
       << " cm², below " << kDegenerateAreaTolerance << " × bbox diagonal²)";
    faults.push_back({"degenerate_triangle", os.str(), line});
  }

  // Two used vertices at exactly the same position split the surface there: a crack that the
  // shell cannot see (typical of scans exported per patch). Weld them before simulating.
  {
    std::vector<char> used(static_cast<size_t>(mesh.vertexCount()), 0);
    for (int t = 0; t < mesh.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) used[static_cast<size_t>(mesh.F(t, k))] = 1;
    struct PositionHash {
      size_t operator()(const std::array<double, 3>& p) const {
        size_t h = 0;
        for (double x : p) h = h * 1000003u ^ std::hash<double>()(x);
        return h;
      }
    };
    std::unordered_map<std::array<double, 3>, int, PositionHash> first;
    for (int i = 0; i < mesh.vertexCount(); ++i) {
      if (!used[static_cast<size_t>(i)] || !mesh.V.row(i).allFinite()) continue;
      const std::array<double, 3> p{mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)};
      auto [it, inserted] = first.try_emplace(p, i);
      if (!inserted) {
        std::ostringstream os;
        os << "vertex " << i << " duplicates vertex " << it->second << " at (" << p[0] << ", " << p[1] << ", " << p[2]
           << "): the surface is split there (weld duplicate vertices before simulating)";
        faults.push_back({"duplicate_vertex", os.str(), 0});
      }
    }
  }

  const EdgeTable table = buildEdgeTable(mesh.F, mesh.vertexCount());
  auto edgeName = [](int a, int b) {
    return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
  };
  if (table.nonManifoldCount > 0) {
    // The edge table keeps two faces per edge; find the third (and later) ones here.
    auto key = [](int a, int b) {
      return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint64_t>(std::max(a, b));
    };
    std::unordered_map<uint64_t, int> seen;
    for (int t = 0; t < mesh.triangleCount(); ++t)
      for (int j = 0; j < 3; ++j) {
        const int a = mesh.F(t, j), b = mesh.F(t, (j + 1) % 3);
        if (++seen[key(a, b)] == 3) {
          int line;
          std::string where = faceWhere(mesh, polygonLine, t, line);
          faults.push_back({"non_manifold_edge",
                            edgeName(std::min(a, b), std::max(a, b)) +
                                " is shared by more than two faces (non-manifold; " + where + " is the third)",
                            line});
        }
      }
  }
  for (const Edge& e : table.edges) {
    if (e.face[1] < 0) continue;
    const int t = e.face[1];
    bool sameWay = false;
    for (int j = 0; j < 3; ++j)
      if (mesh.F(t, j) == e.v[0] && mesh.F(t, (j + 1) % 3) == e.v[1]) sameWay = true;
    if (!sameWay) continue;
    int line0, line1;
    std::string w0 = faceWhere(mesh, polygonLine, e.face[0], line0);
    std::string w1 = faceWhere(mesh, polygonLine, t, line1);
    faults.push_back({"inconsistent_orientation",
                      edgeName(e.v[0], e.v[1]) + " runs the same way in " + w0 + " and " + w1 +
                          " (inconsistent orientation)",
                      line1});
  }
  return faults;
}

void throwFirst(const std::vector<MeshFault>& faults, const std::string& name) {
  if (!faults.empty()) throw InputError(faults.front().message, name, faults.front().line);
}

TriMesh assemble(ParsedObj&& parsed, const std::string& name) {
  TriMesh mesh;
  mesh.V = std::move(parsed.V);
  mesh.UV = std::move(parsed.UV);
  mesh.groups = std::move(parsed.groups);
  mesh.sourcePath = name;
  std::vector<int> polygonCorner;
  triangulate(mesh.V, parsed.polygons, mesh.F, mesh.sourcePolygon, polygonCorner);
  mesh.cornerUV = cornerTexcoords(parsed, mesh.UV, mesh.sourcePolygon, polygonCorner, mesh.F);
  mesh.polygons = std::move(parsed.polygons);
  return mesh;
}

TriMesh readStrict(const std::string& text, const std::string& name) {
  ParsedObj parsed = parseObj(text, name);
  throwFirst(parsed.faults, name);
  std::vector<int> lines = std::move(parsed.polygonLine);
  TriMesh mesh = assemble(std::move(parsed), name);
  throwFirst(meshFaults(mesh, &lines, /*checkFinite=*/false), name);
  return mesh;
}

TriMesh readLenient(const std::string& text, MeshReport& report, const std::string& name) {
  ParsedObj parsed = parseObj(text, name);
  std::vector<MeshFault> faults = std::move(parsed.faults);
  std::vector<int> lines = std::move(parsed.polygonLine);
  TriMesh mesh = assemble(std::move(parsed), name);
  for (MeshFault& f : meshFaults(mesh, &lines, /*checkFinite=*/false)) faults.push_back(std::move(f));
  // File order; faults not tied to a line last.
  std::stable_sort(faults.begin(), faults.end(), [](const MeshFault& a, const MeshFault& b) {
    const int la = a.line > 0 ? a.line : std::numeric_limits<int>::max();
    const int lb = b.line > 0 ? b.line : std::numeric_limits<int>::max();
    return la < lb;
  });
  report.faults.insert(report.faults.end(), faults.begin(), faults.end());
  return mesh;
}

// True when faces[start, start + k − 2) are triangles that tile rest polygon P (k vertices) with
// P's orientation: every corner a vertex of P, in P's cyclic order, every vertex of P used.
bool triangulatesPolygon(const std::vector<int>& P, const std::vector<std::vector<int>>& faces,
                         size_t start) {
  const size_t k = P.size();
  if (k < 4 || start + k - 2 > faces.size()) return false;
  std::vector<char> covered(k, 0);
  for (size_t i = 0; i < k - 2; ++i) {
    const auto& f = faces[start + i];
    if (f.size() != 3) return false;
    long pos[3];
    for (int j = 0; j < 3; ++j) {
      auto it = std::find(P.begin(), P.end(), f[static_cast<size_t>(j)]);
      if (it == P.end()) return false;
      pos[j] = it - P.begin();
      covered[static_cast<size_t>(pos[j])] = 1;
    }
    // Same winding as P: the corners rise in P's cyclic order from the smallest one.
    const int m = static_cast<int>(std::min_element(pos, pos + 3) - pos);
    if (!(pos[m] < pos[(m + 1) % 3] && pos[(m + 1) % 3] < pos[(m + 2) % 3])) return false;
  }
  return std::all_of(covered.begin(), covered.end(), [](char c) { return c != 0; });
}

std::string polygonText(const std::vector<int>& p) {
  std::string s;
  for (size_t i = 0; i < p.size(); ++i) s += (i ? " " : "") + std::to_string(p[i]);
  return s;
}

}  // namespace

TriMesh readObj(const std::string& path) { return readStrict(readWholeFile(path), path); }

TriMesh readObjLenient(const std::string& path, MeshReport& report) {
  return readLenient(readWholeFile(path), report, path);
}

TriMesh readObjFromString(const std::string& text, const std::string& name) {
  return readStrict(text, name);
}

TriMesh readObjFromStringLenient(const std::string& text, MeshReport& report, const std::string& name) {
  return readLenient(text, report, name);
}

TriMesh readObjLike(const std::string& path, const TriMesh& rest) {
  return readObjLikeFromString(readWholeFile(path), rest, path);
}

TriMesh readObjLikeFromString(const std::string& text, const TriMesh& rest, const std::string& path) {
  ParsedObj parsed = parseObj(text, path);
  throwFirst(parsed.faults, path);
  if (parsed.V.rows() != rest.V.rows())
    throw InputError("has " + std::to_string(parsed.V.rows()) + " vertices but the rest mesh" +
                         (rest.sourcePath.empty() ? "" : " " + rest.sourcePath) + " has " +
                         std::to_string(rest.V.rows()),
                     path);
  // The rest mesh's polygons (its triangles when it was built in memory).
  std::vector<std::vector<int>> restPolygons = rest.polygons;
  if (restPolygons.empty())
    for (int t = 0; t < rest.triangleCount(); ++t)
      restPolygons.push_back({rest.F(t, 0), rest.F(t, 1), rest.F(t, 2)});
  // Each rest polygon must appear as itself or as triangles tiling it (ICT's expression shapes
  // come pre-triangulated); either way the rest triangulation is used.
  size_t f = 0;
  for (size_t i = 0; i < restPolygons.size(); ++i) {
    const auto& P = restPolygons[i];
    if (f < parsed.polygons.size() && parsed.polygons[f] == P) {
      ++f;
    } else if (triangulatesPolygon(P, parsed.polygons, f)) {
      f += P.size() - 2;
    } else if (f < parsed.polygons.size()) {
      throw InputError("face " + std::to_string(f) + " (" + polygonText(parsed.polygons[f]) +
                           ") differs from the rest mesh's polygon " + std::to_string(i) + " (" +
                           polygonText(P) +
                           "); a shape must share the rest mesh's polygons (0-based vertex indices)",
                       path, parsed.polygonLine[f]);
    } else {
      throw InputError("has " + std::to_string(parsed.polygons.size()) +
                           " faces, fewer than the rest mesh's " + std::to_string(restPolygons.size()) +
                           " polygons (a shape must share the rest mesh's polygons)",
                       path);
    }
  }
  if (f != parsed.polygons.size())
    throw InputError("has more faces than the rest mesh's " + std::to_string(restPolygons.size()) +
                         " polygons (a shape must share the rest mesh's polygons)",
                     path, parsed.polygonLine[f]);
  TriMesh mesh;
  mesh.V = std::move(parsed.V);
  // The shape's own texture coordinates, when it has any, are kept per vertex only: its corners
  // (perhaps pre-triangulated) do not map onto the rest triangulation, so its corner UVs are
  // unknown. Without any, it shares the rest's texture layout, seams included.
  mesh.cornerUV = parsed.UV.rows() ? MatX2(0, 2) : rest.cornerUV;
  mesh.UV = parsed.UV.rows() ? std::move(parsed.UV) : rest.UV;
  mesh.F = rest.F;  // the rest triangulation, never re-chosen from deformed positions
  mesh.sourcePolygon = rest.sourcePolygon;
  if (mesh.sourcePolygon.empty())
    for (int t = 0; t < rest.triangleCount(); ++t) mesh.sourcePolygon.push_back(t);
  mesh.polygons = rest.polygons;
  mesh.groups = parsed.groups.empty() ? rest.groups : std::move(parsed.groups);
  mesh.sourcePath = path;
  return mesh;
}

void validateMesh(const TriMesh& mesh) {
  throwFirst(meshFaults(mesh, nullptr, /*checkFinite=*/true),
             mesh.sourcePath.empty() ? std::string("<mesh>") : mesh.sourcePath);
}

}  // namespace myo
