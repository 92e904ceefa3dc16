#include "myoshell/io/web_face_file.h"

#include <cstdint>
#include <cstring>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"

namespace myo {

namespace {

constexpr char kMagic[8] = {'M', 'Y', 'O', 'W', 'E', 'B', 'F', '1'};
constexpr uint32_t kVersion = 2;  // 2: a ring's lip_body

class Out {
 public:
  template <class T>
  void pod(const T& v) {
    raw(&v, 1);
  }
  template <class T>
  void raw(const T* p, size_t count) {
    const auto* b = reinterpret_cast<const char*>(p);
    s.append(b, sizeof(T) * count);
  }
  void str(const std::string& v) {
    pod(static_cast<uint32_t>(v.size()));
    s.append(v);
  }
  void vec3(const Vec3& v) { raw(v.data(), 3); }
  void anchor(const MuscleAnchor& a) {
    str(a.landmark);
    vec3(a.offset);
    pod(a.depth);
  }
  std::string s;
};

class In {
 public:
  In(std::string_view b, const std::string& name) : b_(b), name_(name) {}
  template <class T>
  T pod() {
    T v;
    raw(&v, 1);
    return v;
  }
  template <class T>
  void raw(T* p, size_t count) {
    const size_t n = sizeof(T) * count;
    if (count > b_.size() || n > b_.size() - pos_)
      throw InputError("web face data: truncated at byte " + std::to_string(pos_), name_);
    std::memcpy(p, b_.data() + pos_, n);
    pos_ += n;
  }
  std::string str() {
    const uint32_t n = pod<uint32_t>();
    std::string v(n, '\0');
    raw(v.data(), n);
    return v;
  }
  Vec3 vec3() {
    Vec3 v;
    raw(v.data(), 3);
    return v;
  }
  MuscleAnchor anchor() {
    MuscleAnchor a;
    a.landmark = str();
    a.offset = vec3();
    a.depth = pod<double>();
    return a;
  }
  size_t pos() const { return pos_; }

