#include "myoshell/io/animation_exporter.h"

#include <fmt/core.h>

#include <algorithm>
#include <system_error>

#include "myoshell/core/atomic_file.h"
#include "myoshell/core/errors.h"
#include "myoshell/core/io_error.h"
#include "myoshell/head/head_checks.h"
#include "myoshell/io/obj_writer.h"

namespace myo {

namespace fs = std::filesystem;

ExportFormats parseExportFormats(const std::vector<std::string>& names) {
  ExportFormats f;
  for (const std::string& name : names) {
    if (name == "obj") f.obj = true;
    else if (name == "glb") f.glb = true;
    else if (name == "pc2") f.pc2 = true;
    else throw InputError("unknown export format '" + name + "' (use glb, pc2 or obj)");
  }
  return f;
}

AnimationExporter::AnimationExporter(fs::path out, ExportFormats formats, std::string name, const TriMesh& mesh,
                                     double fps, int frames, LengthUnit units, GlbOptions glb)
    : out_(std::move(out)), formats_(formats), mesh_(mesh), perCm_(1.0 / centimetresPer(units)), glbOptions_(glb) {
  std::error_code ec;
  fs::create_directories(formats_.obj ? out_ / "obj" : out_, ec);
  if (ec && isRunTimeIoFailure(ec.value())) throw IoError("cannot create the output folder (" + ec.message() + ")", out_.string());
  if (ec) throw InputError("cannot create the output folder (" + ec.message() + ")", out_.string());
  animation_.name = std::move(name);
  if (formats_.glb || formats_.pc2) {  // the frames are kept only for these
    animation_.triangles = mesh.F;
    animation_.rest = mesh.V;
    animation_.uv = mesh.UV;  // TEXCOORD_0 when the head has UVs
    animation_.cornerUV = mesh.cornerUV;  // its seams split
    animation_.fps = fps;
    animation_.positions.reserve(static_cast<size_t>(std::max(frames, 0)));
  }
}

std::string AnimationExporter::addFrame(int f, const MatX3& positions) {
  std::string rel;
  if (formats_.obj) {
    rel = fmt::format("obj/{}_{:04d}.obj", animation_.name, f);
    if (perCm_ == 1.0) {
      writeObj((out_ / rel).string(), mesh_, &positions);
    } else {
      const MatX3 inUnits = positions * perCm_;  // the head's own unit
      writeObj((out_ / rel).string(), mesh_, &inUnits);
    }
  }
  if (formats_.glb || formats_.pc2) animation_.positions.push_back(positions);
  return rel;
}

std::vector<std::string> AnimationExporter::finish() {
  std::vector<std::string> written;
  if (formats_.glb) {
    glb_ = writeGlb(out_ / (animation_.name + ".glb"), animation_, glbOptions_);
    written.push_back(animation_.name + ".glb");
  }
  if (formats_.pc2) {
    if (perCm_ == 1.0) {
      writePc2(out_ / (animation_.name + ".pc2"), animation_);
    } else {  // the head's own unit
      AnimationFrames inUnits;
      inUnits.rest = animation_.rest * perCm_;
      inUnits.positions.reserve(animation_.positions.size());
      for (const MatX3& p : animation_.positions) inUnits.positions.push_back(p * perCm_);
      writePc2(out_ / (animation_.name + ".pc2"), inUnits);
    }
    written.push_back(animation_.name + ".pc2");
  }
  return written;
}

}  // namespace myo
