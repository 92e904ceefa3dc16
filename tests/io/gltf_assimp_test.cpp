// Our GLB read back by a second, independent glTF reader (assimp, Debian libassimp-dev): the base
// mesh in the head's vertex order, the morph targets as anim meshes, and the weights animation as a
// morph-mesh channel whose keys, played, are the frames.
#include <assimp/Importer.hpp>
#include <assimp/anim.h>
#include <assimp/mesh.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "myoshell/io/animation_export.h"
#include "myoshell/io/obj_writer.h"
#include "myoshell/io/rig_export.h"
#include "myoshell/mesh/obj_reader.h"
#include "support/cli_runner.h"
#include "support/grid_animation.h"
#include "support/scratch_folder.h"
#include "support/seam_rig.h"
#include "support/uv_seam_mesh.h"

namespace myo {
namespace {

namespace fs = std::filesystem;

using test::bulgeAnimation;

double maxDifference(const aiVector3D* v, const MatX3& expected) {
  double worst = 0;
  for (Eigen::Index i = 0; i < expected.rows(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(v[i][c]) - expected(i, c)));
  return worst;
}

// Weight of target `target` in morph key `key` (0 when the key does not list it).
double keyWeight(const aiMeshMorphKey& key, unsigned target) {
  for (unsigned j = 0; j < key.mNumValuesAndWeights; ++j)
    if (key.mValues[j] == target) return key.mWeights[j];
  return 0.0;
}

// Largest difference between the texture coordinates two assimp meshes give the same face corners
// (assimp's OBJ importer makes one vertex per corner, its glTF importer keeps ours, so corners are
// matched through the faces, which both keep in file order).
double maxCornerUvDifference(const aiMesh* a, const aiMesh* b) {
  EXPECT_EQ(a->mNumFaces, b->mNumFaces);
  double worst = 0;
  for (unsigned f = 0; f < a->mNumFaces && f < b->mNumFaces; ++f)
    for (unsigned c = 0; c < 3; ++c) {
      const aiVector3D& ua = a->mTextureCoords[0][a->mFaces[f].mIndices[c]];
      const aiVector3D& ub = b->mTextureCoords[0][b->mFaces[f].mIndices[c]];
      worst = std::max({worst, std::abs(double(ua.x) - ub.x), std::abs(double(ua.y) - ub.y)});
    }
  return worst;
}

// Frame k as assimp's morph animation plays it: the base plus, for every target j, key k's weight
// times anim mesh j's displacement from the base (assimp stores base + target).
MatX3 playedFrame(const aiMesh* mesh, const aiMeshMorphKey& key) {
  MatX3 P(mesh->mNumVertices, 3);
  for (unsigned i = 0; i < mesh->mNumVertices; ++i)
    for (int c = 0; c < 3; ++c) {
      double x = mesh->mVertices[i][c];
      for (unsigned j = 0; j < key.mNumValuesAndWeights; ++j) {
        const aiAnimMesh* am = mesh->mAnimMeshes[key.mValues[j]];
        x += key.mWeights[j] * (double(am->mVertices[i][c]) - mesh->mVertices[i][c]);
      }
      P(i, c) = x;
    }
  return P;
}

using GltfAssimp = test::ScratchFolderTest;
TEST_F(GltfAssimp, ReadsTheBaseMeshMorphTargetsAndWeightsAnimation) {
  const AnimationFrames a = bulgeAnimation(10);
  const fs::path path = dir_ / "bulge.glb";
  const GlbReport report = writeGlb(path, a);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), 0);  // no post-processing: keep the order
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];

  // The base mesh: the head's vertices in its order, its triangles.
  ASSERT_EQ(mesh->mNumVertices, static_cast<unsigned>(a.rest.rows()));
  ASSERT_EQ(mesh->mNumFaces, static_cast<unsigned>(a.triangles.rows()));
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    ASSERT_EQ(mesh->mFaces[f].mNumIndices, 3u);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh->mFaces[f].mIndices[c], static_cast<unsigned>(a.triangles(f, c))) << f;
  }
  EXPECT_TRUE(mesh->HasNormals());

  // One anim mesh per target, named from extras.targetNames.
  ASSERT_EQ(mesh->mNumAnimMeshes, static_cast<unsigned>(report.targets));
  EXPECT_STREQ(mesh->mAnimMeshes[0]->mName.C_Str(), "mode_00");

  // The weights animation: one morph-mesh channel, a key at every frame, k / fps; played, key k is
  // frame k in metres to 0.05 mm.
  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation* anim = scene->mAnimations[0];
  ASSERT_EQ(anim->mNumMorphMeshChannels, 1u) << "assimp exposes no weights channel";
  const aiMeshMorphAnim* channel = anim->mMorphMeshChannels[0];
  ASSERT_EQ(channel->mNumKeys, a.positions.size());
  const double ticksPerSecond = anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 1.0;
  for (unsigned k = 0; k < channel->mNumKeys; ++k) {
    EXPECT_NEAR(channel->mKeys[k].mTime / ticksPerSecond, k / a.fps, 1e-5) << k;
    const MatX3 P = playedFrame(mesh, channel->mKeys[k]);
    EXPECT_LT((P - 0.01 * a.positions[k]).rowwise().norm().maxCoeff(), 5e-5) << "frame " << k;
  }
}

