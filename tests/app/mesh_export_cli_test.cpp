// Mesh export through the real `weft run --export-meshes`: OBJ and PLY are y-up by default
// (Blender's OBJ import shows a hanging cloth hanging), `--up z` keeps weft's frame, and the
// files carry the cloth's colour — an OBJ and a glTF also its texture, written beside them.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/io/mesh_file.h"
#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class MeshExportCli : public CliDirectoryTest {
 protected:
  MeshExportCli() : CliDirectoryTest("mesh_export_cli") {}
  // Runs the tiny scene (pins at z = 0.5 m, the cloth at y in [0, 0.2] m) for one frame.
  fs::path run(const std::string& scene_text, const std::string& options) {
    const fs::path scene = write_scene("scene.json", scene_text);
    const fs::path out = m_dir / "out";
    const auto r = run_weft("run " + scene.string() + " --frames 1 --out " + out.string() + " " + options);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return out;
  }
};

// The tiny scene with `extra` keys in its render block.
std::string with_render(const std::string& extra) {
  std::string text = tiny_scene();
  const std::string camera = R"("target": [0, 0.1, 0.4]})";
  return text.insert(text.find(camera) + camera.size(), extra);
}

std::string file_text(const fs::path& path) {
  std::stringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}

TEST_F(MeshExportCli, ObjIsYUpByDefaultAndZUpWhenAsked) {
  const fs::path out = run(tiny_scene(), "--export-meshes obj");
  const weft::app::TriangleMesh y_up = weft::app::load_triangle_mesh(out / "mesh_0001.obj");
  // The pinned edge is the top: height 0.5 m along y; weft's y ∈ [0, 0.2] is now −z.
  EXPECT_NEAR(y_up.vertices.col(1).maxCoeff(), 0.5, 1e-6);
  EXPECT_LT(y_up.vertices.col(1).minCoeff(), 0.5);
  EXPECT_NEAR(y_up.vertices.col(2).minCoeff(), -0.2, 0.01);
  EXPECT_LT(y_up.vertices.col(2).maxCoeff(), 1e-3);
  EXPECT_CONTAINS(file_text(out / "mesh_0001.mtl"), "Kd 0.8");  // the front colour

  const fs::path z_out = run(tiny_scene(), "--export-meshes ply --up z");
  const weft::app::TriangleMesh z_up = weft::app::load_triangle_mesh(z_out / "mesh_0001.ply");
  EXPECT_NEAR(z_up.vertices.col(2).maxCoeff(), 0.5, 1e-6);
  EXPECT_GT(z_up.vertices.col(1).minCoeff(), -1e-3);

  const auto bad = run_weft("run " + write_scene("s.json", tiny_scene()).string() +
                            " --export-meshes obj --up x --out " + (m_dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_CONTAINS(bad.output, "--up");
}

TEST_F(MeshExportCli, GltfCarriesBaseColourAndTexture) {
  const fs::path plain = run(with_render(R"(, "colors": {"front": [0.1, 0.6, 0.3]})"),
                             "--export-meshes gltf");
  const nlohmann::json p = nlohmann::json::parse(file_text(plain / "mesh_0001.gltf"));
  const nlohmann::json factor = p["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"];
  ASSERT_EQ(factor.size(), 4u) << p["materials"].dump();
  EXPECT_NEAR(factor[0].get<double>(), 0.1, 1e-6);
  EXPECT_NEAR(factor[1].get<double>(), 0.6, 1e-6);
  EXPECT_NEAR(factor[2].get<double>(), 0.3, 1e-6);
  EXPECT_FALSE(fs::exists(plain / "mesh_texture.png"));

  const fs::path textured = run(
      with_render(R"(, "texture": {"woven_check": {}, "scale": ["5 cm", "5 cm"]})"),
      "--export-meshes gltf");
  const nlohmann::json t = nlohmann::json::parse(file_text(textured / "mesh_0001.gltf"));
  const nlohmann::json& pbr = t["materials"][0]["pbrMetallicRoughness"];
  ASSERT_TRUE(pbr.contains("baseColorTexture")) << t["materials"].dump();
  const int image = t["textures"][pbr["baseColorTexture"]["index"].get<int>()]["source"];
  const std::string uri = t["images"][image]["uri"];
  EXPECT_EQ(uri, "mesh_texture.png");
  EXPECT_GT(weft::render::read_image(textured / uri).width(), 0);
  // UVs are texture repeats: the 20 cm cloth spans 4 repeats of 5 cm.
  const nlohmann::json& uv = t["accessors"][t["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].get<int>()];
  EXPECT_NEAR(uv["max"][0].get<double>() - uv["min"][0].get<double>(), 4.0, 1e-4);
  // A later run without the texture removes it.
  run(tiny_scene(), "--export-meshes gltf");
  EXPECT_FALSE(fs::exists(textured / "mesh_texture.png"));
}

// An OBJ names the texture in its MTL (map_Kd) and carries texture coordinates: with the
// piece mapping the 20 cm cloth spans exactly one image, [0, 1] on both axes.
TEST_F(MeshExportCli, ObjCarriesThePieceTextureInItsMtl) {
  const fs::path out = run(with_render(R"(, "texture": {"woven_check": {}, "mapping": "piece"})"),
                           "--export-meshes obj");
  ASSERT_TRUE(fs::exists(out / "mesh_texture.png"));
  const std::string mtl = file_text(out / "mesh_0001.mtl");
  EXPECT_CONTAINS(mtl, "map_Kd mesh_texture.png");
  std::istringstream obj(file_text(out / "mesh_0001.obj"));
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  int count = 0;
  for (std::string line; std::getline(obj, line);) {
    std::istringstream fields(line);
    std::string tag;
    double st[2];
    if (!(fields >> tag) || tag != "vt" || !(fields >> st[0] >> st[1])) continue;
    ++count;
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], st[k]), hi[k] = std::max(hi[k], st[k]);
  }
  ASSERT_GT(count, 0);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(lo[k], 0.0, 1e-6) << "axis " << k;
    EXPECT_NEAR(hi[k], 1.0, 1e-6) << "axis " << k;
  }
}

}  // namespace
