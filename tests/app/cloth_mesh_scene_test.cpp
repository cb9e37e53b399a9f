// Cloth from a mesh file: a rectangle written as an OBJ quad grid gives the
// built-in grid's simulation to the bit, per model; a triangle mesh runs every model (a cloth
// at its flat rest falls as a rigid body: no internal force at rest); bad meshes are errors
// naming the file and the problem; pins by index, region, box and vertex colour.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "scene_test_support.h"
#include "tests/support/test_files.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
using test::rectangle_obj;
using test::scene_error_of;

using test_files::write_text;

// A folder of its own for each test's files.
fs::path cloth_mesh_dir() {
  return test_files::fresh_directory(::testing::TempDir(), "weft_cloth_mesh_test");
}

// A 1 m × 0.5 m sheet hung from its far (v = 1) edge; sizes and spacings are powers of two, so
// assimp's single-precision floats hold the file's coordinates exactly.
Json sheet_scene(const std::string& model, const Json& cloth_shape) {
  Json s = Json::parse(R"({
    "description": "test sheet",
    "cloth": {"material": {"density": "0.2 kg/m^2", "stretch_warp": "200 N/m",
                           "stretch_weft": "150 N/m", "shear": "20 N/m",
                           "bend_warp": "2e-4 N*m", "bend_weft": "1e-4 N*m"},
              "pins": [{"region": {"u": [0, 1], "v": [1, 1]}}]},
    "simulation": {"air_damping": "0.5 1/s"},
    "output": {"fps": 24, "frames": 2}
  })");
  s["simulation"]["model"] = model;
  for (auto it = cloth_shape.begin(); it != cloth_shape.end(); ++it) s["cloth"][it.key()] = it.value();
  return s;
}

sim::Matrix3X simulate(const Json& scene, const fs::path& source, double seconds) {
  const Scene parsed = parse_scene(scene.dump(), source.string());
  const auto simulator = make_simulator(parsed);
  simulator->advance(seconds);
  return simulator->state().x;
}

class RectangleMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(RectangleMesh, GivesTheGridsSimulationToTheBit) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "rectangle.obj", rectangle_obj(9, 5, 1.0, 0.5, 1.0, false));
  const Json grid = {{"size", {"1 m", "0.5 m"}}, {"resolution", {9, 5}}};
  const Json mesh = {{"mesh", "rectangle.obj"}};
  const sim::Matrix3X a = simulate(sheet_scene(GetParam(), grid), dir / "scene.json", 0.25);
  const sim::Matrix3X b = simulate(sheet_scene(GetParam(), mesh), dir / "scene.json", 0.25);
  ASSERT_EQ(a.rows(), b.rows());
  // It moved (the test compares motion, not two resting sheets), and moved the same.
  EXPECT_GT((a.col(2).array() - 1.0).abs().maxCoeff(), 1e-3);
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0) << "not bit-identical";
}

INSTANTIATE_TEST_SUITE_P(Models, RectangleMesh,
                         ::testing::Values("mass_spring", "baraff_witkin", "rft3"));

TEST(ClothMesh, AQuadGridInTheFileIsTheGrid) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "rectangle.obj", rectangle_obj(9, 5, 1.0, 0.5, 1.0, false));
  const Scene s = parse_scene(sheet_scene("mass_spring", {{"mesh", "rectangle.obj"}}).dump(),
                              (dir / "scene.json").string());
  ASSERT_TRUE(s.mesh);
  EXPECT_TRUE(s.mesh->has_grid());
  EXPECT_EQ(s.mesh->nu, 9);
  EXPECT_EQ(s.mesh->nv, 5);
  EXPECT_EQ(s.mesh->source, "rectangle.obj");
}

class TriangleClothMesh : public ::testing::TestWithParam<std::string> {};

