// The anatomical skin's basis through the file cache (AnatomicalSkin with a BasisCache; two files:
// the held basis and the released one, a warm start reading only the released one): a hit is
// the fresh build bit for bit (basis, settled shapes, time steps, later drags, the full-space
// response); every input the basis depends on changes the key; a corrupt or truncated file is a
// miss that rebuilds and rewrites it. The built-in head with two muscles and few modes keeps the
// fresh builds short.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "myoshell/anatomy/anatomical_stepper.h"
#include "myoshell/io/basis_cache_file.h"
#include "myoshell/io/head_files.h"
#include "myoshell/muscles/muscle_def.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

struct AnatomicalCacheDir {
  fs::path path;
  AnatomicalCacheDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("myo_anatomical_cache_test_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~AnatomicalCacheDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::vector<MuscleDef> twoMuscles() {
  std::vector<MuscleDef> out;
  for (const MuscleDef& d : thesisMuscleDefs())
    if (d.name == "zygomaticus_major_left" || d.name == "depressor_anguli_oris_right") out.push_back(d);
  return out;
}

AnatomicalSettings smallSettings() {
  AnatomicalSettings s;
  s.skinModes = 6;
  return s;
}

const std::vector<DragSite> kDrag = {{205, 1.0}};

bool sameBits(const MatX& a, const MatX& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

void expectSameBasis(const ModalBasis& a, const ModalBasis& b) {
  EXPECT_EQ(a.fullVertexCount, b.fullVertexCount);
  EXPECT_EQ(a.freeVertices, b.freeVertices);
  EXPECT_EQ(a.solver, b.solver);
  EXPECT_TRUE(sameBits(a.Phi, b.Phi));
  EXPECT_TRUE(sameBits(a.Psi, b.Psi));
  EXPECT_TRUE(sameBits(a.lambda, b.lambda));
  EXPECT_TRUE(sameBits(a.freeMass, b.freeMass));
}

SkinLoads someLoads(const AnatomicalSkin& skin) {
  SkinLoads l;
  l.activations = VecX::Zero(2);
  l.activations(skin.muscleIndex("zygomaticus_major_left")) = 1.0;
  l.activations(skin.muscleIndex("depressor_anguli_oris_right")) = 0.4;
  l.gravity = gravityForPose(skin.head().frame(), Vec3(60.0, 10.0, 0.0), skin.settings().gravity);
  l.drags = {Vec3(1500.0, 400.0, -200.0)};
  return l;
}

// Steps both skins under the same loads; their displacements must agree exactly at every step.
void expectSameSteps(const std::shared_ptr<const AnatomicalSkin>& a, const std::shared_ptr<const AnatomicalSkin>& b) {
  AnatomicalStepper sa(a), sb(b);
  const SkinLoads l = someLoads(*a);
  for (int k = 0; k < 40; ++k) {
    sa.step(l);
    sb.step(l);
    ASSERT_TRUE(sameBits(sa.displacement(), sb.displacement())) << "step " << k;
  }
  EXPECT_GT(sa.displacement().rowwise().norm().maxCoeff(), 1e-3);  // cm: it moved
}

TEST(AnatomicalBasisCache, AHitIsTheFreshBuildBitForBit) {
  AnatomicalCacheDir dir;
  FileBasisCache cache(dir.path);
  const Head head = loadDefaultHead();
  auto fresh = std::make_shared<AnatomicalSkin>(head, twoMuscles(), smallSettings(), kDrag, &cache);
  EXPECT_FALSE(fresh->basisFromCache());
  EXPECT_EQ(cache.stats().misses, 2);  // the released basis, then the held one
  EXPECT_EQ(cache.stats().stores, 2);
  EXPECT_TRUE(fs::exists(cache.pathFor(fresh->basisKey())));
  EXPECT_TRUE(fs::exists(cache.pathFor(fresh->releasedBasisKey())));
  EXPECT_NE(fresh->releasedBasisKey(), fresh->basisKey());

  // The same build without a cache, drag added afterwards (the sequence AnatomicalFace used):
  // the cache changes nothing in a fresh build.
  auto plain = std::make_shared<AnatomicalSkin>(head, twoMuscles(), smallSettings());
  plain->addDrag(205, 1.0);
  expectSameBasis(*plain->basis(), *fresh->basis());

  auto hit = std::make_shared<AnatomicalSkin>(head, twoMuscles(), smallSettings(), kDrag, &cache);
  EXPECT_TRUE(hit->basisFromCache());
  EXPECT_EQ(cache.stats().hits, 1);  // the released basis only: the held one is read when needed
  EXPECT_EQ(hit->basisKey(), fresh->basisKey());
  expectSameBasis(*fresh->basis(), *hit->basis());

  const SkinLoads l = someLoads(*fresh);
  for (bool warped : {false, true}) {
    const SettledSkin a = fresh->settle(l, warped), b = hit->settle(l, warped);
    EXPECT_TRUE(sameBits(a.u, b.u)) << (warped ? "warped" : "linear");
    EXPECT_TRUE(sameBits(a.q, b.q)) << (warped ? "warped" : "linear");
  }
  expectSameSteps(fresh, hit);

  // After a hit K̂ is factorised on demand: the full-space response and a drag grabbed later are
  // what the fresh build gives.
  EXPECT_TRUE(sameBits(fresh->linearFullResponse(l), hit->linearFullResponse(l)));
  fresh->addDrag(100, 0.8);
  hit->addDrag(100, 0.8);
  expectSameBasis(*fresh->basis(), *hit->basis());
  expectSameSteps(fresh, hit);

  // The held basis's file gone after a warm start (another process cleaned the cache): a drag
  // grabbed later rebuilds it, and gives the same bits.
  auto warm = std::make_shared<AnatomicalSkin>(head, twoMuscles(), smallSettings(), kDrag, &cache);
  EXPECT_TRUE(warm->basisFromCache());
  fs::remove(cache.pathFor(warm->basisKey()));
  warm->addDrag(100, 0.8);
  expectSameBasis(*fresh->basis(), *warm->basis());
  expectSameSteps(fresh, warm);
}

// A cache that records the key asked for and stops the build there (the key is computed before
// the expensive part), so each changed input costs only the assembly.
struct KeyProbe : BasisCache {
  struct Stop {};
  BasisKey asked;
  std::optional<ModalBasis> load(const BasisKey& key) override {
    asked = key;
    throw Stop{};
  }
  void store(const BasisKey&, const ModalBasis&) override {}
};

BasisKey keyOf(const Head& head, const std::vector<MuscleDef>& muscles, const AnatomicalSettings& s,
               const std::vector<DragSite>& drags = kDrag) {
  KeyProbe probe;
  try {
    AnatomicalSkin skin(head, muscles, s, drags, &probe);
  } catch (const KeyProbe::Stop&) {
    return probe.asked;
  }
  ADD_FAILURE() << "the skin did not ask the cache";
  return {};
}

TEST(AnatomicalBasisCache, EveryInputOfTheBasisChangesTheKey) {
  const Head head = loadDefaultHead();
  const std::vector<MuscleDef> muscles = twoMuscles();
  const AnatomicalSettings base = smallSettings();
  const BasisKey ref = keyOf(head, muscles, base);
  EXPECT_EQ(keyOf(head, muscles, base), ref);  // stable

  std::vector<std::pair<std::string, BasisKey>> changed;
  auto with = [&](const std::string& what, auto edit) {
    AnatomicalSettings s = base;
    edit(s);
    changed.emplace_back(what, keyOf(head, muscles, s));
  };
  with("skin modes", [](AnatomicalSettings& s) { s.skinModes = 7; });
  with("Young's modulus", [](AnatomicalSettings& s) { s.skinYoungModulus *= 1.01; });
  with("skin thickness", [](AnatomicalSettings& s) { s.skinThickness *= 1.01; });
  with("attachment override", [](AnatomicalSettings& s) { s.attachmentOverrides.push_back({300, 2.0e4}); });
  with("tissue density", [](AnatomicalSettings& s) { s.attachment.tissueDensity *= 1.01; });
  with("coupling shortening", [](AnatomicalSettings& s) { s.coupling.shortening = 0.15; });
  with("coupling insertion modulus", [](AnatomicalSettings& s) { s.coupling.profile.insertionModulus *= 1.01; });
  with("footprint reach", [](AnatomicalSettings& s) { s.coupling.footprintReach = 1.5; });
  changed.emplace_back("drag radius", keyOf(head, muscles, base, {{205, 1.2}}));
  changed.emplace_back("drag vertex", keyOf(head, muscles, base, {{206, 1.0}}));
  changed.emplace_back("a second drag", keyOf(head, muscles, base, {{205, 1.0}, {100, 1.0}}));
  changed.emplace_back("no drag", keyOf(head, muscles, base, {}));
  std::vector<MuscleDef> edited = muscles;
  edited[0].insertion.offset += Vec3(0.0, 0.01, 0.0);
  changed.emplace_back("muscle insertion", keyOf(head, edited, base));
  changed.emplace_back("one muscle fewer", keyOf(head, {muscles[0]}, base));
  Head moved = head;
  moved.mesh.V(10, 0) += 1e-6;
  changed.emplace_back("one vertex moved", keyOf(moved, muscles, base));
  for (const auto& [what, key] : changed) EXPECT_NE(key, ref) << what;

  // Gravity's magnitude and the time-stepping settings do not enter the basis: same key.
  AnatomicalSettings s = base;
  s.gravity = 500.0;
  s.dt = 1.0 / 120.0;
  s.dampingMass = 3.0;
  s.warping = true;
  EXPECT_EQ(keyOf(head, muscles, s), ref);
}

std::vector<char> readCacheBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AnatomicalBasisCache, ACorruptOrTruncatedFileIsAMissThatRebuilds) {
  AnatomicalCacheDir dir;
  FileBasisCache cache(dir.path);
  const Head head = loadDefaultHead();
  const AnatomicalSkin first(head, twoMuscles(), smallSettings(), kDrag, &cache);
  const fs::path releasedFile = cache.pathFor(first.releasedBasisKey()), heldFile = cache.pathFor(first.basisKey());
  const std::vector<char> good = readCacheBytes(releasedFile), goodHeld = readCacheBytes(heldFile);
  ASSERT_GT(good.size(), 1000u);
  {  // truncated: as a run killed while another wrote it (the atomic writer prevents it; a copy may not)
    std::ofstream out(releasedFile, std::ios::binary | std::ios::trunc);
    out.write(good.data(), static_cast<std::streamsize>(good.size() / 2));
  }
  // The released basis is rejected; it is remade from the held one in the cache and written back.
  const AnatomicalSkin remade(head, twoMuscles(), smallSettings(), kDrag, &cache);
  EXPECT_TRUE(remade.basisFromCache());
  EXPECT_EQ(cache.stats().rejected, 1);
  EXPECT_NE(cache.lastRejection().find("payload is"), std::string::npos) << cache.lastRejection();
  expectSameBasis(*first.basis(), *remade.basis());
  EXPECT_EQ(readCacheBytes(releasedFile), good);  // written back whole

  std::vector<char> flipped = goodHeld;  // one byte inside the held basis's Φ, and no released file
  flipped[goodHeld.size() / 2] ^= 0x04;
  {
    std::ofstream out(heldFile, std::ios::binary | std::ios::trunc);
    out.write(flipped.data(), static_cast<std::streamsize>(flipped.size()));
  }
  fs::remove(releasedFile);
  const AnatomicalSkin again(head, twoMuscles(), smallSettings(), kDrag, &cache);
  EXPECT_FALSE(again.basisFromCache());
  EXPECT_EQ(cache.stats().rejected, 2);
  EXPECT_NE(cache.lastRejection().find("checksum mismatch"), std::string::npos) << cache.lastRejection();
  expectSameBasis(*first.basis(), *again.basis());
  EXPECT_EQ(readCacheBytes(heldFile), goodHeld);
  EXPECT_EQ(readCacheBytes(releasedFile), good);
}

}  // namespace
}  // namespace myo
