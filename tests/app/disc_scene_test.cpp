// "cloth.shape": disc specimens in scene files (the Cusick drape test), pins on them, and what
// is drawn of them (app/run/frame_mesh.h): the used vertices only; "cloth.edge": the staircase
// of grid cells or the smooth edge of a disc meshed in rings.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <utility>
#include <vector>
#include <string>

#include "app/run/frame_mesh.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "sim/material/material_presets.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json disc_scene() {
  return Json::parse(R"({
    "description": "a 30 cm disc, falling",
    "cloth": {"size": ["30 cm", "30 cm"], "resolution": [15, 15], "shape": "disc",
              "origin": ["-15 cm", "-15 cm", "50 cm"]},
    "simulation": {"air_damping": "0 1/s"}
  })");
}

TEST(DiscScene, ShapeIsReadAndDefaultsToRectangle) {
  EXPECT_EQ(test::parse_json_scene(disc_scene()).grid.shape, sim::SpecimenShape::disc);
  Json j = disc_scene();
  j["cloth"].erase("shape");
  EXPECT_EQ(test::parse_json_scene(j).grid.shape, sim::SpecimenShape::rectangle);
  j["cloth"]["shape"] = "rectangle";
  EXPECT_EQ(test::parse_json_scene(j).grid.shape, sim::SpecimenShape::rectangle);
}

TEST(DiscScene, AnUnknownShapeListsTheChoices) {
  Json j = disc_scene();
  j["cloth"]["shape"] = "circle";
  EXPECT_CONTAINS(test::scene_error_of(j),
                  "scene.json: cloth.shape: expected one of 'rectangle', 'disc', got the string "
                  "'circle'");
}

TEST(DiscScene, APinOutsideTheDiscIsAnErrorNamingThePin) {
  Json j = disc_scene();
  j["cloth"]["pins"] = Json::parse(R"([{"grid": [7, 7]}, {"corner": "u0v0"}])");
  EXPECT_EQ(test::scene_error_of(j),
            "scene.json: cloth.pins[1]: corner u0v0 is not part of the cloth (outside the "
            "trimmed specimen)");
  j["cloth"]["pins"] = Json::parse(R"([{"region": {"u": [0, 0.05], "v": [0.9, 1]}}])");
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: cloth.pins[0]: region");
  EXPECT_CONTAINS(test::scene_error_of(j), "contains no vertex of the cloth");
}

// Falling for a few frames, the unused vertices stay where they were and are not drawn; the
// drawn mesh is the used vertices, in order, and two triangles per kept cell.
TEST(DiscScene, OnlyTheDiscIsDrawn) {
  const Scene scene = test::parse_json_scene(disc_scene());
  const auto sim = make_simulator(scene);
  sim->advance(0.1);
  const sim::ClothMesh& mesh = sim->mesh();
  const sim::Matrix3X& x = sim->state().x;
  const render::RenderMesh drawn = to_render_mesh(mesh, x);
  ASSERT_EQ(static_cast<sim::Index>(drawn.positions.size()), mesh.used_vertex_count());
  ASSERT_LT(mesh.used_vertex_count(), mesh.vertex_count());
  EXPECT_EQ(drawn.triangles.size(), 2 * mesh.quads.size());
  std::size_t k = 0;
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v) {
    if (!mesh.is_used(v)) {
      EXPECT_EQ(sim::Vec3(x.row(v).transpose()), sim::Vec3(mesh.rest_positions.row(v).transpose()));
      continue;
    }
    EXPECT_EQ(drawn.positions[k], sim::Vec3(x.row(v).transpose()).cast<float>());
    ++k;
  }
  // Everything drawn has fallen (by g t²/2 ≈ 4.9 cm) and lies within the disc's radius, plus
  // half a cell diagonal, of its axis.
  const double h = 0.3 / 14.0;
  for (const Eigen::Vector3f& p : drawn.positions) {
    EXPECT_NEAR(p.z(), 0.5 - 0.5 * 9.81 * 0.01, 0.002);
    EXPECT_LE(std::hypot(p.x(), p.y()), 0.15 + h / std::sqrt(2.0) + 1e-6);
  }
  for (const auto& t : drawn.triangles)
    for (std::uint32_t v : t) EXPECT_LT(v, drawn.positions.size());
}