// A triangle mesh at its flat rest shape and unpinned: no internal force, so every vertex falls
// ½ g t² whatever the model (air damping 0); its mass is the density times its area.
TEST_P(TriangleClothMesh, FallsAsARigidBodyFromRest) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "triangles.obj", rectangle_obj(7, 5, 0.6, 0.4, 1.0, true));
  Json scene = sheet_scene(GetParam(), {{"mesh", "triangles.obj"}});
  scene["cloth"].erase("pins");
  scene["simulation"]["air_damping"] = "0 1/s";
  scene["render"]["ground"]["collider"] = false;
  const Scene parsed = parse_scene(scene.dump(), (dir / "scene.json").string());
  ASSERT_TRUE(parsed.mesh);
  EXPECT_FALSE(parsed.mesh->has_grid());
  EXPECT_EQ(parsed.mesh->faces.size(), 2u * 6 * 4);
  EXPECT_NEAR(parsed.mesh->vertex_area_m2.sum(), 0.6 * 0.4, 1e-7);
  const auto simulator = make_simulator(parsed);
  const double t = 0.2;
  simulator->advance(t);
  const sim::Matrix3X& x = simulator->state().x;
  const double drop = 0.5 * 9.81 * t * t;
  // Rigid: every vertex the same height (to rounding), the fall ½ g t² to the integrator's
  // first-order error in the step.
  EXPECT_LT(x.col(2).maxCoeff() - x.col(2).minCoeff(), 1e-9);
  EXPECT_NEAR(x(0, 2), 1.0 - drop, 0.02 * drop);
  for (sim::Index v = 0; v < x.rows(); ++v)
    EXPECT_NEAR(x(v, 0), parsed.mesh->start()(v, 0), 1e-9) << "vertex " << v;
}

INSTANTIATE_TEST_SUITE_P(Models, TriangleClothMesh,
                         ::testing::Values("mass_spring", "baraff_witkin", "rft3", "rft6"));

// A hanging triangle-mesh sheet stretches under its weight by about what the grid's does:
// the models agree on the physics, not the bits (a different mesh).
TEST(ClothMesh, TriangleMeshHangsLikeTheGrid) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "triangles.obj", rectangle_obj(9, 5, 1.0, 0.5, 1.0, true));
  const Json grid = {{"size", {"1 m", "0.5 m"}}, {"resolution", {9, 5}}};
  const Json mesh = {{"mesh", "triangles.obj"}};
  const sim::Matrix3X a = simulate(sheet_scene("baraff_witkin", grid), dir / "scene.json", 0.3);
  const sim::Matrix3X b = simulate(sheet_scene("baraff_witkin", mesh), dir / "scene.json", 0.3);
  // The meshes number their vertices differently: compare the lowest points.
  EXPECT_NEAR(a.col(2).minCoeff(), b.col(2).minCoeff(), 0.05 * (1.0 - a.col(2).minCoeff()));
}

TEST(ClothMesh, PinsByIndexRegionAndBox) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "triangles.obj", rectangle_obj(7, 5, 0.6, 0.4, 1.0, true));
  const auto pinned = [&](const Json& pins) {
    Json scene = sheet_scene("baraff_witkin", {{"mesh", "triangles.obj"}});
    scene["cloth"]["pins"] = pins;
    const Scene s = parse_scene(scene.dump(), (dir / "scene.json").string());
    return sim::resolve_pins(s.pins, *s.mesh);
  };
  EXPECT_EQ(pinned(Json::parse(R"([{"vertex": 3}])")), std::vector<sim::Index>{3});
  // The v = max edge: 7 vertices, by fractions, by a material box and by a world box.
  EXPECT_EQ(pinned(Json::parse(R"([{"region": {"u": [0, 1], "v": [1, 1]}}])")).size(), 7u);
  EXPECT_EQ(pinned(Json::parse(R"([{"box": {"min": ["0 m", "0.39 m"], "max": ["1 m", "1 m"]}}])")).size(), 7u);
  EXPECT_EQ(pinned(Json::parse(R"([{"box": {"space": "world", "min": ["-1 m", "0.39 m", "0 m"],
                                            "max": ["0.05 m", "1 m", "2 m"]}}])")).size(), 1u);
  const std::string no_grid = scene_error_of(
      [&] {
        Json scene = sheet_scene("baraff_witkin", {{"mesh", "triangles.obj"}});
        scene["cloth"]["pins"] = Json::parse(R"([{"corner": "u0v0"}])");
        return scene;
      }(),
      dir / "scene.json");
  EXPECT_CONTAINS(no_grid, "cloth.pins[0]");
  EXPECT_CONTAINS(no_grid, "needs the cloth's warp/weft grid");
  EXPECT_CONTAINS(no_grid, "triangles.obj");
}

