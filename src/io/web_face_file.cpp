#include "myoshell/io/web_face_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"

namespace myo {

namespace {

constexpr char kMagic[8] = {'M', 'Y', 'O', 'W', 'E', 'B', 'F', '1'};
constexpr uint32_t kVersion = 7;  // 2: takes; 3: the FACS map; 4: a linear muscle's `thickens`, a ring's `lip_body`; 5: `pushes`; 6: `continues_into`; 7: a ring's `hoop`

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
  void track(const ScalarTrack& t) {
    pod(static_cast<uint32_t>(t.keys().size()));
    for (const Keyframe<double>& k : t.keys()) {
      pod(k.time);
      pod(k.value);
      pod(static_cast<uint8_t>(k.interpolation));
    }
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
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy may not take
    std::memcpy(p, b_.data() + pos_, n);
    pos_ += n;
  }
  std::string str() {
    const uint32_t n = pod<uint32_t>();
    // Before allocating: a length past the file's end is a truncation (fuzz_web_face found the
    // allocation of a 2.7 GB string from four damaged bytes).
    if (n > remaining()) throw InputError("web face data: truncated at byte " + std::to_string(pos_) + " (a string of " +
                                          std::to_string(n) + " bytes)", name_);
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
  // A track of `what` (InputError naming it for keys out of order or an unknown interpolation).
  ScalarTrack track(const std::string& what) {
    const uint32_t n = pod<uint32_t>();
    if (n > remaining() / 17) throw InputError("web face data: " + what + ": " + std::to_string(n) + " keys do not fit", name_);
    std::vector<Keyframe<double>> keys(n);
    for (Keyframe<double>& k : keys) {
      k.time = pod<double>();
      k.value = pod<double>();
      const uint8_t i = pod<uint8_t>();
      if (i > static_cast<uint8_t>(Interpolation::Smooth))
        throw InputError("web face data: " + what + ": interpolation " + std::to_string(i) + " is not 0, 1 or 2", name_);
      k.interpolation = static_cast<Interpolation>(i);
    }
    try {
      return ScalarTrack(std::move(keys), what);
    } catch (const InputError& e) {
      throw InputError("web face data: " + e.message(), name_);
    }
  }
  // A byte that must be 0 or 1 (a file holds nothing else, so it writes back byte for byte).
  bool flag(const std::string& what) {
    const uint8_t v = pod<uint8_t>();
    if (v > 1) throw InputError("web face data: " + what + ": a flag byte of " + std::to_string(v) + " (want 0 or 1)", name_);
    return v == 1;
  }
  size_t pos() const { return pos_; }
  size_t remaining() const { return b_.size() - pos_; }

 private:
  std::string_view b_;
  const std::string& name_;
  size_t pos_ = 0;
};

}  // namespace

std::string webFaceBytes(const std::vector<MuscleDef>& muscles, const BasisKey& key, const ModalBasis& basis,
                         const std::vector<SceneDesc>& takes, const FacsMap& facs) {
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
    o.pod(static_cast<uint8_t>(d.thickens));
    o.pod(static_cast<uint8_t>(d.ring.lipBody));
    o.pod(static_cast<uint8_t>(d.pushes ? 1 : 0));
    if (d.pushes) o.anchor(*d.pushes);
    o.pod(static_cast<uint8_t>(d.continuesInto ? 1 : 0));
    if (d.continuesInto) o.anchor(*d.continuesInto);
    o.pod(static_cast<uint8_t>(d.ring.hoop ? 1 : 0));
    if (d.ring.hoop) {
      o.str(d.ring.hoop->landmark);
      o.vec3(d.ring.hoop->offset);
      o.pod(d.ring.hoop->radius);
    }
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
  o.pod(static_cast<uint32_t>(takes.size()));
  for (const SceneDesc& t : takes) {
    const auto refuse = [&](const std::string& what) {
      throw InputError("web face data: take '" + t.name + "' has " + what +
                       " on its timeline; a take carries activations and the jaw only");
    };
    if (!t.gravity.empty()) refuse("a gravity track");
    if (!t.headPose.empty()) refuse("a head pose");
    if (t.hasGaze()) refuse("the eyes' turn");
    if (!t.drags.empty() || !t.dragForces.empty()) refuse("drags");
    if (t.modelKind != FaceModelKind::Anatomical) refuse("the thesis's model");
    o.str(t.name);
    o.pod(t.duration);
    o.pod(t.fps);
    o.pod(static_cast<uint32_t>(t.activations.size()));
    for (const auto& [muscle, track] : t.activations) {
      o.str(muscle);
      o.track(track);
    }
    for (const ScalarTrack* j : {&t.jawOpen, &t.jawForward, &t.jawLateral}) o.track(*j);
  }
  o.pod(static_cast<uint32_t>(facs.entries.size()));
  for (const FacsEntry& e : facs.entries) {
    o.pod(static_cast<int32_t>(e.au));
    o.str(e.name);
    o.pod(static_cast<uint8_t>(e.openface));
    o.pod(static_cast<uint32_t>(e.muscles.size()));
    for (const auto& [muscle, w] : e.muscles) {
      o.str(muscle);
      o.pod(w);
    }
    o.str(e.needs);
    for (double v : {e.jawOpenDeg, e.jawForwardCm, e.jawLateralCm, e.gazePitchDeg, e.gazeYawDeg, e.mouthPressureKpa}) o.pod(v);
  }
  o.pod(fnv1a64(o.s.data(), o.s.size()));
  return std::move(o.s);
}

void writeWebFaceFile(const std::string& path, const std::vector<MuscleDef>& muscles, const BasisKey& key,
                      const ModalBasis& basis, const std::vector<SceneDesc>& takes, const FacsMap& facs) {
  writeFileAtomically(path, webFaceBytes(muscles, key, basis, takes, facs), "cannot write the web face data");
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
  if (count > in.remaining() / 64)  // a muscle takes well over 64 bytes
    throw InputError("web face data: " + std::to_string(count) + " muscles do not fit in the file", name);
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
    if (in.flag("muscle '" + d.name + "' coupling")) {
      CouplingProfile c;
      c.insertionModulus = in.pod<double>();
      c.bellyModulus = in.pod<double>();
      c.originEnd = in.pod<double>();
      c.bellyStart = in.pod<double>();
      c.insertionStart = in.pod<double>();
      d.coupling = c;
    }
    const uint32_t path = in.pod<uint32_t>();
    if (path > in.remaining() / 36)  // an anchor takes at least 36 bytes
      throw InputError("web face data: muscle '" + d.name + "': a ring path of " + std::to_string(path) + " anchors does not fit", name);
    for (uint32_t k = 0; k < path; ++k) d.ring.path.push_back(in.anchor());
    d.ring.closed = in.flag("muscle '" + d.name + "' ring closed");
    for (MuscleAnchor& a : d.ring.anchors) a = in.anchor();
    d.ring.shortening = in.pod<double>();
    d.ring.protrusion = in.pod<double>();
    d.ring.centre = in.pod<double>();
    d.ring.alongSkin = in.flag("muscle '" + d.name + "' ring along the skin");
    d.thickens = in.flag("muscle '" + d.name + "' thickens");
    d.ring.lipBody = in.flag("muscle '" + d.name + "' ring in the lip's body");
    if (in.flag("muscle '" + d.name + "' pushes")) d.pushes = in.anchor();
    if (in.flag("muscle '" + d.name + "' continues into")) d.continuesInto = in.anchor();
    if (in.flag("muscle '" + d.name + "' ring hoop")) {
      MuscleDef::Ring::Hoop hoop;
      hoop.landmark = in.str();
      hoop.offset = in.vec3();
      hoop.radius = in.pod<double>();
      d.ring.hoop = hoop;
    }
    d.validate();
    w.muscles.push_back(std::move(d));
  }
  w.basisKey.words[0] = in.pod<uint64_t>();
  w.basisKey.words[1] = in.pod<uint64_t>();
  ModalBasis& b = w.basis;
  const uint32_t full = in.pod<uint32_t>();
  if (full > static_cast<uint32_t>(std::numeric_limits<int>::max()))
    throw InputError("web face data: a head of " + std::to_string(full) + " vertices", name);
  b.fullVertexCount = static_cast<int>(full);
  const uint32_t f = in.pod<uint32_t>();
  const uint32_t d = in.pod<uint32_t>();
  // Each free vertex takes 4 + 8 + 12·d bytes and each mode 8: the sizes must fit in what is left.
  if (f > static_cast<uint32_t>(b.fullVertexCount) || d > 100000 ||
      static_cast<double>(f) * (12.0 + 12.0 * d) + 8.0 * d > static_cast<double>(in.remaining()))
    throw InputError("web face data: basis sizes " + std::to_string(f) + " free vertices, " + std::to_string(d) + " modes do not fit", name);
  b.freeVertices.resize(f);
  in.raw(b.freeVertices.data(), f);
  for (const int v : b.freeVertices)
    if (v < 0 || v >= b.fullVertexCount)
      throw InputError("web face data: free vertex " + std::to_string(v) + " is outside the head's " +
                       std::to_string(b.fullVertexCount) + " vertices", name);
  b.lambda.resize(d);
  in.raw(b.lambda.data(), d);
  b.freeMass.resize(f);
  in.raw(b.freeMass.data(), f);
  Eigen::MatrixXf phi(3 * static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(d));
  in.raw(phi.data(), static_cast<size_t>(phi.size()));
  if (!phi.allFinite() || !b.lambda.allFinite() || !b.freeMass.allFinite())
    throw InputError("web face data: the basis holds a value that is not finite", name);
  b.Phi = phi.cast<double>();
  b.Psi = MatX::Zero(b.Phi.rows(), b.Phi.cols());
  b.solver = "web face data";
  const uint32_t takes = in.pod<uint32_t>();
  if (takes > in.remaining() / 48)  // a take takes at least 48 bytes
    throw InputError("web face data: " + std::to_string(takes) + " takes do not fit in the file", name);
  for (uint32_t k = 0; k < takes; ++k) {
    SceneDesc t;
    t.name = in.str();
    t.duration = in.pod<double>();
    t.fps = in.pod<double>();
    if (!(t.duration > 0.0 && t.duration <= 3600.0) || !(t.fps > 0.0 && t.fps <= 1000.0))
      throw InputError("web face data: take '" + t.name + "' lasts " + std::to_string(t.duration) + " s at " +
                       std::to_string(t.fps) + " fps (want (0, 3600] s, (0, 1000] fps)", name);
    const uint32_t tracks = in.pod<uint32_t>();
    if (tracks > in.remaining() / 8)
      throw InputError("web face data: take '" + t.name + "': " + std::to_string(tracks) + " tracks do not fit", name);
    for (uint32_t i = 0; i < tracks; ++i) {
      std::string muscle = in.str();
      ScalarTrack track = in.track("take '" + t.name + "', muscle '" + muscle + "'");
      if (!t.activations.emplace(muscle, std::move(track)).second)
        throw InputError("web face data: take '" + t.name + "' gives muscle '" + muscle + "' twice", name);
    }
    t.jawOpen = in.track("take '" + t.name + "', jaw open");
    t.jawForward = in.track("take '" + t.name + "', jaw forward");
    t.jawLateral = in.track("take '" + t.name + "', jaw lateral");
    w.takes.push_back(std::move(t));
  }
  const uint32_t aus = in.pod<uint32_t>();
  if (aus > in.remaining() / 65)  // an entry takes at least 65 bytes
    throw InputError("web face data: " + std::to_string(aus) + " action units do not fit in the file", name);
  for (uint32_t k = 0; k < aus; ++k) {
    FacsEntry e;
    e.au = in.pod<int32_t>();
    if (e.au < 1 || e.au > 999) throw InputError("web face data: action unit number " + std::to_string(e.au) + " is not in 1–999", name);
    const std::string what = "web face data: AU" + std::to_string(e.au);
    if (w.facs.find(e.au)) throw InputError(what + " is given twice", name);
    e.name = in.str();
    e.openface = in.flag("AU" + std::to_string(e.au) + " openface");
    const uint32_t muscles = in.pod<uint32_t>();
    if (muscles > in.remaining() / 12) throw InputError(what + ": " + std::to_string(muscles) + " muscles do not fit", name);
    for (uint32_t m = 0; m < muscles; ++m) {
      std::string muscle = in.str();
      const double weight = in.pod<double>();
      if (!(weight >= 0.0 && weight <= 1.0))
        throw InputError(what + ": muscle '" + muscle + "' has weight " + std::to_string(weight) + " outside [0, 1]", name);
      e.muscles.emplace_back(std::move(muscle), weight);
    }
    e.needs = in.str();
    for (double* v : {&e.jawOpenDeg, &e.jawForwardCm, &e.jawLateralCm, &e.gazePitchDeg, &e.gazeYawDeg, &e.mouthPressureKpa}) {
      *v = in.pod<double>();
      if (!std::isfinite(*v)) throw InputError(what + ": a jaw, gaze or pressure value is not finite", name);
    }
    w.facs.entries.push_back(std::move(e));
  }
  if (in.pos() != bytes.size() - 8)
    throw InputError("web face data: " + std::to_string(bytes.size() - 8 - in.pos()) + " bytes after the FACS map", name);
  return w;
}

std::optional<ModalBasis> WebFaceBasisCache::load(const BasisKey& key) {
  if (key == key_) return basis_;
  throw InputError("web face data: the face built here has basis key " + key.hex() + ", the data file holds " +
                   key_.hex() + " (the data was made from other sources or on a platform that rounds differently; "
                   "rebuild it with make web)");
}

}  // namespace myo
