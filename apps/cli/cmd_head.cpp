// `myoshell head [default|OBJ|DIR] [--landmarks FILE] [--pins FILE] [--json] [--render PNG]`:
// loads a head, reports its counts, landmarks, face frame and gravity pins, and renders a picture
// with the landmarks (and optionally the pins) marked.
//
// The picture comes from a small software rasterizer (orthographic, flat Lambert shading, z-buffer,
// 2×2 supersampling) and a self-contained PNG writer (fixed-Huffman deflate with run matches), kept
// here until the render layer lands. Markers: Multi-PIE 68 points red, named landmarks blue,
// gravity pins green (--pins-marked); a named landmark that is also a Multi-PIE point shows as a blue
// dot in a red ring; markers hidden behind the surface are not drawn.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "command.h"
#include "myoshell/core/errors.h"
#include "myoshell/face/head.h"
#include "myoshell/mesh/edge_table.h"
#include "myoshell/mesh/subdivision.h"

namespace myo::cli {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// PNG writer: 8-bit RGB, filter "Sub" on every row, zlib stream with one fixed-Huffman deflate
// block whose matches are runs (distance 1..3) or the row above.

class BitWriter {
 public:
  void bits(std::uint32_t value, int count) {  // LSB first
    for (int i = 0; i < count; ++i) bit((value >> i) & 1u);
  }
  void huffman(std::uint32_t code, int length) {  // MSB first
    for (int i = length - 1; i >= 0; --i) bit((code >> i) & 1u);
  }
  std::vector<std::uint8_t> finish() {
    if (n_) out_.push_back(cur_);
    n_ = 0;
    cur_ = 0;
    return std::move(out_);
  }

 private:
  void bit(std::uint32_t b) {
    cur_ |= static_cast<std::uint8_t>(b << n_);
    if (++n_ == 8) {
      out_.push_back(cur_);
      cur_ = 0;
      n_ = 0;
    }
  }
  std::vector<std::uint8_t> out_;
  std::uint8_t cur_ = 0;
  int n_ = 0;
};

void fixedLiteral(BitWriter& w, int sym) {
  if (sym < 144) w.huffman(0x30 + sym, 8);
  else if (sym < 256) w.huffman(0x190 + sym - 144, 9);
  else if (sym < 280) w.huffman(sym - 256, 7);
  else w.huffman(0xc0 + sym - 280, 8);
}

void fixedMatch(BitWriter& w, int length, int distance) {
  static const int lbase[] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                              31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
  static const int lextra[] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                               2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
  static const int dbase[] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,
                              33,  49,  65,  97,  129, 193,  257,  385,  513,  769,
                              1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
  static const int dextra[] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                               6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
  int l = 28;
  while (lbase[l] > length) --l;
  fixedLiteral(w, 257 + l);
  w.bits(static_cast<std::uint32_t>(length - lbase[l]), lextra[l]);
  int d = 29;
  while (dbase[d] > distance) --d;
  w.huffman(static_cast<std::uint32_t>(d), 5);
  w.bits(static_cast<std::uint32_t>(distance - dbase[d]), dextra[d]);
}

std::vector<std::uint8_t> zlibCompress(const std::vector<std::uint8_t>& data, int rowBytes) {
  BitWriter w;
  w.bits(1, 1);  // final block
  w.bits(1, 2);  // fixed Huffman
  const int n = static_cast<int>(data.size());
  const int candidates[] = {1, 2, 3, rowBytes};
  for (int i = 0; i < n;) {
    int bestLen = 0, bestDist = 0;
    for (int d : candidates) {
      if (d > i || d > 32768) continue;
      int len = 0;
      while (len < 258 && i + len < n && data[i + len] == data[i + len - d]) ++len;
      if (len > bestLen) {
        bestLen = len;
        bestDist = d;
      }
    }
    if (bestLen >= 3) {
      fixedMatch(w, bestLen, bestDist);
      i += bestLen;
    } else {
      fixedLiteral(w, data[i]);
      ++i;
    }
  }
  fixedLiteral(w, 256);
  std::vector<std::uint8_t> out = {0x78, 0x01};
  const auto body = w.finish();
  out.insert(out.end(), body.begin(), body.end());
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t c : data) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  const std::uint32_t adler = (b << 16) | a;
  for (int k = 3; k >= 0; --k) out.push_back(static_cast<std::uint8_t>(adler >> (8 * k)));
  return out;
}