// A head with UVs: the GLB's TEXCOORD_0 read by assimp equals what assimp reads from our OBJ of
// the same mesh, corner by corner (and equals the UVs given); a head without UVs has none.
TEST_F(GltfAssimp, TexcoordsEqualTheObjs) {
  AnimationFrames a = bulgeAnimation(3);
  a.uv.resize(a.rest.rows(), 2);
  for (Eigen::Index v = 0; v < a.uv.rows(); ++v) a.uv.row(v) << 0.1 + 0.15 * (v % 6), 0.05 + 0.3 * (v / 6) - 0.01 * v;
  writeGlb(dir_ / "uv.glb", a);
  TriMesh mesh;
  mesh.V = a.rest;
  mesh.F = a.triangles;
  mesh.UV = a.uv;
  writeObj((dir_ / "uv.obj").string(), mesh);

  Assimp::Importer glbImporter, objImporter;
  const aiScene* glb = glbImporter.ReadFile((dir_ / "uv.glb").string(), 0);
  const aiScene* obj = objImporter.ReadFile((dir_ / "uv.obj").string(), 0);
  ASSERT_NE(glb, nullptr) << glbImporter.GetErrorString();
  ASSERT_NE(obj, nullptr) << objImporter.GetErrorString();
  const aiMesh* g = glb->mMeshes[0];
  const aiMesh* o = obj->mMeshes[0];
  ASSERT_TRUE(g->HasTextureCoords(0));
  ASSERT_TRUE(o->HasTextureCoords(0));
  EXPECT_EQ(g->mNumUVComponents[0], 2u);
  EXPECT_LT(maxCornerUvDifference(g, o), 1e-6);
  for (unsigned v = 0; v < g->mNumVertices; ++v) {
    EXPECT_NEAR(g->mTextureCoords[0][v].x, a.uv(v, 0), 1e-6) << v;
    EXPECT_NEAR(g->mTextureCoords[0][v].y, a.uv(v, 1), 1e-6) << v;
  }

  a.uv.resize(0, 2);
  writeGlb(dir_ / "plain.glb", a);
  Assimp::Importer plainImporter;
  const aiScene* plain = plainImporter.ReadFile((dir_ / "plain.glb").string(), 0);
  ASSERT_NE(plain, nullptr) << plainImporter.GetErrorString();
  EXPECT_FALSE(plain->mMeshes[0]->HasTextureCoords(0));
}

// A simulated run: the GLB played by assimp's weights gives the frames the PC2 cache holds, vertex
// by vertex (×0.01: metres).
TEST_F(GltfAssimp, CliRunGlbMatchesTheSimulatedFrames) {
  write("small.json", test::kSmallScene);
  const auto r = test::runCli("run '" + (dir_ / "small.json").string() + "' --out '" + (dir_ / "out").string() + "'" +
                              cacheArg() + " --format glb,pc2,obj");
  ASSERT_EQ(r.exitCode, 0) << r.merged;
  const PointCache pc = readPc2(dir_ / "out" / "small.pc2");

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir_ / "out" / "small.glb").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];
  ASSERT_EQ(mesh->mNumVertices, static_cast<unsigned>(pc.numPoints));  // the built-in head has no seams
  ASSERT_EQ(scene->mNumAnimations, 1u);
  ASSERT_EQ(scene->mAnimations[0]->mNumMorphMeshChannels, 1u);
  const aiMeshMorphAnim* channel = scene->mAnimations[0]->mMorphMeshChannels[0];
  ASSERT_EQ(channel->mNumKeys, pc.samples.size());
  for (unsigned k = 0; k < channel->mNumKeys; ++k)  // every frame, in metres, within 0.1 mm
    EXPECT_LT((playedFrame(mesh, channel->mKeys[k]) - 0.01 * pc.samples[k].cast<double>()).rowwise().norm().maxCoeff(),
              1e-4)
        << "frame " << k;
  // The skin moved: the last frame differs from the first by more than round-off.
  EXPECT_GT((pc.samples.back() - pc.samples.front()).cwiseAbs().maxCoeff(), 0.01);

  // The default head has UVs: the GLB carries the same ones as the run's OBJ frames.
  Assimp::Importer objImporter;
  const aiScene* obj = objImporter.ReadFile((dir_ / "out" / "obj" / "small_0000.obj").string(), 0);
  ASSERT_NE(obj, nullptr) << objImporter.GetErrorString();
  ASSERT_TRUE(mesh->HasTextureCoords(0));
  ASSERT_TRUE(obj->mMeshes[0]->HasTextureCoords(0));
  EXPECT_LT(maxCornerUvDifference(mesh, obj->mMeshes[0]), 1e-6);
}


