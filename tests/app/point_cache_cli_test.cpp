// `weft run --export-cache pc2,mdd,gltf`: the files read back — the point
// caches byte by byte against their formats (app/io/point_cache.h), the animated glTF and the
// OBJ with its material through assimp's importer — and checked against the simulation: frame 0
// is the start, the pinned corners stay where the scene pins them in every frame, a free corner
// falls, and every format holds the same frames.

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace weft::app {
namespace {

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// The 4-byte word at `offset`, little- or big-endian, as T (int32 or float32).
template <class T>
T word(const std::string& bytes, std::size_t offset, bool big_endian) {
  std::uint32_t w = 0;
  for (int k = 0; k < 4; ++k) {
    const auto byte = static_cast<std::uint8_t>(bytes.at(offset + static_cast<std::size_t>(k)));
    w |= static_cast<std::uint32_t>(byte) << (big_endian ? 24 - 8 * k : 8 * k);
  }
  T value;
  std::memcpy(&value, &w, 4);
  return value;
}

using Frames = std::vector<std::vector<Eigen::Vector3f>>;

Frames points(const std::string& bytes, std::size_t offset, int frames, int count, bool big_endian) {
  Frames out(static_cast<std::size_t>(frames));
  for (auto& frame : out) {
    for (int v = 0; v < count; ++v, offset += 12)
      frame.emplace_back(word<float>(bytes, offset, big_endian),
                         word<float>(bytes, offset + 4, big_endian),
                         word<float>(bytes, offset + 8, big_endian));
  }
  return out;
}

class PointCacheCli : public test::CliDirectoryTest {
 protected:
  PointCacheCli() : CliDirectoryTest("point_cache_cli") {}
};

TEST_F(PointCacheCli, CachesReadBackAsTheSimulatedFrames) {
  // The tiny hang: 9 × 9 vertices, pinned at corners u0v1 = (−0.1, 0.2, 0.5) and
  // u1v1 = (0.1, 0.2, 0.5) m; 4 frames at 24 fps, cached as frames 0 (the start) to 4: sample
  // k is frame k, as Blender's Mesh Cache modifier plays it on its defaults. --every 3 draws
  // frames 1 and 4 only; the cache still holds every frame. The cloth's colour is the materials'.
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const auto r = test::run_weft("run " + scene.string() + " --export-cache pc2,mdd,gltf --every 3 "
                                "--set 'render.colors.front=[0.125,0.5,0.75]' --out " +
                                (m_dir / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(m_dir / "run" / "frame_0004.png")) << "the last frame";
  EXPECT_FALSE(std::filesystem::exists(m_dir / "run" / "frame_0002.png"));
  const int frames = 5, count = 81;  // frames 0..4

  const std::string pc2 = file_bytes(m_dir / "run" / "cloth.pc2");
  ASSERT_EQ(pc2.size(), 32u + 12u * frames * count);
  EXPECT_EQ(pc2.substr(0, 12), std::string("POINTCACHE2\0", 12));
  EXPECT_EQ(word<std::int32_t>(pc2, 12, false), 1);  // version
  EXPECT_EQ(word<std::int32_t>(pc2, 16, false), count);
  EXPECT_EQ(word<float>(pc2, 20, false), 0.0f);  // start frame: frame 0
  EXPECT_EQ(word<float>(pc2, 24, false), 1.0f);  // sample rate
  EXPECT_EQ(word<std::int32_t>(pc2, 28, false), frames);
  const Frames cached = points(pc2, 32, frames, count, false);

  const std::string mdd = file_bytes(m_dir / "run" / "cloth.mdd");
  ASSERT_EQ(mdd.size(), 8u + 4u * frames + 12u * frames * count);
  EXPECT_EQ(word<std::int32_t>(mdd, 0, true), frames);
  EXPECT_EQ(word<std::int32_t>(mdd, 4, true), count);
  for (int k = 0; k < frames; ++k)  // frame k at t = k / 24 s
    EXPECT_NEAR(word<float>(mdd, 8 + 4 * static_cast<std::size_t>(k), true), k / 24.0, 1e-6);
  EXPECT_EQ(points(mdd, 8 + 4 * frames, frames, count, true), cached);

  // y up: weft's (x, y, z) is (x, z, −y). Pins at vertices (0, 8) and (8, 8) = 72 and 80.
  for (const auto& frame : cached) {
    EXPECT_TRUE(frame[72].isApprox(Eigen::Vector3f(-0.1f, 0.5f, -0.2f), 1e-6f)) << frame[72];
    EXPECT_TRUE(frame[80].isApprox(Eigen::Vector3f(0.1f, 0.5f, -0.2f), 1e-6f)) << frame[80];
  }
  EXPECT_LT(cached[4][0].y(), cached[1][0].y() - 0.01f) << "the free corner falls";
  // Frame 0 is the start: the flat sheet at z = 0.5 m, y up 0.5 m.
  for (int v = 0; v < count; ++v) EXPECT_FLOAT_EQ(cached[0][v].y(), 0.5f) << v;
  EXPECT_LT(cached[1][0].y(), 0.5f) << "frame 1 has fallen";

  // The OBJ: frame 0's positions in the caches' vertex order, and the grid's triangles.
  std::ifstream obj(m_dir / "run" / "cloth.obj");
  std::vector<Eigen::Vector3f> rest;
  int faces = 0;
  std::string mtllib, usemtl;
  for (std::string line; std::getline(obj, line);) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      Eigen::Vector3f p;
      in >> p.x() >> p.y() >> p.z();
      rest.push_back(p);
    }
    if (tag == "mtllib") in >> mtllib;
    if (tag == "usemtl") in >> usemtl;
    faces += tag == "f";
  }
  ASSERT_EQ(rest.size(), static_cast<std::size_t>(count));
  EXPECT_EQ(faces, 2 * 8 * 8);
  for (int v = 0; v < count; ++v) EXPECT_TRUE(rest[v].isApprox(cached[0][v], 1e-6f)) << v;
  EXPECT_EQ(mtllib, "cloth.mtl");
  EXPECT_EQ(usemtl, "cloth");

  // The OBJ and its material through assimp: the cloth's colour.
  {
    Assimp::Importer obj_importer;
    const aiScene* read = obj_importer.ReadFile((m_dir / "run" / "cloth.obj").string(), 0);
    ASSERT_NE(read, nullptr) << obj_importer.GetErrorString();
    aiColor3D kd;
    const aiMaterial* material = read->mMaterials[read->mMeshes[0]->mMaterialIndex];
    ASSERT_EQ(material->Get(AI_MATKEY_COLOR_DIFFUSE, kd), aiReturn_SUCCESS);
    EXPECT_EQ(Eigen::Vector3f(kd.r, kd.g, kd.b), Eigen::Vector3f(0.125f, 0.5f, 0.75f));
  }

  // The glTF through assimp: frame 0 as the mesh, frames 1..4 as its morph targets, one
  // animation stepping through them, and a material of the cloth's colour.
  Assimp::Importer importer;
  const aiScene* gltf = importer.ReadFile((m_dir / "run" / "cloth.gltf").string(), 0);
  ASSERT_NE(gltf, nullptr) << importer.GetErrorString();
  ASSERT_EQ(gltf->mNumMeshes, 1u);
  const aiMesh* mesh = gltf->mMeshes[0];
  ASSERT_EQ(mesh->mNumVertices, static_cast<unsigned>(count));
  EXPECT_EQ(mesh->mNumFaces, 128u);
  for (int v = 0; v < count; ++v) {
    const aiVector3D& p = mesh->mVertices[v];
    EXPECT_TRUE(Eigen::Vector3f(p.x, p.y, p.z).isApprox(cached[0][v], 1e-6f)) << v;
  }
  ASSERT_EQ(mesh->mNumAnimMeshes, static_cast<unsigned>(frames - 1));
  for (int k = 1; k < frames; ++k) {
    const aiAnimMesh* target = mesh->mAnimMeshes[k - 1];
    float worst = 0.0f;
    for (int v = 0; v < count; ++v) {
      const aiVector3D& p = target->mVertices[v];
      worst = std::max(worst, (Eigen::Vector3f(p.x, p.y, p.z) - cached[k][v]).norm());
    }
    EXPECT_LT(worst, 1e-6f) << "morph target " << k - 1 << " is frame " << k;
  }
  aiColor4D base;
  ASSERT_EQ(gltf->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_BASE_COLOR, base), aiReturn_SUCCESS);
  EXPECT_EQ(Eigen::Vector4f(base.r, base.g, base.b, base.a), Eigen::Vector4f(0.125f, 0.5f, 0.75f, 1.0f));
  ASSERT_EQ(gltf->mNumAnimations, 1u);
  EXPECT_EQ(gltf->mAnimations[0]->mNumMorphMeshChannels, 1u);
}

TEST_F(PointCacheCli, UnknownFormatIsRefused) {
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const auto r = test::run_weft("run " + scene.string() + " --export-cache pc2,abc --out " +
                                (m_dir / "bad").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--export-cache: expected pc2, mdd, gltf"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(m_dir / "bad"));
}

}  // namespace
}  // namespace weft::app
