// Simulator::save_state / restore_state: a simulator restored from the state
// of another one after some steps goes on with the same bits — for the integrators, projections
// and contact settings that weft run's checkpoint tests (tests/app/checkpoint_cli_test.cpp)
// do not reach through a scene: dynamic relaxation, RK4, velocity Verlet, implicit Euler by a
// direct solver with fast projection reusing its factorization (reuse_iterations; the CLI
// tests reach it with CG), pairwise projection, self-collision without projection.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "sim/pins.h"
#include "sim/simulator.h"
#include "tests/sim/test_cloth.h"

namespace weft::sim {
namespace {

struct Case {
  std::string name;
  SimSettings settings;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::vector<Case> cases() {
  std::vector<Case> out;
  SimSettings base;
  base.air_damping_1_s = 0.5;
  base.obstacles = {SphereObstacle{Vec3(0.5, 0.5, 1.7), 0.15}};
  auto add = [&](std::string name, auto change) {
    SimSettings s = base;
    change(s);
    out.push_back({std::move(name), s});
  };
  add("dynamic_relaxation", [](SimSettings& s) { s.integrator = Integrator::dynamic_relaxation; });
  add("rk4", [](SimSettings& s) { s.integrator = Integrator::rk4; });
  add("velocity_verlet", [](SimSettings& s) { s.integrator = Integrator::velocity_verlet; });
  add("implicit_direct_fast_projection_reuse", [](SimSettings& s) {
    s.integrator = Integrator::implicit_euler;
    s.time_step = fixed_time_step(1.0 / 240.0);
    s.projection.method = ProjectionMethod::fast_projection;
    s.projection.reuse_iterations = 8;
  });
  add("pairwise_projection", [](SimSettings& s) {
    s.projection.method = ProjectionMethod::pairwise;
    s.projection.max_iterations = 4;
  });
  add("self_collision", [](SimSettings& s) {
    s.integrator = Integrator::implicit_euler;
    s.implicit_solve = ImplicitSolve::conjugate_gradient;
    s.time_step = fixed_time_step(1.0 / 240.0);
    s.self_collision.enabled = true;
    s.self_collision.thickness_m = 0.02;
  });
  return out;
}

class SimulatorState : public ::testing::TestWithParam<Case> {};

Simulator make(const SimSettings& s) {
  const ClothMesh mesh = test_cloth::square(13);
  return Simulator(mesh, test_cloth::fabric(200.0), resolve_pins({PinCorner{"u0v0"}}, mesh), s);
}

TEST_P(SimulatorState, ARestoredSimulatorGoesOnWithTheSameBits) {
  const SimSettings& s = GetParam().settings;
  Simulator first = make(s);
  for (int frame = 0; frame < 8; ++frame) first.advance(1.0 / 24.0);
  StateWriter saved;
  first.save_state(saved);
  Simulator second = make(s);
  StateReader reader(saved.bytes(), "test");
  second.restore_state(reader);
  EXPECT_TRUE(reader.at_end());
  for (int frame = 0; frame < 8; ++frame) {
    first.advance(1.0 / 24.0);
    second.advance(1.0 / 24.0);
  }
  EXPECT_EQ(first.steps_taken(), second.steps_taken());
  EXPECT_EQ(first.state().time_s, second.state().time_s);
  EXPECT_TRUE(first.state().x == second.state().x) << "positions differ";
  EXPECT_TRUE(first.state().v == second.state().v) << "velocities differ";
  const StepStatistics a = first.take_step_statistics(), b = second.take_step_statistics();
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.projection_iterations, b.projection_iterations);
  EXPECT_EQ(a.projection_factorizations, b.projection_factorizations);
  EXPECT_EQ(a.projection_reuse_iterations, b.projection_reuse_iterations);
  EXPECT_EQ(a.cg_iterations, b.cg_iterations);
  EXPECT_EQ(a.max_self_contacts, b.max_self_contacts);
  if (first.self_collision()) {
    EXPECT_GT(a.max_self_contacts, 0) << "the case should bring the cloth into self-contact";
    EXPECT_EQ(first.self_collision()->rebuilds(), second.self_collision()->rebuilds());
    EXPECT_EQ(first.self_collision()->candidate_count(), second.self_collision()->candidate_count());
  }
  if (first.relaxation()) {
    EXPECT_EQ(first.relaxation()->status().kinetic_peaks, second.relaxation()->status().kinetic_peaks);
  }
  if (s.projection.method == ProjectionMethod::fast_projection && s.projection.reuse_iterations > 0) {
    EXPECT_GT(a.projection_reuse_iterations, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Settings, SimulatorState, ::testing::ValuesIn(cases()),
                         [](const auto& test) { return test.param.name; });

TEST(SimulatorStateErrors, AStateOfAnotherSimulationIsRefusedNamingTheSection) {
  SimSettings s;
  Simulator small = make(s);
  small.advance(0.01);
  StateWriter saved;
  small.save_state(saved);
  const ClothMesh mesh = test_cloth::square(9);
  Simulator other(mesh, test_cloth::fabric(200.0), resolve_pins({PinCorner{"u0v0"}}, mesh), s);
  StateReader reader(saved.bytes(), "state.bin");
  try {
    other.restore_state(reader);
    FAIL() << "restored a 13x13 state into a 9x9 cloth";
  } catch (const StateArchiveError& e) {
    EXPECT_NE(std::string(e.what()).find("state.bin: section 'simulator': a 169×3 matrix"),
              std::string::npos) << e.what();
  }
  StateWriter implicit_state;
  s.integrator = Integrator::implicit_euler;
  make(s).save_state(implicit_state);
  StateReader implicit_reader(implicit_state.bytes(), "implicit.bin");
  EXPECT_THROW(small.restore_state(implicit_reader), StateArchiveError);
}

}  // namespace
}  // namespace weft::sim