// A rectangle is drawn as before: every vertex, numbered as the simulator numbers them.
TEST(DiscScene, TheRectangleIsDrawnWhole) {
  Json j = disc_scene();
  j["cloth"]["shape"] = "rectangle";
  const Scene scene = test::parse_json_scene(j);
  const sim::ClothMesh mesh = sim::make_grid(scene.grid);
  const render::RenderMesh drawn = to_render_mesh(mesh, mesh.rest_positions);
  ASSERT_EQ(static_cast<sim::Index>(drawn.positions.size()), mesh.vertex_count());
  const auto triangles = mesh.triangles();
  ASSERT_EQ(drawn.triangles.size(), triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_EQ(static_cast<sim::Index>(drawn.triangles[t][c]), triangles[t][c]);
}

// The wireframe's lines of a trimmed grid: exactly the sides of the kept
// cells, each once, in the drawn mesh's numbering; no cell diagonal among them.
TEST(DiscScene, WireframeEdgesAreTheKeptCellsWarpAndWeftSides) {
  const Scene scene = test::parse_json_scene(disc_scene());
  const sim::ClothMesh mesh = sim::make_grid(scene.grid);
  const render::RenderMesh drawn = to_render_mesh(mesh, mesh.rest_positions);
  std::vector<std::uint32_t> slot(static_cast<std::size_t>(mesh.vertex_count()), 0);
  for (std::uint32_t k = 0, v = 0; v < slot.size(); ++v)
    if (mesh.is_used(v)) slot[v] = k++;
  std::set<std::pair<std::uint32_t, std::uint32_t>> expected, actual;
  for (const auto& q : mesh.quads)
    for (int k = 0; k < 4; ++k)
      expected.insert(std::minmax(slot[static_cast<std::size_t>(q[k])],
                                  slot[static_cast<std::size_t>(q[(k + 1) % 4])]));
  for (const auto& [a, b] : drawn.edges) {
    EXPECT_TRUE(actual.insert(std::minmax(a, b)).second) << "edge " << a << "-" << b << " twice";
    // A warp or weft edge: its ends differ in one material coordinate only.
    const Eigen::Vector2f d = drawn.uvs[a] - drawn.uvs[b];
    EXPECT_TRUE((d.x() == 0.0f) != (d.y() == 0.0f)) << "edge " << a << "-" << b << " is diagonal";
  }
  EXPECT_EQ(actual, expected);
  EXPECT_LT(drawn.edges.size(), 3 * drawn.triangles.size() / 2);  // fewer than all sides
}

// "cloth.edge": a disc's edge, the grid's staircase or smooth (sim/round_specimen.h).
TEST(DiscScene, EdgeIsReadAndDefaultsToStaircase) {
  EXPECT_EQ(test::parse_json_scene(disc_scene()).grid.disc_edge, sim::DiscEdge::staircase);
  Json j = disc_scene();
  j["cloth"]["edge"] = "smooth";
  EXPECT_EQ(test::parse_json_scene(j).grid.disc_edge, sim::DiscEdge::smooth);
  j["cloth"]["edge"] = "staircase";
  EXPECT_EQ(test::parse_json_scene(j).grid.disc_edge, sim::DiscEdge::staircase);
}

TEST(DiscScene, EdgeErrorsNameTheKey) {
  Json j = disc_scene();
  j["cloth"]["edge"] = "round";
  EXPECT_CONTAINS(test::scene_error_of(j),
                  "scene.json: cloth.edge: expected one of 'staircase', 'smooth', got the string "
                  "'round'");
  j["cloth"]["edge"] = "smooth";
  j["cloth"]["shape"] = "rectangle";
  EXPECT_EQ(test::scene_error_of(j),
            "scene.json: cloth.edge: applies to a disc (\"shape\": \"disc\"); a rectangle's "
            "edges are straight grid lines");
  j["cloth"].erase("shape");
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: cloth.edge: applies to a disc");
  // With a mesh file, checked before the file is read.
  j = disc_scene();
  for (const char* key : {"size", "resolution", "shape"}) j["cloth"].erase(key);
  j["cloth"]["mesh"] = "no_such_file.obj";
  j["cloth"]["edge"] = "smooth";
  EXPECT_EQ(test::scene_error_of(j),
            "scene.json: cloth.edge: the cloth comes from the mesh file in cloth.mesh; a grid key "
            "does not apply");
}

// A smooth disc is its ring mesh: no grid, 1 + 3N(N + 1) vertices for N = ⌈(n − 1)/2⌉ rings,
// named so in what weft prints; it falls like the staircase disc.
TEST(DiscScene, ASmoothDiscIsItsRingMesh) {
  Json j = disc_scene();
  j["cloth"]["edge"] = "smooth";
  const Scene scene = test::parse_json_scene(j);
  const sim::ClothMesh mesh = cloth_mesh(scene);
  EXPECT_FALSE(mesh.has_grid());
  EXPECT_EQ(mesh.vertex_count(), 1 + 3 * 7 * 8);  // resolution 15: 7 rings
  EXPECT_EQ(cloth_size_text(scene), "169 vertices (a disc in 7 rings)");
  const auto sim = make_simulator(scene);
  sim->advance(0.1);
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v)
    EXPECT_NEAR(sim->state().x(v, 2), 0.5 - 0.5 * 9.81 * 0.01, 0.002) << v;
  const render::RenderMesh drawn = to_render_mesh(sim->mesh(), sim->state().x);
  EXPECT_EQ(static_cast<sim::Index>(drawn.positions.size()), mesh.vertex_count());
  EXPECT_EQ(drawn.triangles.size(), mesh.faces.size());
}