std::uint32_t crc32(const std::uint8_t* p, size_t n, std::uint32_t crc = 0) {
  static std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xff] ^ (crc >> 8);
  return ~crc;
}

void writePng(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  const int rowBytes = 3 * width + 1;
  std::vector<std::uint8_t> raw(static_cast<size_t>(rowBytes) * height);
  for (int y = 0; y < height; ++y) {
    std::uint8_t* row = &raw[static_cast<size_t>(y) * rowBytes];
    const std::uint8_t* src = &rgb[static_cast<size_t>(y) * 3 * width];
    row[0] = 1;  // Sub
    for (int x = 0; x < 3 * width; ++x)
      row[1 + x] = static_cast<std::uint8_t>(src[x] - (x >= 3 ? src[x - 3] : 0));
  }
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  auto chunk = [&](const char* type, const std::vector<std::uint8_t>& body) {
    const std::uint32_t len = static_cast<std::uint32_t>(body.size());
    for (int k = 3; k >= 0; --k) png.push_back(static_cast<std::uint8_t>(len >> (8 * k)));
    std::vector<std::uint8_t> tb(type, type + 4);
    tb.insert(tb.end(), body.begin(), body.end());
    png.insert(png.end(), tb.begin(), tb.end());
    const std::uint32_t c = crc32(tb.data(), tb.size());
    for (int k = 3; k >= 0; --k) png.push_back(static_cast<std::uint8_t>(c >> (8 * k)));
  };
  std::vector<std::uint8_t> ihdr;
  for (std::uint32_t v : {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)})
    for (int k = 3; k >= 0; --k) ihdr.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, adaptive filters, no interlace
  chunk("IHDR", ihdr);
  chunk("IDAT", zlibCompress(raw, rowBytes));
  chunk("IEND", {});
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw InputError("cannot write picture", path);
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    if (!out) throw InputError("cannot write picture", path);
  }
  fs::rename(tmp, path);
}

// ---------------------------------------------------------------------------------------------
// Rasterizer.

struct RenderOptions {
  int size = 800;          // output width and height, pixels
  double yawDegrees = 0;   // turn the head about +y before looking at it along −z
  bool wire = false;       // darken triangle edges
  bool markLandmarks = true;
  bool markPins = false;
};

struct Marker {
  int vertex;
  std::array<std::uint8_t, 3> color;
  double radius;  // pixels at output size
};

