// Cloth frames exported through assimp (app/io/mesh_export.h) and read back: every format keeps the
// vertex positions (to float precision), the triangle count, the normals and the UVs = material
// coordinates; every format is y-up unless asked for weft's z-up (OBJ/PLY).
#include "app/io/mesh_export.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/run/frame_mesh.h"
#include "app/io/mesh_file.h"
#include "app/scene/scene.h"
#include "sim/grid.h"

namespace fs = std::filesystem;

namespace {

using weft::app::MeshFormat;
using weft::app::UpAxis;

// A 5×4-vertex, 20 cm × 15 cm cloth bent into a wave, as weft run exports it.
weft::render::RenderMesh wavy_cloth() {
  weft::sim::GridSpec spec;
  spec.size_u_m = 0.20;
  spec.size_v_m = 0.15;
  spec.nu = 5;
  spec.nv = 4;
  spec.origin = {-0.1, -0.05, 0.3};
  const weft::sim::ClothMesh mesh = weft::sim::make_grid(spec);
  weft::sim::Matrix3X x = mesh.rest_positions;
  for (Eigen::Index v = 0; v < x.rows(); ++v) x(v, 2) += 0.03 * std::sin(20.0 * x(v, 0) + 7.0 * x(v, 1));
  return weft::app::to_render_mesh(mesh, x);
}

fs::path output_dir() {
  const fs::path dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "mesh_export";
  fs::create_directories(dir);
  return dir;
}

// The cloth point or direction p as the file's vertex data holds it: an OBJ/PLY turned y-up,
// (x, y, z) ↦ (x, z, −y), unless asked for z-up; a glTF's in weft's coordinates.
Eigen::Vector3f stored(MeshFormat format, UpAxis up, const Eigen::Vector3f& p) {
  if (format != MeshFormat::gltf && up == UpAxis::y) return {p.x(), p.z(), -p.y()};
  return p;
}

// Where a reader that applies the node transforms puts the cloth point p: y-up, the glTF's
// root node turning its data, unless an OBJ/PLY was asked for z-up.
Eigen::Vector3d placed(MeshFormat format, UpAxis up, const Eigen::Vector3f& p) {
  if (format == MeshFormat::gltf) return {p.x(), p.z(), -p.y()};
  return stored(format, up, p).cast<double>();
}

Eigen::Vector3f vec(const aiVector3D& p) { return {p.x, p.y, p.z}; }

void expect_round_trip(MeshFormat format, UpAxis up = UpAxis::y) {
  const weft::render::RenderMesh cloth = wavy_cloth();
  const fs::path path = output_dir() / (std::string(up == UpAxis::y ? "wavy." : "wavy_z.") +
                                        weft::app::mesh_extension(format));
  fs::remove(path);
  weft::app::MeshExportOptions options;
  options.up = up;
  weft::app::export_mesh(cloth, format, path, options);
  ASSERT_TRUE(fs::exists(path)) << path;

  // Through weft's own reader (node transforms applied, identical positions joined).
  const weft::app::TriangleMesh read = weft::app::load_triangle_mesh(path);
  EXPECT_EQ(read.vertices.rows(), static_cast<Eigen::Index>(cloth.positions.size())) << path;
  EXPECT_EQ(read.triangles.size(), cloth.triangles.size()) << path;
  // Each vertex read is a cloth vertex, placed as the format says (joined order may differ).
  for (Eigen::Index k = 0; k < read.vertices.rows(); ++k) {
    double best = INFINITY;
    for (const Eigen::Vector3f& p : cloth.positions)
      best = std::min(best, (read.vertices.row(k).transpose() - placed(format, up, p)).norm());
    EXPECT_LT(best, 1e-6) << path << " vertex " << k;
  }

  // The mesh's own data through assimp, with the attributes (whatever the node transform):
  // match each vertex read to the cloth vertex stored at its position, then compare normal
  // and UV.
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_JoinIdenticalVertices);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];
  ASSERT_TRUE(mesh->HasTextureCoords(0)) << path << ": no UVs";
  ASSERT_TRUE(mesh->HasNormals()) << path << ": no normals";
  EXPECT_EQ(mesh->mNumFaces, cloth.triangles.size());
  for (unsigned k = 0; k < mesh->mNumVertices; ++k) {
    const Eigen::Vector3f p = vec(mesh->mVertices[k]);
    // The nearest cloth vertex (positions are read back exactly or within float rounding).
    std::size_t nearest = 0;
    float best = INFINITY;
    for (std::size_t v = 0; v < cloth.positions.size(); ++v) {
      const float d = (stored(format, up, cloth.positions[v]) - p).norm();
      if (d < best) best = d, nearest = v;
    }
    EXPECT_LT(best, 1e-6f) << path << " vertex " << k;
    const Eigen::Vector3f n = vec(mesh->mNormals[k]);
    EXPECT_LT((n - stored(format, up, cloth.normals[nearest])).norm(), 1e-5f)
        << path << " normal " << k;
    const aiVector3D uv = mesh->mTextureCoords[0][k];
    EXPECT_NEAR(uv.x, cloth.uvs[nearest].x(), 1e-6f) << path << " u " << k;
    EXPECT_NEAR(uv.y, cloth.uvs[nearest].y(), 1e-6f) << path << " v " << k;
  }
}

TEST(MeshExport, ObjRoundTrip) { expect_round_trip(MeshFormat::obj); }
TEST(MeshExport, PlyRoundTrip) { expect_round_trip(MeshFormat::ply); }
TEST(MeshExport, ObjAndPlyKeepWeftsZUpWhenAsked) {
  expect_round_trip(MeshFormat::obj, UpAxis::z);
  expect_round_trip(MeshFormat::ply, UpAxis::z);
}
TEST(MeshExport, GltfRoundTrip) { expect_round_trip(MeshFormat::gltf); }

TEST(MeshExport, FormatNames) {
  EXPECT_EQ(weft::app::parse_mesh_format("ply", "--export-meshes"), MeshFormat::ply);
  try {
    weft::app::parse_mesh_format("stl", "--export-meshes");
    FAIL() << "no error";
  } catch (const weft::app::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--export-meshes: expected one of obj, ply, gltf"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