// A smooth disc has no grid vertices or corners to pin: the error names the pin and the ways
// that work instead.
TEST(DiscScene, GridAndCornerPinsOnASmoothDiscAreErrorsNamingThePin) {
  Json j = disc_scene();
  j["cloth"]["edge"] = "smooth";
  j["cloth"]["pins"] = Json::parse(R"([{"vertex": 0}, {"grid": [7, 7]}])");
  EXPECT_EQ(test::scene_error_of(j),
            "scene.json: cloth.pins[1]: a pin by grid vertex needs the warp/weft grid, and a disc "
            "with \"edge\": \"smooth\" is meshed in rings of triangles without one: pin by "
            "\"vertex\" (0 is the centre), \"region\" (fractions of the disc's box: {\"u\": "
            "[0.5, 0.5], \"v\": [0.5, 0.5]} is the centre) or \"box\"");
  j["cloth"]["pins"] = Json::parse(R"([{"corner": "u0v0"}])");
  EXPECT_CONTAINS(test::scene_error_of(j), "scene.json: cloth.pins[0]: a pin by corner needs");
}

// The region at the middle of the box pins the centre alone, on either edge: the grid's centre
// vertex, or the rings' vertex 0.
TEST(DiscScene, TheMiddleRegionPinsTheCentreOfEitherDisc) {
  Json j = disc_scene();
  j["cloth"]["pins"] = Json::parse(R"([{"region": {"u": [0.5, 0.5], "v": [0.5, 0.5]}}])");
  const Scene staircase = test::parse_json_scene(j);
  const sim::ClothMesh grid = cloth_mesh(staircase);
  EXPECT_EQ(sim::resolve_pins(staircase.pins, grid), std::vector<sim::Index>{grid.index(7, 7)});
  j["cloth"]["edge"] = "smooth";
  const Scene smooth = test::parse_json_scene(j);
  EXPECT_EQ(sim::resolve_pins(smooth.pins, cloth_mesh(smooth)), std::vector<sim::Index>{0});
}

// The Cusick drape scene with a smooth edge: a Ø30 cm wool disc centred over a Ø18 cm support
// disc (cusick_drape.json is the same test on the grid's staircase disc, for the mass-spring
// model and its static solves).
TEST(DiscScene, CusickDrapeSceneIsTheStandardGeometry) {
  const Scene s = load_scene(std::filesystem::path(WEFT_SOURCE_DIR) / "assets" / "scenes" /
                             "cusick_drape_round.json");
  EXPECT_EQ(s.grid.shape, sim::SpecimenShape::disc);
  EXPECT_EQ(s.grid.disc_edge, sim::DiscEdge::smooth);
  EXPECT_NEAR(s.grid.size_u_m, 0.30, 1e-12);
  EXPECT_NEAR(s.grid.size_v_m, 0.30, 1e-12);
  // Held at its centre only, in place of the standard's upper clamping disc.
  const sim::ClothMesh mesh = cloth_mesh(s);
  EXPECT_EQ(sim::resolve_pins(s.pins, mesh), std::vector<sim::Index>{0});
  EXPECT_TRUE(sim::Vec3(mesh.rest_positions.row(0).transpose())
                  .isApprox(s.grid.origin + 0.15 * s.grid.warp_axis + 0.15 * s.grid.weft_axis));
  EXPECT_EQ(s.material.density_kg_m2, sim::material_preset("wool_kang_yu").material.density_kg_m2);
  const sim::Vec3 centre = s.grid.origin + 0.15 * s.grid.warp_axis + 0.15 * s.grid.weft_axis;
  bool support = false;
  for (const sim::Obstacle& o : s.sim.obstacles) {
    if (const auto* c = std::get_if<sim::CylinderObstacle>(&o)) {
      support = true;
      EXPECT_NEAR(c->radius_m, 0.09, 1e-12);
      EXPECT_NEAR(c->center_m.x(), centre.x(), 1e-12);
      EXPECT_NEAR(c->center_m.y(), centre.y(), 1e-12);
      EXPECT_GT(centre.z(), c->center_m.z() + 0.5 * c->height_m);  // starts above its top
    }
  }
  EXPECT_TRUE(support);
}

}  // namespace
}  // namespace weft::app