void renderHead(const Head& head, const RenderOptions& opt, const std::string& path) {
  const int ss = 2, W = opt.size * ss, H = opt.size * ss;
  const TriMesh& m = head.mesh;
  // View: rotate about y by yaw, look along −z (image right = +x', up = +y').
  const double yaw = opt.yawDegrees * std::numbers::pi / 180.0;
  const Mat3 R = Eigen::AngleAxisd(yaw, Vec3::UnitY()).toRotationMatrix();
  MatX3 P(m.vertexCount(), 3);
  for (int i = 0; i < m.vertexCount(); ++i) P.row(i) = (R * Vec3(m.V.row(i))).transpose();
  const Vec3 lo = P.colwise().minCoeff(), hi = P.colwise().maxCoeff();
  const double extent = std::max(hi.x() - lo.x(), hi.y() - lo.y()) * 1.08;
  const double px = W / extent;
  const Vec3 c = 0.5 * (lo + hi);
  auto toScreen = [&](const Vec3& p) {
    return Vec3((p.x() - c.x()) * px + 0.5 * W, (c.y() - p.y()) * px + 0.5 * H, p.z());
  };
  std::vector<double> zbuf(static_cast<size_t>(W) * H, -1e300);
  std::vector<std::array<double, 3>> img(static_cast<size_t>(W) * H, {0.16, 0.17, 0.20});
  const Vec3 light = Vec3(-0.35, 0.45, 1.0).normalized();
  for (int t = 0; t < m.triangleCount(); ++t) {
    const Vec3 a = P.row(m.F(t, 0)), b = P.row(m.F(t, 1)), cc = P.row(m.F(t, 2));
    Vec3 n = (b - a).cross(cc - a);
    if (n.norm() == 0) continue;
    n.normalize();
    const bool front = n.z() >= 0;
    const double lambert = std::abs(n.dot(light));
    std::array<double, 3> base = front ? std::array<double, 3>{0.93, 0.78, 0.68}
                                       : std::array<double, 3>{0.55, 0.60, 0.75};
    std::array<double, 3> col;
    for (int k = 0; k < 3; ++k) col[k] = base[k] * (0.25 + 0.75 * lambert);
    const Vec3 s0 = toScreen(a), s1 = toScreen(b), s2 = toScreen(cc);
    const double area = (s1.x() - s0.x()) * (s2.y() - s0.y()) - (s2.x() - s0.x()) * (s1.y() - s0.y());
    if (std::abs(area) < 1e-12) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s0.x(), s1.x(), s2.x()}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({s0.x(), s1.x(), s2.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s0.y(), s1.y(), s2.y()}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({s0.y(), s1.y(), s2.y()}))));
    const double e01 = (s1 - s0).head<2>().norm(), e12 = (s2 - s1).head<2>().norm(),
                 e20 = (s0 - s2).head<2>().norm();
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double qx = x + 0.5, qy = y + 0.5;
        const double w0 = ((s1.x() - qx) * (s2.y() - qy) - (s2.x() - qx) * (s1.y() - qy)) / area;
        const double w1 = ((s2.x() - qx) * (s0.y() - qy) - (s0.x() - qx) * (s2.y() - qy)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * s0.z() + w1 * s1.z() + w2 * s2.z();
        const size_t idx = static_cast<size_t>(y) * W + x;
        if (z <= zbuf[idx]) continue;
        zbuf[idx] = z;
        std::array<double, 3> pc = col;
        if (opt.wire) {
          // Pixel distance to the nearest edge: w_k · |2·area| / |opposite edge|.
          const double d = std::min({w0 * std::abs(area) / e12, w1 * std::abs(area) / e20,
                                     w2 * std::abs(area) / e01});
          if (d < 0.9 * ss)
            for (double& v : pc) v *= 0.55;
        }
        img[idx] = pc;
      }
  }
  // Markers, drawn where the marked vertex is visible (depth within a tolerance of the surface).
  std::vector<Marker> markers;
  if (opt.markPins)
    for (int v : head.gravityPins) markers.push_back({v, {40, 200, 60}, 2.2});
  if (opt.markLandmarks) {
    for (int v : head.landmarks.multipie68) markers.push_back({v, {230, 30, 30}, 3.5});
    // Named landmarks: a smaller blue dot, drawn on top (a red ring means it is also a Multi-PIE point).
    for (const auto& [name, v] : head.landmarks.named) markers.push_back({v, {40, 110, 255}, 1.8});
  }
  const double tol = 0.02 * extent;
  for (const Marker& mk : markers) {
    const Vec3 s = toScreen(P.row(mk.vertex));
    const int cx = static_cast<int>(s.x()), cy = static_cast<int>(s.y());
    if (cx < 0 || cy < 0 || cx >= W || cy >= H) continue;
    // Visible if the surface around the marker is not much nearer to the camera than the vertex.
    double front = -1e300;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = std::clamp(cx + dx, 0, W - 1), y = std::clamp(cy + dy, 0, H - 1);
        front = std::max(front, zbuf[static_cast<size_t>(y) * W + x]);
      }
    if (s.z() < front - tol) continue;
    const double r = mk.radius * ss;
    for (int y = static_cast<int>(s.y() - r - 2); y <= static_cast<int>(s.y() + r + 2); ++y)
      for (int x = static_cast<int>(s.x() - r - 2); x <= static_cast<int>(s.x() + r + 2); ++x) {
        if (x < 0 || y < 0 || x >= W || y >= H) continue;
        const double d = std::hypot(x + 0.5 - s.x(), y + 0.5 - s.y());
        auto& p = img[static_cast<size_t>(y) * W + x];
        if (d <= r)
          for (int k = 0; k < 3; ++k) p[k] = mk.color[k] / 255.0;
        else if (d <= r + 0.8 * ss)
          p = {0.05, 0.05, 0.05};  // dark outline
      }
  }
  // Downsample ss×ss → output.
  const int w = opt.size, h = opt.size;
  std::vector<std::uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 3; ++k) {
        double sum = 0;
        for (int j = 0; j < ss; ++j)
          for (int i = 0; i < ss; ++i) sum += img[static_cast<size_t>(y * ss + j) * W + (x * ss + i)][k];
        rgb[(static_cast<size_t>(y) * w + x) * 3 + k] =
            static_cast<std::uint8_t>(std::clamp(sum / (ss * ss), 0.0, 1.0) * 255.0 + 0.5);
      }
  writePng(path, w, h, rgb);
}

