// Contact invariants on every drape scene of assets/scenes: with
// self-collision on, after every step no free vertex is closer to any obstacle than the
// collision thickness (so none is inside one), and the final frame has no edge–triangle
// crossing. To keep the set within seconds each scene runs coarse (17 × 17 vertices) for its
// first 0.75 s — the fall, the impact and the folds forming, where contact is hardest; the
// full-resolution runs are the gallery's (gallery/README.md).
//
// Then every drape scene as shipped, at full resolution to its last frame, where each has
// come (nearly) to rest: no edge–triangle crossing. Without self-collision six of them ended
// with 62–602 crossings (their folds passing through each other, drawn as slits in the cloth);
// which folds cross follows the last bits of a chaotic motion, so a scene at 0 without it
// could cross after any change of rounding — hence the full runs, not a coarse stand-in.

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "app/scene/scene.h"
#include "coarse_scene.h"
#include "sim/collision/self_intersection.h"

namespace weft::app {
namespace {

Scene coarse_scene_with_self_collision(const std::string& name) {
  Scene scene = test::coarse_scene(name, 17);
  scene.sim.self_collision.enabled = true;
  return scene;
}

// A scene file's name without its extension, as the test's name.
std::string scene_test_name(const ::testing::TestParamInfo<std::string>& info) {
  return info.param.substr(0, info.param.find('.'));
}

class DrapeSceneContact : public ::testing::TestWithParam<std::string> {};

TEST_P(DrapeSceneContact, NoVertexInsideAnObstacleAfterAnyStepAndNoCrossingAtTheEnd) {
  const Scene scene = coarse_scene_with_self_collision(GetParam());
  const std::unique_ptr<sim::Simulator> sim = make_simulator(scene);
  const double thickness = scene.sim.collision_thickness_m;
  const double h = sim->time_step();
  const long steps = static_cast<long>(0.75 / h);
  double closest = 1e300;
  for (long k = 0; k < steps; ++k) {
    sim->step(h);
    const sim::Matrix3X& x = sim->state().x;
    for (sim::Index i = 0; i < x.rows(); ++i) {
      if (!sim->mesh().is_used(i)) continue;
      bool pinned = false;
      for (const sim::Index p : sim->pinned()) pinned |= p == i;
      if (pinned) continue;
      for (std::size_t o = 0; o < scene.sim.obstacles.size(); ++o) {
        const double d = sim::signed_distance(scene.sim.obstacles[o], x.row(i).transpose());
        closest = std::min(closest, d);
        ASSERT_GE(d, thickness - 1e-9) << GetParam() << ": vertex " << i << " at step " << k
                                       << " is " << d << " m from obstacle " << o;
      }
    }
  }
  const auto triangles = sim->mesh().triangles();
  const sim::Index crossings = sim::count_edge_triangle_crossings(
      sim->state().x, triangles, sim::unique_edges(triangles));
  EXPECT_EQ(crossings, 0) << GetParam();
  std::printf("%s (17 x 17, %ld steps): %d crossings", GetParam().c_str(), steps, crossings);
  if (!scene.sim.obstacles.empty()) std::printf(", closest approach to an obstacle %.3g mm", 1e3 * closest);
  std::printf("\n");
}

INSTANTIATE_TEST_SUITE_P(Scenes, DrapeSceneContact,
                         ::testing::Values("pedestal_drape.json", "kang_yu_40_pedestal.json",
                                           "disc_drape_50.json", "sphere_drape_30.json",
                                           "cusick_drape.json", "sphere_drape_mesh.json",
                                           "hang_corners_20.json", "hang_corners_100.json"),
                         scene_test_name);

class DrapeSceneAtRest : public ::testing::TestWithParam<std::string> {};

TEST_P(DrapeSceneAtRest, EndsWithoutCrossingItself) {
  const Scene scene = test::scene_file(GetParam());
  const std::unique_ptr<sim::Simulator> sim = make_simulator(scene);
  for (int frame = 0; frame < scene.frames; ++frame) sim->advance(1.0 / scene.fps);
  const auto triangles = sim->mesh().triangles();
  const sim::Index crossings = sim::count_edge_triangle_crossings(
      sim->state().x, triangles, sim::unique_edges(triangles));
  EXPECT_EQ(crossings, 0) << GetParam();
  const sim::Diagnostics d = sim->diagnostics();
  std::printf("%s at %.2f s: %d crossings, kinetic energy %.3g J, fastest vertex %.3g m/s\n",
              GetParam().c_str(), d.time_s, crossings, d.kinetic_energy_J, d.max_speed_m_s);
}

// disc_drape_50.json has its own test to rest (drape_scenes_test.cpp).
INSTANTIATE_TEST_SUITE_P(Scenes, DrapeSceneAtRest,
                         ::testing::Values("cusick_drape.json", "cusick_drape_round.json",
                                           "disc_drape_50_remeshed.json",
                                           "disc_drape_50_uniform.json", "drape_static_dr.json",
                                           "kang_yu_40_pedestal.json", "napkin_mesh_drape.json",
                                           "pedestal_drape.json", "sphere_drape.json",
                                           "sphere_drape_20_remeshed.json", "sphere_drape_30.json",
                                           "sphere_drape_inextensible.json",
                                           "sphere_drape_mesh.json"),
                         scene_test_name);

}  // namespace
}  // namespace weft::app
