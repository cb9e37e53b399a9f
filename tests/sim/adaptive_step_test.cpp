// The adaptive time step of inextensible cloth (sim/adaptive_step.h): the controller's rule, and
// what it does to the two-corner hang — steps that land on the frames, every projection
// converged, fewer steps than the fixed 1/120 s once the sheet swings, the same bits again and
// after a checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/check.h"
#include "sim/adaptive_step.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::sim {
namespace {

AdaptiveStepSettings settings(double min_s, double max_s, double strain) {
  AdaptiveStepSettings a;
  a.min_step_s = min_s;
  a.max_step_s = max_s;
  a.max_prediction_strain = strain;
  return a;
}

TEST(AdaptiveStep, TheStepFollowsTheProjectionsIterations) {
  AdaptiveStep step(settings(1e-4, 0.04, 0.25));
  EXPECT_EQ(step.planned_step_s(), 0.04);  // the first step is the longest
  step.accept(0.01, 1, true);
  EXPECT_DOUBLE_EQ(step.planned_step_s(), 0.0125);  // one iteration or none: longer
  step.accept(0.01, 0, true);
  EXPECT_DOUBLE_EQ(step.planned_step_s(), 0.0125);
  step.accept(0.01, 2, true);
  EXPECT_DOUBLE_EQ(step.planned_step_s(), 0.01);  // two: the same
  step.accept(0.01, 5, true);
  EXPECT_DOUBLE_EQ(step.planned_step_s(), 0.007);  // three or more: shorter
  step.accept(0.01, 1, false);
  EXPECT_DOUBLE_EQ(step.planned_step_s(), 0.005);  // missed the tolerance: half
  step.accept(0.039, 0, true);
  EXPECT_EQ(step.planned_step_s(), 0.04);  // within [min, max]
  step.accept(1.1e-4, 9, true);
  EXPECT_EQ(step.planned_step_s(), 1e-4);
}

// Strain grows as h², so a prediction strained ε > ε_max at h is redone at h √(0.9 ε_max/ε).
TEST(AdaptiveStep, APredictionStrainedBeyondTheLimitIsRedoneShorter) {
  AdaptiveStep step(settings(1e-4, 0.04, 0.25));
  EXPECT_FALSE(step.reject(0.04, 0.25));
  EXPECT_EQ(step.planned_step_s(), 0.04);  // not rejected: the plan is accept()'s
  EXPECT_TRUE(step.reject(0.04, 0.25 * 0.9 * 16.0));
  EXPECT_NEAR(step.planned_step_s(), 0.01, 1e-15);
  // At the shortest step nothing is rejected: it is taken, whatever it costs.
  EXPECT_FALSE(step.reject(1e-4, 10.0));
  EXPECT_TRUE(step.reject(2e-4, 1e6));
  EXPECT_EQ(step.planned_step_s(), 1e-4);
}

TEST(AdaptiveStep, TheRemainingTimeIsSplitIntoEqualStepsNoLongerThanPlanned) {
  AdaptiveStep step(settings(1e-4, 0.01, 0.25));
  EXPECT_DOUBLE_EQ(step.next_step(0.04), 0.01);
  EXPECT_DOUBLE_EQ(step.next_step(0.041), 0.041 / 5.0);
  EXPECT_DOUBLE_EQ(step.next_step(0.004), 0.004);
  EXPECT_EQ(step.next_step(0.0), 0.0);
}

TEST(AdaptiveStep, BadSettingsNameTheSetting) {
  const auto message = [](const AdaptiveStepSettings& a) {
    try {
      AdaptiveStep step(a);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(settings(0.0, 0.01, 0.05)).find("min_step"), std::string::npos);
  EXPECT_NE(message(settings(0.02, 0.01, 0.05)).find("max_step"), std::string::npos);
  EXPECT_NE(message(settings(1e-3, 0.01, std::nan(""))).find("max_prediction_strain"), std::string::npos);
}

SimSettings hang_settings(bool adaptive, double max_prediction_strain = 0.25) {
  SimSettings s;
  s.integrator = Integrator::implicit_euler;
  s.implicit_solve = ImplicitSolve::conjugate_gradient;
  s.implicit_cg_tolerance = 1e-3;
  s.air_damping_1_s = 1.0;
  s.projection.method = ProjectionMethod::fast_projection;
  s.projection.tolerance = 1e-3;
  s.time_step = adaptive ? adaptive_time_step() : fixed_time_step(1.0 / 120.0);
  s.time_step.adaptive.max_prediction_strain = max_prediction_strain;
  return s;
}

ClothMesh hang_mesh(Index n) {
  GridSpec grid;
  grid.nu = grid.nv = n;
  grid.origin = Vec3(-0.5, 0.0, 1.6);
  return make_grid(grid);
}

struct HangRun {
  long steps = 0, rejected = 0, unconverged = 0;
  double min_step_s = 1e9, max_step_s = 0.0, worst_strain = 0.0;
  Matrix3X x;
};

// The 1 m wool sheet hanging from two corners, `frames` frames at 24 fps.
HangRun hang(Index n, int frames, bool adaptive, double max_prediction_strain = 0.25) {
  const ClothMesh mesh = hang_mesh(n);
  Simulator sim(mesh, Material{}, resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh),
                hang_settings(adaptive, max_prediction_strain));
  HangRun run;
  for (int frame = 1; frame <= frames; ++frame) {
    sim.advance(frame / 24.0 - sim.state().time_s);
    EXPECT_EQ(sim.state().time_s, frame / 24.0) << "frame " << frame;
    const StepStatistics st = sim.take_step_statistics();
    run.steps += st.steps;
    run.rejected += st.rejected_steps;
    run.unconverged += st.unconverged_steps;
    run.min_step_s = std::min(run.min_step_s, st.min_step_s);
    run.max_step_s = std::max(run.max_step_s, st.max_step_s);
    run.worst_strain = std::max(run.worst_strain, st.worst_projected_strain);
  }
  run.x = sim.state().x;
  return run;
}

// From the flat start the first step of 1/24 s drops the free row below the held top edge by
// g h² while the top edge stays: the edges between them (l = 1/23 m) stretch to
// √(1 + (g h²/l)²) − 1 = 7.3 %, beyond the limit of 5 % set here, so that step is redone
// shorter. Later the steps grow past 1/120 s, every projection still meets its tolerance, and
// the run takes fewer steps than the fixed step.
TEST(AdaptiveStep, TheHangTakesFewerStepsThanTheFixedStepAndEveryOneConverges) {
  const int frames = 24;
  const HangRun fixed = hang(24, frames, false);
  const double h = 1.0 / 24.0, l = 1.0 / 23.0, drop = 9.81 * h * h;
  ASSERT_GT(std::sqrt(1.0 + drop * drop / (l * l)) - 1.0, 0.05);
  const HangRun adaptive = hang(24, frames, true, 0.05);
  EXPECT_EQ(fixed.steps, 5 * frames);
  EXPECT_GE(adaptive.rejected, 1);
  EXPECT_EQ(adaptive.unconverged, 0);
  EXPECT_LE(adaptive.worst_strain, 1e-3);
  EXPECT_LT(adaptive.min_step_s, 1.0 / 120.0);
  EXPECT_GT(adaptive.max_step_s, 1.0 / 120.0);
  EXPECT_LT(adaptive.steps, fixed.steps);
  std::printf("24² hang, %d frames: %ld fixed steps, %ld adaptive (%ld rejected), %.3g–%.3g s\n",
              frames, fixed.steps, adaptive.steps, adaptive.rejected, adaptive.min_step_s,
              adaptive.max_step_s);
}

TEST(AdaptiveStep, SameBitsTwiceAndAfterACheckpoint) {
  const ClothMesh mesh = hang_mesh(12);
  const std::vector<Index> pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  Simulator whole(mesh, Material{}, pins, hang_settings(true));
  Simulator first(mesh, Material{}, pins, hang_settings(true));
  StateWriter saved;
  for (int frame = 1; frame <= 12; ++frame) {
    whole.advance(1.0 / 24.0);
    if (frame <= 6) first.advance(1.0 / 24.0);
    if (frame == 6) first.save_state(saved);
  }
  Simulator resumed(mesh, Material{}, pins, hang_settings(true));
  StateReader in(saved.bytes(), "checkpoint");
  resumed.restore_state(in);
  for (int frame = 7; frame <= 12; ++frame) resumed.advance(1.0 / 24.0);
  EXPECT_TRUE(resumed.state().x == whole.state().x);
  EXPECT_TRUE(resumed.state().v == whole.state().v);
  EXPECT_EQ(resumed.steps_taken(), whole.steps_taken());
  EXPECT_EQ(hang(12, 6, true).x, hang(12, 6, true).x);
}

// The scene reader refuses such a scene naming simulation.time_step (tests/app/
// solver_scene_test.cpp); settings that reach the simulator anyway are a bug in their maker.
TEST(AdaptiveStep, WithoutFastProjectionItIsABug) {
  const ClothMesh mesh = hang_mesh(6);
  SimSettings s = hang_settings(true);
  s.projection.method = ProjectionMethod::none;
  EXPECT_THROW(Simulator(mesh, Material{}, {}, s), base::InternalError);
  s = hang_settings(true);
  s.integrator = Integrator::symplectic_euler;
  try {
    Simulator sim(mesh, Material{}, {}, s);
    ADD_FAILURE() << "accepted";
  } catch (const base::InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("fast projection"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace weft::sim