// ---------------------------------------------------------------------------------------------

struct HeadArgs {
  std::string head = "default";
  std::string landmarks;
  std::string pins;
  bool json = false;
  std::string render;
  std::string view = "front";
  int size = 800;
  bool wire = false;
  bool markPins = false;
  bool noLandmarks = false;
  int levels = 2;
  bool closedMouth = false;
  std::string writeObj;
  std::string writeLandmarks;
};

Head loadFromArgs(const HeadArgs& a) {
  if (a.head == "default") {
    if (!a.landmarks.empty() || !a.pins.empty())
      throw InputError("--landmarks and --pins apply to an OBJ head, not the default head");
    DefaultHeadOptions o;
    o.subdivisionLevels = a.levels;
    o.openMouth = !a.closedMouth;
    return loadDefaultHead(o);
  }
  fs::path obj = a.head;
  std::string landmarks = a.landmarks, pins = a.pins;
  if (fs::is_directory(obj)) {  // a folder laid out like ../shared/data/ict
    const fs::path dir = obj;
    obj = dir / "head_skin.obj";
    if (landmarks.empty()) landmarks = (dir / "landmarks_multipie68.json").string();
    if (pins.empty() && fs::exists(dir / "rigid_vertices.json"))
      pins = (dir / "rigid_vertices.json").string();
  }
  if (!fs::exists(obj))
    throw InputError("no such head: give 'default', an OBJ file or a folder with head_skin.obj",
                     obj.string());
  if (landmarks.empty())
    throw InputError("an OBJ head needs --landmarks FILE (layout of docs/heads.md)", obj.string());
  Head h = loadHead(obj.string(), landmarks, pins);
  return h;
}

nlohmann::ordered_json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

