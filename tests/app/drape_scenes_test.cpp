// The classic drape scenes of assets/scenes (seed 002, Zhou & Sze, sections 4.4, 4.6
// and 6.2), simulated and measured as `weft measure` does (app/run/measure.h), against the
// paper's numbers:
// - 50 × 50 cm on a Ø20 cm disc: 8–12 folds (12 by static equilibrium, Fig. 10; 8 by dynamic
//   relaxation, Fig. 15);
// - the two-corner hangs with mass damping 5 s⁻¹ have basically stopped moving by 2.0 s
//   (20 cm, Fig. 12) and 2.4 s (100 cm, Fig. 13); weft's settle time (max speed < 1 cm/s)
//   within 30 % of those.
// To keep the set near 25 s of CPU time two scenes run coarser than their files: the disc drape
// on 41 × 41 vertices instead of 61 × 61 and for 1.5 s instead of 2.5 s (measured: 10 folds
// either way, and from about 1 s on), the 20 cm hang on 31 × 31 instead of 41 × 41 (settle
// time 2.12 s on both). The 100 cm hang runs as its file says.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/run/measure.h"
#include "app/scene/scene.h"
#include "coarse_scene.h"

namespace weft::app {
namespace {

SceneMeasurement measure(const Scene& scene) {
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  return measure_scene(scene, *simulator, false);
}

TEST(DrapeScenes, FiftyCentimetreSquareOnATwentyCentimetreDiscHasEightToTwelveFolds) {
  Scene scene = test::coarse_scene("disc_drape_50.json", 41);
  scene.frames = 36;  // 1.5 s at 24 fps
  const SceneMeasurement m = measure(scene);
  ASSERT_TRUE(m.support);
  EXPECT_EQ(m.support->kind, "cylinder");
  ASSERT_TRUE(m.final_drape);
  EXPECT_GE(m.final_drape->folds, 8);
  EXPECT_LE(m.final_drape->folds, 12);
  // The overhang hangs: well below the flat sheet's DC of 1, and it cannot be below 0.
  EXPECT_GT(m.final_drape->drape_coefficient, 0.0);
  EXPECT_LT(m.final_drape->drape_coefficient, 0.5);
  EXPECT_NEAR(m.rows.front().drape_coefficient.value(), 1.0, 0.01);  // flat at t = 0
  EXPECT_EQ(m.self_intersections, 0);
  std::printf("disc drape 50 cm on 20 cm (41 x 41): %d folds, DC %.3f\n", m.final_drape->folds,
              m.final_drape->drape_coefficient);
}

// The disc drape as shipped, to rest (weft measure --until-settled 10): the cloth must not pass
// through itself. Without self-collision its skirt's folds crossed (46 at 2.5 s and 48 at rest
// on one build, none after moving the start up 1 µm: which folds cross is the last bits of a
// chaotic motion, so the count at rest followed any change of rounding); with it, none.
// 125 frames at 61² with self-collision: minutes, hence slow (label app-slow).
TEST(DrapeScenes, FiftyCentimetreSquareRestsOnTheDiscWithoutCrossingItself) {
  Scene scene = test::scene_file("disc_drape_50.json");
  ASSERT_TRUE(scene.sim.self_collision.enabled);
  scene.frames = static_cast<int>(std::lround(10.0 * scene.fps));  // --until-settled 10
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  const SceneMeasurement m = measure_scene(scene, *simulator, true, {}, true);
  ASSERT_TRUE(m.settle_time_s) << "still moving after 10 s";
  ASSERT_TRUE(m.final_drape);
  EXPECT_EQ(m.self_intersections, 0);
  EXPECT_GE(m.final_drape->folds, 8);
  EXPECT_LE(m.final_drape->folds, 12);
  std::printf("disc drape 50 cm at rest: settled at %.2f s, %d folds, DC %.3f, %d crossings\n",
              *m.settle_time_s, m.final_drape->folds, m.final_drape->drape_coefficient,
              m.self_intersections);
}

void expect_settles_near(const Scene& scene, double paper_s) {
  const SceneMeasurement m = measure(scene);
  EXPECT_FALSE(m.support);  // a hang: nothing under the cloth
  ASSERT_TRUE(m.settle_time_s) << scene.source << " still moves at the end";
  EXPECT_NEAR(*m.settle_time_s, paper_s, 0.3 * paper_s) << scene.source;
  std::printf("%s: settles at %.2f s (paper %.1f s)\n", scene.source.c_str(), *m.settle_time_s,
              paper_s);
}

TEST(DrapeScenes, TwentyCentimetreHangSettlesByAboutTwoSeconds) {
  Scene scene = test::coarse_scene("hang_corners_20.json", 31);
  expect_settles_near(scene, 2.0);
}

TEST(DrapeScenes, MetreHangSettlesByAboutTwoPointFourSeconds) {
  expect_settles_near(test::scene_file("hang_corners_100.json"), 2.4);
}

}  // namespace
}  // namespace weft::app