 private:
  std::string_view b_;
  const std::string& name_;
  size_t pos_ = 0;
};

}  // namespace

std::string webFaceBytes(const std::vector<MuscleDef>& muscles, const BasisKey& key, const ModalBasis& basis) {
  Out o;
  o.raw(kMagic, 8);
  o.pod(kVersion);
  o.pod(static_cast<uint32_t>(muscles.size()));
  for (const MuscleDef& d : muscles) {
    if (d.imported()) throw InputError("web face data: muscle '" + d.name + "' is imported (an OBJ shell); the page takes generated muscles only");
    o.str(d.name);
    o.pod(static_cast<int32_t>(d.kind));
    o.str(d.side);
    o.str(d.facs);
    o.anchor(d.origin);
    o.anchor(d.insertion);
    o.pod(d.width);
    o.pod(d.thickness);
    o.pod(static_cast<int32_t>(d.stations));
    o.pod(static_cast<int32_t>(d.ringNodes));
    o.pod(d.contraction);
    o.pod(d.springStiffness);
    o.pod(d.roiAlpha);
    o.pod(static_cast<uint8_t>(d.coupling ? 1 : 0));
    if (d.coupling) {
      const CouplingProfile& c = *d.coupling;
      for (double v : {c.insertionModulus, c.bellyModulus, c.originEnd, c.bellyStart, c.insertionStart}) o.pod(v);
    }
    o.pod(static_cast<uint32_t>(d.ring.path.size()));
    for (const MuscleAnchor& a : d.ring.path) o.anchor(a);
    o.pod(static_cast<uint8_t>(d.ring.closed));
    for (const MuscleAnchor& a : d.ring.anchors) o.anchor(a);
    o.pod(d.ring.shortening);
    o.pod(d.ring.protrusion);
    o.pod(d.ring.centre);
    o.pod(static_cast<uint8_t>(d.ring.alongSkin));
    o.pod(static_cast<uint8_t>(d.ring.lipBody));
  }
  o.pod(key.words[0]);
  o.pod(key.words[1]);
  o.pod(static_cast<uint32_t>(basis.fullVertexCount));
  o.pod(static_cast<uint32_t>(basis.freeCount()));
  o.pod(static_cast<uint32_t>(basis.modeCount()));
  o.raw(basis.freeVertices.data(), basis.freeVertices.size());
  o.raw(basis.lambda.data(), static_cast<size_t>(basis.lambda.size()));
  o.raw(basis.freeMass.data(), static_cast<size_t>(basis.freeMass.size()));
  const Eigen::MatrixXf phi = basis.Phi.cast<float>();
  o.raw(phi.data(), static_cast<size_t>(phi.size()));
  o.pod(fnv1a64(o.s.data(), o.s.size()));
  return std::move(o.s);
}

void writeWebFaceFile(const std::string& path, const std::vector<MuscleDef>& muscles, const BasisKey& key,
                      const ModalBasis& basis) {
  writeFileAtomically(path, webFaceBytes(muscles, key, basis), "cannot write the web face data");
}

WebFace readWebFace(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 8 + 8 || std::memcmp(bytes.data(), kMagic, 8) != 0)
    throw InputError("web face data: not a Myoshell web face file (no MYOWEBF1 magic)", name);
  uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  if (fnv1a64(bytes.data(), bytes.size() - 8) != stored)
    throw InputError("web face data: checksum mismatch (a damaged or partial download)", name);
  In in(bytes.substr(0, bytes.size() - 8), name);
  char magic[8];
  in.raw(magic, 8);
  if (const uint32_t v = in.pod<uint32_t>(); v != kVersion)
    throw InputError("web face data: format version " + std::to_string(v) + " is not " + std::to_string(kVersion), name);
  WebFace w;
  const uint32_t count = in.pod<uint32_t>();
  for (uint32_t m = 0; m < count; ++m) {
    MuscleDef d;
    d.name = in.str();
    const int32_t kind = in.pod<int32_t>();
    if (kind != 0 && kind != 1) throw InputError("web face data: muscle '" + d.name + "' has kind " + std::to_string(kind), name);
    d.kind = static_cast<MuscleKind>(kind);
    d.side = in.str();
    d.facs = in.str();
    d.origin = in.anchor();
    d.insertion = in.anchor();
    d.width = in.pod<double>();
    d.thickness = in.pod<double>();
    d.stations = in.pod<int32_t>();
    d.ringNodes = in.pod<int32_t>();
    d.contraction = in.pod<double>();
    d.springStiffness = in.pod<double>();
    d.roiAlpha = in.pod<double>();
    if (in.pod<uint8_t>()) {
      CouplingProfile c;
      c.insertionModulus = in.pod<double>();
      c.bellyModulus = in.pod<double>();
      c.originEnd = in.pod<double>();
      c.bellyStart = in.pod<double>();
      c.insertionStart = in.pod<double>();
      d.coupling = c;
    }
    const uint32_t path = in.pod<uint32_t>();
    for (uint32_t k = 0; k < path; ++k) d.ring.path.push_back(in.anchor());
    d.ring.closed = in.pod<uint8_t>() != 0;
    for (MuscleAnchor& a : d.ring.anchors) a = in.anchor();
    d.ring.shortening = in.pod<double>();
    d.ring.protrusion = in.pod<double>();
    d.ring.centre = in.pod<double>();
    d.ring.alongSkin = in.pod<uint8_t>() != 0;
    d.ring.lipBody = in.pod<uint8_t>() != 0;
    d.validate();
    w.muscles.push_back(std::move(d));
  }
  w.basisKey.words[0] = in.pod<uint64_t>();
  w.basisKey.words[1] = in.pod<uint64_t>();
  ModalBasis& b = w.basis;
  b.fullVertexCount = static_cast<int>(in.pod<uint32_t>());
  const uint32_t f = in.pod<uint32_t>();
  const uint32_t d = in.pod<uint32_t>();
  if (f > static_cast<uint32_t>(b.fullVertexCount) || d > 100000)
    throw InputError("web face data: basis sizes " + std::to_string(f) + " free vertices, " + std::to_string(d) + " modes do not fit", name);
  b.freeVertices.resize(f);
  in.raw(b.freeVertices.data(), f);
  b.lambda.resize(d);
  in.raw(b.lambda.data(), d);
  b.freeMass.resize(f);
  in.raw(b.freeMass.data(), f);
  Eigen::MatrixXf phi(3 * static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(d));
  in.raw(phi.data(), static_cast<size_t>(phi.size()));
  b.Phi = phi.cast<double>();
  b.Psi = MatX::Zero(b.Phi.rows(), b.Phi.cols());
  b.solver = "web face data";
  if (in.pos() != bytes.size() - 8)
    throw InputError("web face data: " + std::to_string(bytes.size() - 8 - in.pos()) + " bytes after the basis", name);
  return w;
}

std::optional<ModalBasis> WebFaceBasisCache::load(const BasisKey& key) {
  if (key == key_) return basis_;
  throw InputError("web face data: the face built here has basis key " + key.hex() + ", the data file holds " +
                   key_.hex() + " (the data was made from other sources or on a platform that rounds differently; "
                   "rebuild it with make web)");
}

}  // namespace myo