int runHead(const HeadArgs& a) {
  const Head head = loadFromArgs(a);
  const TriMesh& m = head.mesh;
  const EdgeTable edges = buildEdgeTable(m.F, m.vertexCount());
  const auto loops = boundaryLoops(m.F, m.vertexCount());
  const FaceFrame f = head.frame();
  const Vec3 lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();

  nlohmann::ordered_json j;
  j["name"] = head.name;
  j["source"] = m.sourcePath;
  if (head.name == "default") j["source_sha256"] = defaultHeadSourceSha256();
  j["vertices"] = m.vertexCount();
  j["triangles"] = m.triangleCount();
  j["edges"] = edges.edges.size();
  j["boundary_loops"] = nlohmann::ordered_json::array();
  for (const auto& l : loops) j["boundary_loops"].push_back(l.size());
  j["bbox_cm"] = {{"min", vec(lo)}, {"max", vec(hi)}};
  j["landmarks"]["file"] = head.landmarks.sourcePath;
  j["landmarks"]["multipie68"] = head.landmarks.multipie68.size();
  j["landmarks"]["named"] = head.landmarks.named.size();
  j["landmarks"]["required"] = nlohmann::ordered_json::object();
  for (const RequiredLandmark& r : kRequiredLandmarks)
    j["landmarks"]["required"][r.name] = head.landmarks.vertex(r.name);
  j["frame"] = {{"origin", vec(f.origin)}, {"x", vec(f.axes.col(0))}, {"y", vec(f.axes.col(1))},
                {"z", vec(f.axes.col(2))}, {"scale", f.scale}};
  j["gravity_pins"] = {{"count", head.gravityPins.size()}, {"source", head.pinsSource}};

  if (!a.writeObj.empty()) {
    // The head's triangles as OBJ; the resolved landmarks go into "# landmark NAME ID" comments.
    std::ofstream out(a.writeObj);
    if (!out) throw InputError("cannot write OBJ", a.writeObj);
    out << "# " << head.name << " head written by myoshell head\n";
    for (const auto& [name, v] : head.landmarks.resolved()) out << "# landmark " << name << " " << v << "\n";
    for (int i = 0; i < m.vertexCount(); ++i)
      out << fmt::format("v {:.9g} {:.9g} {:.9g}\n", m.V(i, 0), m.V(i, 1), m.V(i, 2));
    for (int t = 0; t < m.triangleCount(); ++t)
      out << "f " << m.F(t, 0) + 1 << ' ' << m.F(t, 1) + 1 << ' ' << m.F(t, 2) + 1 << "\n";
    j["obj"] = a.writeObj;
  }
  if (!a.writeLandmarks.empty()) {
    std::ofstream out(a.writeLandmarks);
    if (!out) throw InputError("cannot write landmark file", a.writeLandmarks);
    out << landmarksToJson(head.landmarks);
    j["landmark_file"] = a.writeLandmarks;
  }
  if (!a.render.empty()) {
    RenderOptions ro;
    ro.size = a.size;
    if (a.view == "front") ro.yawDegrees = 0;
    else if (a.view == "threequarter") ro.yawDegrees = -40;
    else if (a.view == "side") ro.yawDegrees = -90;
    else if (a.view == "back") ro.yawDegrees = 180;
    else throw InputError("--view must be front, threequarter, side or back, not '" + a.view + "'");
    ro.wire = a.wire;
    ro.markPins = a.markPins;
    ro.markLandmarks = !a.noLandmarks;
    renderHead(head, ro, a.render);
    j["render"] = a.render;
  }

  if (a.json) {
    fmt::print("{}\n", j.dump(2));
    return kExitOk;
  }
  fmt::print("head {}: {} vertices, {} triangles, {} boundary loop(s)", head.name, m.vertexCount(),
             m.triangleCount(), loops.size());
  if (!loops.empty()) {
    fmt::print(" (edges:");
    for (const auto& l : loops) fmt::print(" {}", l.size());
    fmt::print(")");
  }
  fmt::print("\nlandmarks: {} Multi-PIE points, {} named, all {} required names resolved ({})\n",
             head.landmarks.multipie68.size(), head.landmarks.named.size(), kRequiredLandmarks.size(),
             head.landmarks.sourcePath);
  fmt::print("frame: origin ({:.3f}, {:.3f}, {:.3f}) cm, scale {:.3f} cm, z ({:.3f}, {:.3f}, {:.3f})\n",
             f.origin.x(), f.origin.y(), f.origin.z(), f.scale, f.axes(0, 2), f.axes(1, 2),
             f.axes(2, 2));
  fmt::print("gravity pins: {} ({})\n", head.gravityPins.size(), head.pinsSource);
  if (!a.render.empty()) fmt::print("wrote {}\n", a.render);
  return kExitOk;
}

static CommandRegistrar reg("head", [](CLI::App& app) -> std::function<int()> {
  auto args = std::make_shared<HeadArgs>();
  CLI::App* sub = app.add_subcommand(
      "head", "Load a head (the built-in default, an OBJ with a landmark file, or a folder like "
              "../shared/data/ict) and report counts, landmarks, face frame and gravity pins");
  sub->add_option("head", args->head, "'default', an OBJ file, or a folder with head_skin.obj, "
                                      "landmarks_multipie68.json and rigid_vertices.json");
  sub->add_option("--landmarks", args->landmarks, "landmark file (layout: docs/heads.md)");
  sub->add_option("--pins", args->pins, "vertex-set file of gravity pins (default: the rim rule)");
  sub->add_flag("--json", args->json, "print the report as JSON");
  sub->add_option("--render", args->render, "write a PNG picture with the landmarks marked");
  sub->add_option("--view", args->view, "front, threequarter, side or back")->capture_default_str();
  sub->add_option("--size", args->size, "picture size in pixels")->check(CLI::Range(64, 4096));
  sub->add_flag("--wire", args->wire, "draw the triangle edges");
  sub->add_flag("--pins-marked", args->markPins, "mark the gravity pins (green)");
  sub->add_flag("--no-landmarks", args->noLandmarks, "do not mark the landmarks");
  sub->add_option("--levels", args->levels, "default head: subdivision levels (default 2)")
      ->check(CLI::Range(0, 4));
  sub->add_flag("--closed-mouth", args->closedMouth, "default head: keep the mouth closed");
  sub->add_option("--write-obj", args->writeObj, "write the head as OBJ (landmarks in comments)");
  sub->add_option("--write-landmarks", args->writeLandmarks, "write the head's landmark file");
  return [args] { return runHead(*args); };
});

}  // namespace
}  // namespace myo::cli