// A rig (io/rig_export.h): one anim mesh per name, named from extras.targetNames, holding the base
// plus the delta; everything in metres as written (the node has no transform).
TEST_F(GltfAssimp, ReadsARigsNamedTargetsInMetres) {
  const AnimationFrames a = bulgeAnimation(3);
  RigExport rig;
  rig.name = "bulge";
  rig.rest = a.rest;
  rig.triangles = a.triangles;
  rig.names = {"mouthSmileLeft", "jawOpen", "cheekPuff"};
  for (const MatX3& p : a.positions) rig.deltas.push_back(p - a.rest);
  writeRigGlb(dir_ / "rig.glb", rig);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir_ / "rig.glb").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];
  ASSERT_EQ(mesh->mNumVertices, static_cast<unsigned>(a.rest.rows()));
  EXPECT_LT(maxDifference(mesh->mVertices, a.rest * 0.01), 1e-7);
  ASSERT_EQ(mesh->mNumAnimMeshes, 3u);
  for (unsigned k = 0; k < 3; ++k) {
    EXPECT_EQ(std::string(mesh->mAnimMeshes[k]->mName.C_Str()), rig.names[k]);
    EXPECT_LT(maxDifference(mesh->mAnimMeshes[k]->mVertices, a.positions[k] * 0.01), 1e-7) << k;
  }
  EXPECT_EQ(scene->mNumAnimations, 0u);
}

// A head with UV seams (tests/support/uv_seam_mesh.h): assimp reads the head's 7 vertices plus 2
// seam duplicates, each face corner with the OBJ's own texture coordinate (as assimp reads it from
// our OBJ of the same head, and as the reader's corner UVs hold it); every anim mesh moves a
// duplicate exactly as its original.
TEST_F(GltfAssimp, ARigWithSeamsHasTheObjsCornerUvs) {
  const TriMesh head = readObjFromString(test::kUvSeamObj, "seam.obj");
  const RigExport rig = test::seamRig(head, {"jawOpen"});
  const MatX3& delta = rig.deltas[0];
  writeRigGlb(dir_ / "seam.glb", rig);
  TriMesh triangles = head;  // assimp's OBJ importer keeps quads: write the triangles to compare faces
  triangles.polygons.clear();
  triangles.sourcePolygon.clear();
  writeObj((dir_ / "seam.obj").string(), triangles);

  Assimp::Importer glbImporter, objImporter;
  const aiScene* glb = glbImporter.ReadFile((dir_ / "seam.glb").string(), 0);
  const aiScene* obj = objImporter.ReadFile((dir_ / "seam.obj").string(), 0);
  ASSERT_NE(glb, nullptr) << glbImporter.GetErrorString();
  ASSERT_NE(obj, nullptr) << objImporter.GetErrorString();
  const aiMesh* g = glb->mMeshes[0];
  ASSERT_EQ(g->mNumVertices, 9u);  // 7 + 2 seam duplicates
  ASSERT_TRUE(g->HasTextureCoords(0));
  EXPECT_LT(maxCornerUvDifference(g, obj->mMeshes[0]), 1e-6);
  double worst = 0;
  for (unsigned f = 0; f < g->mNumFaces; ++f)
    for (unsigned c = 0; c < 3; ++c) {
      const aiVector3D& uv = g->mTextureCoords[0][g->mFaces[f].mIndices[c]];
      worst = std::max({worst, std::abs(uv.x - head.cornerUV(3 * f + c, 0)), std::abs(uv.y - head.cornerUV(3 * f + c, 1))});
    }
  EXPECT_LT(worst, 1e-6);

  const int source[9] = {0, 1, 2, 3, 4, 5, 6, 1, 4};
  ASSERT_EQ(g->mNumAnimMeshes, 1u);
  const aiAnimMesh* am = g->mAnimMeshes[0];
  for (unsigned i = 0; i < 9; ++i) {
    const Vec3 rest = head.V.row(source[i]), moved = rest + delta.row(source[i]).transpose();
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(g->mVertices[i][k], 0.01 * rest[k], 1e-7) << i;
      EXPECT_NEAR(am->mVertices[i][k], 0.01 * moved[k], 1e-7) << i;
    }
  }
}

}  // namespace
}  // namespace myo
