// The self-collision drape at 32²: a 1 m sheet dropped from 30 cm above a Ø50 cm sphere on the
// ground (assets/scenes/sphere_drape_inextensible.json's set-up with a fixed step: implicit
// Euler, h = 1/120 s, fast projection to 1e-3, friction 0.5) with self-collision on
// (neighbourhood 0). Without the impact zones (sim/collision/impact_zones.h) it passes through
// itself from frame 10; with them no frame has a crossing, and the warp/weft strain stays
// bounded.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "sim/collision/self_intersection.h"
#include "sim/simulator.h"

namespace weft::sim {
namespace {

struct ZoneDrapeRun {
  std::vector<Index> crossings;  // per frame
  double worst_strain = 0.0;     // the largest warp/weft strain at the end of a frame
  long unresolved_steps = 0;     // steps whose impact zones hit their pass limit
  long most_zone_vertices = 0;
  int frames_beyond_tolerance = 0;  // frames ending with a strain above the projection's 1e-3
  int unreported_frames = 0;        // … whose steps were all counted as converged
  Matrix3X x;
};

// The sphere on the ground, friction 0.5, self-collision on with `threads` threads.
SimSettings sphere_drop_settings(int threads) {
  SimSettings s;
  s.obstacles = {SphereObstacle{Vec3(0.0, 0.0, 0.6), 0.25},
                 PlaneObstacle{Vec3::Zero(), Vec3::UnitZ()}};
  s.collision_friction = 0.5;
  s.self_collision.enabled = true;
  s.self_collision.threads = threads;
  s.solver_threads = threads;
  return s;
}

ZoneDrapeRun drop_drape_with_zones(Index n, int frames, int threads, bool impact_zones,
                                   double neighbourhood_edges = 0.0) {
  SimSettings s = sphere_drop_settings(threads);
  s.integrator = Integrator::implicit_euler;
  s.time_step = fixed_time_step(1.0 / 120.0);
  s.air_damping_1_s = 2.0;
  s.projection.method = ProjectionMethod::fast_projection;
  s.projection.tolerance = 1e-3;
  s.implicit_solve = ImplicitSolve::conjugate_gradient;
  s.implicit_cg_tolerance = 1e-3;
  s.self_collision.neighbourhood_edges = neighbourhood_edges;
  s.self_collision.impact_zones = impact_zones;
  GridSpec grid;
  grid.nu = grid.nv = n;
  grid.origin = Vec3(-0.5, -0.5, 1.15);
  Simulator sim(make_grid(grid), Material{}, {}, s);
  const auto triangles = sim.mesh().triangles();
  const auto edges = unique_edges(triangles);
  ZoneDrapeRun run;
  for (int frame = 1; frame <= frames; ++frame) {
    sim.advance(1.0 / 24.0);
    const StepStatistics st = sim.take_step_statistics();
    run.unresolved_steps += st.unresolved_impact_steps;
    run.most_zone_vertices = std::max(run.most_zone_vertices, st.max_impact_zone_vertices);
    const double strain = sim.diagnostics().max_strain;
    run.worst_strain = std::max(run.worst_strain, strain);
    if (strain > s.projection.tolerance) {
      ++run.frames_beyond_tolerance;
      if (st.unconverged_steps == 0) ++run.unreported_frames;
    }
    run.crossings.push_back(count_edge_triangle_crossings(sim.state().x, triangles, edges));
    if (std::getenv("WEFT_TEST_VERBOSE"))
      std::printf("frame %d: %ld steps, %ld unconverged, strain %.2e, %ld self contacts, %ld zone "
                  "vertices, %d crossings\n",
                  frame, st.steps, st.unconverged_steps, strain, st.max_self_contacts,
                  st.max_impact_zone_vertices, static_cast<int>(run.crossings.back()));
  }
  run.x = sim.state().x;
  return run;
}

TEST(ImpactZoneDrape, InextensibleDrapeNeverPassesThroughItself) {
  const ZoneDrapeRun run = drop_drape_with_zones(32, 24, 2, true);
  for (std::size_t f = 0; f < run.crossings.size(); ++f)
    EXPECT_EQ(run.crossings[f], 0) << "frame " << f + 1;
  EXPECT_EQ(run.unresolved_steps, 0);
  std::printf("32² inextensible drape with impact zones: worst strain %.2e, at most %ld zone "
              "vertices in a step\n",
              run.worst_strain, run.most_zone_vertices);
  EXPECT_LE(run.worst_strain, 0.05);
  EXPECT_EQ(run.unreported_frames, 0);
}

// With the default neighbourhood the zones form in sharper folds. Held projections could not
// keep the edges leaving them: 5 frames ended beyond the projection's tolerance (0.25 % at
// 32²), counted as unconverged. Now a zone takes in the free ends of the edges it leaves
// stretched (ImpactZones::absorb) and every frame ends within the tolerance; any frame beyond
// it must still be reported.
TEST(ImpactZoneDrape, ZonesTakeInTheEdgesTheyLeaveStretched) {
  const ZoneDrapeRun run = drop_drape_with_zones(32, 24, 2, true, 1.0);
  for (std::size_t f = 0; f < run.crossings.size(); ++f)
    EXPECT_EQ(run.crossings[f], 0) << "frame " << f + 1;
  EXPECT_GT(run.most_zone_vertices, 0);  // zones formed
  EXPECT_EQ(run.frames_beyond_tolerance, 0) << "worst strain " << run.worst_strain;
  EXPECT_EQ(run.unreported_frames, 0);
}

TEST(ImpactZoneDrape, SameBitsOnOneAndTwoThreads) {
  const ZoneDrapeRun one = drop_drape_with_zones(32, 12, 1, true);
  const ZoneDrapeRun two = drop_drape_with_zones(32, 12, 2, true);
  EXPECT_TRUE(one.x == two.x) << "largest difference " << (one.x - two.x).cwiseAbs().maxCoeff()
                              << " m";
}

// The drop of bench/self_collision_bench.cpp (a wool sheet 22 cm above a Ø50 cm sphere on the
// ground, friction 0.3, self-collision thickness 3 mm, fast projection to 1e-3): at 56² with
// block Jacobi, and at 64² with the line preconditioner, the held projections' rounds ran out
// in some steps with zones that had moved again after the last projection, and those steps
// ended with edges stretched up to 61 % and 85 %. Their stretched edges now join the zones,
// so every step ends within the tolerance; and no frame has a crossing.
TEST(ImpactZoneDrape, EveryStepEndsWithinTheToleranceAfterTheHeldRoundsRunOut) {
  SimSettings s;
  s.obstacles = {SphereObstacle{Vec3(0.0, 0.0, 0.25), 0.25},
                 PlaneObstacle{Vec3::Zero(), Vec3::UnitZ()}};
  s.collision_friction = 0.3;
  s.self_collision.enabled = true;
  s.self_collision.thickness_m = 3e-3;
  s.solver_threads = s.self_collision.threads = 2;
  s.integrator = Integrator::implicit_euler;
  s.implicit_solve = ImplicitSolve::conjugate_gradient;
  s.implicit_cg_tolerance = 1e-3;
  s.implicit_cg_preconditioner = CgPreconditioner::block_jacobi;
  s.projection.method = ProjectionMethod::fast_projection;
  GridSpec grid;
  grid.nu = grid.nv = 56;
  grid.origin = Vec3(-0.5, -0.5, 0.72);
  Simulator sim(make_grid(grid), Material{}, {}, s);
  const auto triangles = sim.mesh().triangles();
  const auto edges = unique_edges(triangles);
  long most_zone_vertices = 0;
  for (int frame = 1; frame <= 12; ++frame) {
    sim.advance(1.0 / 24.0);
    const StepStatistics st = sim.take_step_statistics();
    EXPECT_EQ(st.unconverged_steps, 0) << "frame " << frame;
    EXPECT_LE(st.worst_projected_strain, s.projection.tolerance) << "frame " << frame;
    EXPECT_EQ(count_edge_triangle_crossings(sim.state().x, triangles, edges), 0)
        << "frame " << frame;
    most_zone_vertices = std::max(most_zone_vertices, st.max_impact_zone_vertices);
  }
  EXPECT_GT(most_zone_vertices, 0);  // zones formed
  std::printf("56² drop: at most %ld zone vertices in a step\n", most_zone_vertices);
}

// Explicit steps far shorter than a frame run the failsafe once a window of steps
// (SelfCollisionSettings::failsafe_interval_s), not after every step: a 32² mass-spring sheet
// (symplectic Euler) dropped onto the sphere, 12 frames. Both ways no frame has a crossing,
// the windowed drop ends where the one checked every step does (its centre of mass within
// 5 mm, its fastest vertex as slow), with a fraction of the failsafe's runs, and with the same
// bits on one and two threads.
struct ExplicitDropRun {
  std::vector<Index> crossings;  // per frame
  long steps = 0, failsafe_runs = 0;
  double fastest_m_s = 0.0;  // at the end
  Matrix3X x;
};

// A 32² mass-spring sheet (symplectic Euler, the automatic step) 40 cm above the sphere.
std::unique_ptr<Simulator> explicit_drop(double interval_s, int threads) {
  SimSettings s = sphere_drop_settings(threads);
  s.self_collision.failsafe_interval_s = interval_s;
  GridSpec grid;
  grid.nu = grid.nv = 32;
  grid.origin = Vec3(-0.5, -0.5, 1.0);
  return std::make_unique<Simulator>(make_grid(grid), Material{}, std::vector<Index>{}, s);
}

ExplicitDropRun drop_explicitly(double interval_s, int threads) {
  const std::unique_ptr<Simulator> made = explicit_drop(interval_s, threads);
  Simulator& sim = *made;
  const auto triangles = sim.mesh().triangles();
  const auto edges = unique_edges(triangles);
  ExplicitDropRun run;
  for (int frame = 1; frame <= 12; ++frame) {
    sim.advance(1.0 / 24.0);
    run.steps += sim.take_step_statistics().steps;
    run.crossings.push_back(count_edge_triangle_crossings(sim.state().x, triangles, edges));
  }
  run.failsafe_runs = sim.impact_zones()->runs();
  run.fastest_m_s = sim.state().v.rowwise().norm().maxCoeff();
  run.x = sim.state().x;
  return run;
}

TEST(ImpactZoneDrape, ExplicitStepsRunTheFailsafeOnceAWindow) {
  const ExplicitDropRun every = drop_explicitly(0.0, 2);
  const ExplicitDropRun windowed = drop_explicitly(SelfCollisionSettings{}.failsafe_interval_s, 2);
  for (std::size_t f = 0; f < every.crossings.size(); ++f) {
    EXPECT_EQ(every.crossings[f], 0) << "frame " << f + 1;
    EXPECT_EQ(windowed.crossings[f], 0) << "frame " << f + 1;
  }
  EXPECT_EQ(every.failsafe_runs, every.steps);
  EXPECT_EQ(windowed.steps, every.steps);
  EXPECT_LE(windowed.failsafe_runs, every.steps / 3);  // 1/1000 s holds three steps here
  const Vec3 moved = (windowed.x.colwise().mean() - every.x.colwise().mean()).transpose();
  EXPECT_LT(moved.norm(), 5e-3);
  EXPECT_LT(windowed.fastest_m_s, 2.0 * every.fastest_m_s + 0.05);
  std::printf("32² mass-spring drop: %ld steps, failsafe %ld times (every step: %ld), centres "
              "of mass %.2e m apart, fastest vertex %.3f against %.3f m/s\n",
              every.steps, windowed.failsafe_runs, every.failsafe_runs, moved.norm(),
              windowed.fastest_m_s, every.fastest_m_s);
  const ExplicitDropRun one = drop_explicitly(SelfCollisionSettings{}.failsafe_interval_s, 1);
  EXPECT_TRUE(one.x == windowed.x);
}

// A zone's vertices leave a window with the zone's mean velocity over it, (x − x_window_start)
// / window, not the last step's jump to the rigid motion. With a window as long as a frame
// (failsafe_interval 1 s), the window starts with the frame: checked on every free zone vertex
// of the first frames of the 32² drop that end with zones.
TEST(ImpactZoneDrape, ZoneVerticesLeaveAWindowWithItsMeanVelocity) {
  const std::unique_ptr<Simulator> sim = explicit_drop(1.0, 1);
  const double frame_s = 1.0 / 24.0;
  long checked = 0;
  for (int frame = 1; frame <= 12 && checked < 50; ++frame) {
    const Matrix3X start = sim->state().x;
    sim->advance(frame_s);
    for (const Index v : sim->impact_zones()->zone_vertices()) {
      if (!(sim->system().inv_mass[v] > 0.0)) continue;
      const Vec3 mean = (sim->state().x.row(v) - start.row(v)).transpose() / frame_s;
      EXPECT_LT((Vec3(sim->state().v.row(v).transpose()) - mean).norm(), 1e-9 * (1.0 + mean.norm()))
          << "vertex " << v << " in frame " << frame;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0) << "no zone formed";
}

}  // namespace
}  // namespace weft::sim