// Pins by vertex color (OBJ "v x y z r g b", read by assimp): exactly the red vertices, on a
// triangle mesh and on a quad grid (renumbered), and they stay put while the rest falls.
TEST(ClothMesh, PinsByVertexColor) {
  const fs::path dir = cloth_mesh_dir();
  for (const bool triangles : {true, false}) {
    // Red: the two vertices at u = 0 of the v = max edge and (2, 4); the rest white.
    std::string obj = rectangle_obj(5, 5, 0.4, 0.4, 1.0, triangles);
    std::string coloured;
    std::size_t at = 0, v = 0;
    std::vector<sim::Vec3> red_at;
    for (std::size_t end; (end = obj.find('\n', at)) != std::string::npos; at = end + 1) {
      std::string line = obj.substr(at, end - at);
      if (line.rfind("v ", 0) == 0) {
        const int i = static_cast<int>(v % 5), j = static_cast<int>(v / 5);
        const bool red = (j == 4 && i <= 1) || (i == 2 && j == 4);
        line += red ? " 1 0 0" : " 1 1 1";
        if (red) red_at.emplace_back(i * 0.1, j * 0.1, 1.0);
        ++v;
      }
      coloured += line + "\n";
    }
    write_text(dir / "coloured.obj", coloured);
    Json scene = sheet_scene("baraff_witkin", {{"mesh", "coloured.obj"}});
    scene["cloth"]["pins"] = Json::parse(R"([{"color": [1, 0, 0]}])");
    const Scene s = parse_scene(scene.dump(), (dir / "scene.json").string());
    ASSERT_EQ(s.mesh->has_grid(), !triangles);
    const std::vector<sim::Index> pinned = sim::resolve_pins(s.pins, *s.mesh);
    ASSERT_EQ(pinned.size(), red_at.size());
    for (std::size_t k = 0; k < pinned.size(); ++k) {
      const sim::Vec3 x = s.mesh->start().row(pinned[k]).transpose();
      bool red = false;
      for (const sim::Vec3& r : red_at) red = red || (x - r).norm() < 1e-6;
      EXPECT_TRUE(red) << "vertex " << pinned[k] << " at " << x.transpose() << " is not red";
    }
    const auto simulator = make_simulator(s);
    simulator->advance(0.2);
    const sim::Matrix3X& x = simulator->state().x;
    for (const sim::Index p : pinned)
      EXPECT_EQ((x.row(p) - s.mesh->start().row(p)).norm(), 0.0) << "pinned vertex " << p;
    EXPECT_LT(x.col(2).minCoeff(), 1.0 - 0.05) << "the rest did not fall";
  }
}

TEST(ClothMeshErrors, PinByColorNamesTheFileAndTheColor) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "plain.obj", rectangle_obj(5, 5, 0.4, 0.4, 1.0, true));
  write_text(dir / "coloured.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 1 0\nv 0 1 0 1 0 0\n"
                              "f 1 2 3\nf 1 3 4\n");
  const auto error = [&](const std::string& file, const std::string& pins) {
    Json scene = sheet_scene("baraff_witkin", {{"mesh", file}});
    scene["cloth"]["pins"] = Json::parse(pins);
    return scene_error_of(scene, dir / "scene.json");
  };
  const std::string none = error("plain.obj", R"([{"color": [1, 0, 0]}])");
  EXPECT_CONTAINS(none, "cloth.pins[0].color");
  EXPECT_CONTAINS(none, "plain.obj has no vertex colors");
  const std::string blue = error("coloured.obj", R"([{"vertex": 0}, {"color": [0, 0, 1]}])");
  EXPECT_CONTAINS(blue, "cloth.pins[1].color");
  EXPECT_CONTAINS(blue, "no vertex of coloured.obj has the color [0, 0, 1] (tolerance 0.01)");
  // The green pair, within a tolerance; a tolerance without a color is an unknown key.
  Json scene = sheet_scene("baraff_witkin", {{"mesh", "coloured.obj"}});
  scene["cloth"]["pins"] = Json::parse(R"([{"color": [0.1, 0.9, 0], "tolerance": 0.2}])");
  const Scene s = parse_scene(scene.dump(), (dir / "scene.json").string());
  EXPECT_EQ(sim::resolve_pins(s.pins, *s.mesh), (std::vector<sim::Index>{1, 2}));
  EXPECT_CONTAINS(error("coloured.obj", R"([{"vertex": 0, "tolerance": 0.1}])"), "tolerance");
}

