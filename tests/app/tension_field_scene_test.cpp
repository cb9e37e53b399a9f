// The tension-field shape as a scene's initial shape (app/scene/tension_field_scene.h): the cloth
// starts laid on Conci's folds — supports l = L − d apart, n + 1 bulges down its centre, every
// vertical fibre its rest length —, pins hold it there, simulation.dynamics false keeps it,
// and bad scenes name the key at fault.

#include <gtest/gtest.h>

#include <cmath>

#include "app/run/measure.h"
#include "app/scene/scene.h"
#include "analysis/measure/curtain_folds.h"
#include "tests/app/coarse_scene.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

Json curtain_json() {
  Scene scene = test::scene_file("curtain_tension_field.json");
  return Json::parse(scene.text);
}

Scene curtain(sim::Index n) {
  Json j = curtain_json();
  j["cloth"]["resolution"] = {n, n};
  return test::parse_json_scene(j);
}

TEST(TensionFieldScene, StartsOnTheFoldsWithTheSupportsASpanApart) {
  const Scene scene = curtain(57);
  ASSERT_TRUE(scene.tension_field);
  EXPECT_FALSE(scene.dynamics);
  const auto simulator = make_simulator(scene);
  const sim::ClothMesh& mesh = simulator->mesh();
  const sim::Matrix3X& x = simulator->state().x;
  // Table 1 row 2 with Q = 1.29: n = 7, span l = 140 − 10 cm.
  const sim::TensionFieldResult r = sim::solve_tension_field(tension_field_inputs(
      *scene.tension_field, scene.grid, scene.material, scene.sim.gravity_m_s2));
  EXPECT_EQ(r.wrinkles, 7);
  const double span =
      (x.row(mesh.index(mesh.nu - 1, 0)) - x.row(mesh.index(0, 0))).norm();
  EXPECT_NEAR(span, 1.30, 1e-9);
  EXPECT_EQ(analysis::count_curtain_folds(mesh, x).folds, r.wrinkles + 1);
  // Vertical fibres keep their length (chords of the folded fibre: within 1 %).
  for (sim::Index i = 0; i < mesh.nu; i += 7) {
    double length = 0.0;
    for (sim::Index j = 1; j < mesh.nv; ++j)
      length += (x.row(mesh.index(i, j)) - x.row(mesh.index(i, j - 1))).norm();
    EXPECT_NEAR(length, 1.40, 0.014) << "column " << i;
  }
}

TEST(TensionFieldScene, PinsHoldTheSupportsWhereTheShapePutThem) {
  Json j = curtain_json();
  j["cloth"]["resolution"] = {15, 15};
  j["simulation"] = {{"dynamics", true}, {"model", "mass_spring"},
                     {"integrator", "implicit_euler"}, {"time_step", "5 ms"}};
  const Scene scene = test::parse_json_scene(j);
  const auto simulator = make_simulator(scene);
  const sim::Matrix3X start = simulator->state().x;
  simulator->advance(0.1);
  const sim::ClothMesh& mesh = simulator->mesh();
  for (const sim::Index v : {mesh.index(0, 0), mesh.index(mesh.nu - 1, 0)})
    EXPECT_EQ((simulator->state().x.row(v) - start.row(v)).norm(), 0.0);
  EXPECT_GT((simulator->state().x - start).norm(), 0.0) << "the free cloth moves";
}

TEST(TensionFieldScene, WithoutDynamicsEveryFrameIsTheInitialShape) {
  Scene scene = curtain(15);
  scene.frames = 3;
  const auto simulator = make_simulator(scene);
  const sim::Matrix3X start = simulator->state().x;
  const SceneMeasurement m = measure_scene(scene, *simulator, false);
  EXPECT_EQ(simulator->state().x, start);
  ASSERT_EQ(m.rows.size(), 4u);
  EXPECT_NEAR(m.rows.back().time_s, 3.0 / scene.fps, 1e-12);
  ASSERT_TRUE(m.curtain);
  EXPECT_EQ(m.curtain->folds, 8);
}

TEST(TensionFieldScene, BadScenesNameTheKey) {
  Json j = curtain_json();
  j["cloth"]["weft_axis"] = {0, 1, 0};
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.weft_axis: the tension-field shape hangs the cloth");
  j = curtain_json();
  j["cloth"]["initial_shape"]["tension_field"]["support_shift"] = "150 cm";
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.initial_shape.tension_field.support_shift: ");
  j = curtain_json();
  j["cloth"]["initial_shape"]["tension_field"]["youngs_modulus"] = "165 N/m";
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.initial_shape.tension_field.youngs_modulus: expected a stress");
  j = curtain_json();
  j["cloth"]["initial_shape"]["tension_field"]["ratio"] = 0.9;
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.initial_shape.tension_field.ratio");
  j = curtain_json();
  j["cloth"]["initial_shape"] = {{"tension_feld", Json::object()}};
  EXPECT_CONTAINS(test::scene_error_of(j), "is 'tension_feld' a misspelling?");
  j = curtain_json();
  j["cloth"]["shape"] = "disc";
  j["cloth"]["pins"] = Json::array();  // the corners are cut away
  EXPECT_CONTAINS(test::scene_error_of(j), "cloth.shape: the tension-field shape needs a rectangle");
}

}  // namespace
}  // namespace weft::app