// The scene error of the cloth read from `obj` (written as bad.obj), with `extra` cloth keys.
std::string mesh_error(const std::string& obj, const Json& extra = Json::object()) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "bad.obj", obj);
  Json cloth = {{"mesh", "bad.obj"}};
  for (auto it = extra.begin(); it != extra.end(); ++it) cloth[it.key()] = it.value();
  Json scene = sheet_scene("baraff_witkin", cloth);
  scene["cloth"].erase("pins");
  return scene_error_of(scene, dir / "scene.json");
}

TEST(ClothMeshErrors, NameTheFileAndTheProblem) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  {
    const fs::path dir = cloth_mesh_dir();
    Json scene = sheet_scene("baraff_witkin", {{"mesh", "missing.obj"}});
    const std::string e = scene_error_of(scene, dir / "scene.json");
    EXPECT_CONTAINS(e, "cloth.mesh");
    EXPECT_CONTAINS(e, "missing.obj: cannot read mesh file");
  }
  const std::string no_uv = mesh_error(square + "f 1 2 3 4\n", {{"pattern", "uv"}});
  EXPECT_CONTAINS(no_uv, "bad.obj: no texture coordinates");
  const std::string fin = mesh_error(square + "v 0.5 0 0\nf 1 2 3\nf 1 3 4\nf 1 5 2\n");
  EXPECT_CONTAINS(fin, "bad.obj");
  EXPECT_CONTAINS(fin, "zero area");
  const std::string shared =
      mesh_error(square + "v 0.5 -1 0\nv 0.5 2 0\nf 1 2 3\nf 2 1 5\nf 1 2 6\n");
  EXPECT_CONTAINS(shared, "bad.obj");
  EXPECT_CONTAINS(shared, "more than two faces (a non-manifold mesh)");
  const std::string bent = mesh_error(square + "v 0.5 0.5 0.3\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n",
                                      {{"pattern", "plane"}});
  EXPECT_CONTAINS(bent, "bad.obj: the mesh is not flat");
  const std::string seam = mesh_error(square + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 5 5\n"
                                      "f 1/1 2/2 3/3\nf 1/5 3/3 4/4\n");
  EXPECT_CONTAINS(seam, "bad.obj: vertex");
  EXPECT_CONTAINS(seam, "UV seam");
  const std::string grid_keys = mesh_error(square + "f 1 2 3 4\n", {{"size", {"1 m", "1 m"}}});
  EXPECT_CONTAINS(grid_keys, "cloth.size: the cloth comes from the mesh file");
}

TEST(ClothMeshErrors, FastProjectionOnATriangleMeshNamesTheReason) {
  const fs::path dir = cloth_mesh_dir();
  write_text(dir / "triangles.obj", rectangle_obj(7, 5, 0.6, 0.4, 1.0, true));
  Json scene = sheet_scene("baraff_witkin", {{"mesh", "triangles.obj"}});
  scene["simulation"]["constraints"] = {{"method", "fast_projection"}};
  const Scene s = parse_scene(scene.dump(), (dir / "scene.json").string());
  try {
    make_simulator(s);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(std::string(e.what()), "warp/weft edges");
    EXPECT_CONTAINS(std::string(e.what()), "needs the cloth's warp/weft grid");
    EXPECT_CONTAINS(std::string(e.what()), "triangles.obj");
  }
}

}  // namespace
}  // namespace weft::app
