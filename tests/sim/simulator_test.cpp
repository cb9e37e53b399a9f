// Dynamics against analytic solutions and invariants.
#include "sim/simulator.h"

#include <gtest/gtest.h>

#include "tests/sim/test_cloth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>

#include "base/constants.h"
#include "sim/collision/obstacle.h"
#include "sim/pin_motion.h"
#include "sim/pins.h"

namespace weft::sim {
namespace {

using test_cloth::fabric;
using test_cloth::square;

double centre_of_mass_z(const Simulator& sim) {
  return sim.state().x.col(2).dot(sim.masses_kg()) / sim.masses_kg().sum();
}

// Symplectic Euler under constant g from rest: v_n = n h g, x_n = x0 + g h² n(n+1)/2, i.e.
// x0 + g t²/2 + g t h/2: exact to round-off, first order in h against the true x0 + g t²/2.
TEST(Simulator, FreeFallMatchesTheIntegratorsClosedFormAndConvergesAtFirstOrder) {
  const double t_end = 0.5;
  double previous_error = 0.0;
  for (double h : {4e-3, 2e-3, 1e-3}) {
    SimSettings settings;
    settings.air_damping_1_s = 0.0;
    settings.time_step = fixed_time_step(h);
    Simulator sim(square(9), fabric(500.0), {}, settings);
    sim.advance(t_end);
    const Vec3 g = settings.gravity_m_s2;
    const long n = std::lround(t_end / h);
    ASSERT_EQ(sim.steps_taken(), n);
    double error = 0.0;
    for (Index k = 0; k < sim.mesh().vertex_count(); ++k) {
      const Vec3 x0 = sim.mesh().rest_positions.row(k).transpose();
      const Vec3 x = sim.state().x.row(k).transpose();
      const Vec3 discrete = x0 + g * h * h * 0.5 * static_cast<double>(n * (n + 1));
      EXPECT_LT((x - discrete).norm(), 1e-9) << "vertex " << k << " h " << h;
      error = std::max(error, (x - (x0 + 0.5 * g * t_end * t_end)).norm());
    }
    EXPECT_NEAR(error, 0.5 * g.norm() * t_end * h, 1e-9);
    if (previous_error > 0.0) {
      EXPECT_NEAR(previous_error / error, 2.0, 1e-6);  // first order
    }
    previous_error = error;
  }
}

// A frame splits into the fewest equal steps no longer than the time step, where a step typed in
// decimals (1/48 s as 0.0208333 s) may be longer by up to substep_slack: 2 steps, not 3.
TEST(Simulator, AFrameSplitsIntoTheFewestStepsNoLongerThanTheStepTyped) {
  const auto substeps_of = [](double step_s) {
    SimSettings settings;
    settings.time_step = fixed_time_step(step_s);
    return Simulator(square(5), fabric(500.0), {}, settings).substeps(1.0 / 24.0);
  };
  EXPECT_EQ(substeps_of(1.0 / 48.0), 2);
  EXPECT_EQ(substeps_of(0.0208333), 2);     // 1.6e-6 short of 1/48 s
  EXPECT_EQ(substeps_of(0.0208333333), 2);  // 1.6e-9 short
  EXPECT_EQ(substeps_of(0.0083333), 5);
  EXPECT_EQ(substeps_of(0.02), 3);          // 4 % short: a third step
  EXPECT_EQ(substeps_of(0.02083), 3);       // 1.6e-4 short: beyond the slack
  EXPECT_EQ(substeps_of(0.001), 42);        // 41.7 steps of 1 ms
  EXPECT_EQ(substeps_of(1.0), 1);
}

TEST(Simulator, PinnedVerticesDoNotMoveAtAll) {
  const ClothMesh mesh = square(11);
  const auto pinned = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}, PinGrid{5, 10}}, mesh);
  Simulator sim(mesh, fabric(300.0), pinned, SimSettings{});
  sim.advance(0.5);
  for (Index p : pinned) {
    EXPECT_EQ(Vec3(sim.state().x.row(p)), Vec3(mesh.rest_positions.row(p)));
    EXPECT_EQ(Vec3(sim.state().v.row(p)), Vec3::Zero());
  }
  EXPECT_LT(sim.state().x.col(2).minCoeff(), 1.5);  // the rest has fallen
}

// A cloth started from given positions (e.g. tension-field folds): pins hold their vertices
// there, a moving pin's path is an offset from there, and bad positions or a late call are errors.
TEST(Simulator, InitialPositionsAreWherePinsHoldAndPathsStart) {
  const ClothMesh mesh = square(11);
  const auto pinned = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  Simulator sim(mesh, fabric(300.0), pinned, SimSettings{});
  Matrix3X start = mesh.rest_positions;
  start.col(1) *= 0.5;  // squeezed along weft
  start.col(2).array() += 0.25;
  sim.set_initial_positions(start);
  EXPECT_EQ(sim.state().x, start);
  const PinPath path({{0.0, Vec3::Zero()}, {0.5, Vec3(0.1, 0.0, 0.0)}});
  sim.set_pin_path({pinned.front()}, path);
  sim.advance(0.5);
  EXPECT_NEAR((Vec3(sim.state().x.row(pinned.front())) - (Vec3(start.row(pinned.front())) + Vec3(0.1, 0, 0))).norm(), 0.0, 1e-12);
  EXPECT_EQ(Vec3(sim.state().x.row(pinned.back())), Vec3(start.row(pinned.back())));
  EXPECT_THROW(sim.set_initial_positions(start), std::invalid_argument);  // after a step

  Simulator fresh(mesh, fabric(300.0), pinned, SimSettings{});
  EXPECT_THROW(fresh.set_initial_positions(start.topRows(5)), std::invalid_argument);
  Matrix3X bad = start;
  bad(7, 2) = std::nan("");
  try {
    fresh.set_initial_positions(bad);
    ADD_FAILURE() << "a NaN position was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 7"), std::string::npos) << e.what();
  }
}

// Without damping the swinging cloth exchanges kinetic, elastic and gravitational energy;
// symplectic Euler keeps the total bounded (no drift), within a few per cent of the swing.
TEST(Simulator, UndampedSwingKeepsItsTotalEnergy) {
  const ClothMesh mesh = square(13, 0.5);
  SimSettings settings;
  settings.air_damping_1_s = 0.0;
  Simulator sim(mesh, fabric(200.0), resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), settings);
  const double e0 = sim.diagnostics().total_energy_J();
  double peak_kinetic = 0.0, worst_drift = 0.0;
  for (int frame = 0; frame < 48; ++frame) {
    sim.advance(1.0 / 24.0);
    const Diagnostics d = sim.diagnostics();
    peak_kinetic = std::max(peak_kinetic, d.kinetic_energy_J);
    worst_drift = std::max(worst_drift, std::abs(d.total_energy_J() - e0));
  }
  ASSERT_GT(peak_kinetic, 0.05);  // it really swings (0.5 m × 0.5 m × 0.2 kg/m² drops ~0.25 m)
  EXPECT_LT(worst_drift / peak_kinetic, 0.05) << "drift " << worst_drift << " J";
}

TEST(Simulator, DampedHangingClothComesToRest) {
  const ClothMesh mesh = square(17, 0.5);
  SimSettings settings;
  settings.air_damping_1_s = 2.0;
  Simulator sim(mesh, fabric(300.0), resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), settings);
  double peak = 0.0;
  while (sim.state().time_s < 10.0 - 1e-9) {
    sim.advance(0.1);
    peak = std::max(peak, sim.diagnostics().kinetic_energy_J);
  }
  EXPECT_LT(sim.diagnostics().kinetic_energy_J, 1e-6 * peak);
}

// A 1 m cloth hanging from two adjacent corners settles to the same shape at 16², 32² and 64²:
// the drop of its centre of mass agrees within 5 % and converges. (The strain right at a
// point pin is singular in the continuum and grows with refinement; integral measures do not.)
// The static shape is reached by dynamic relaxation (sim/integrators/dynamic_relaxation.h),
// not by seconds of damped dynamics: the equilibrium does not depend on the path.
TEST(Simulator, TwoCornerSagIsResolutionIndependent) {
  std::vector<double> sag;
  for (Index n : {16, 32, 64}) {
    const ClothMesh mesh = square(n);
    SimSettings settings;
    settings.integrator = Integrator::dynamic_relaxation;
    Simulator sim(mesh, fabric(200.0), resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), settings);
    // ‖f + M g‖ / ‖M g‖ over the free vertices. Measured: from 1e-3 down to 1e-6 the sag moves
    // by less than 1e-5 m at every size (16², 32², 64²: 2.7k, 10k, 16k iterations to 1e-3).
    const double tolerance = 1e-3;
    while (sim.relaxation()->status().iterations < 200000) {
      sim.step(sim.time_step());
      if (sim.relaxation()->status().residual <= tolerance) break;
    }
    ASSERT_LE(sim.relaxation()->status().residual, tolerance) << n << "² has not settled";
    sag.push_back(2.0 - centre_of_mass_z(sim));
  }
  const double lo = *std::min_element(sag.begin(), sag.end());
  const double hi = *std::max_element(sag.begin(), sag.end());
  std::printf("two-corner sag of the centre of mass: 16² %.4f m, 32² %.4f m, 64² %.4f m\n", sag[0], sag[1], sag[2]);
  EXPECT_LT(hi / lo - 1.0, 0.05) << "sags " << sag[0] << ", " << sag[1] << ", " << sag[2] << " m";
  EXPECT_LT(std::abs(sag[2] - sag[1]), std::abs(sag[1] - sag[0]));
  EXPECT_GT(sag[0], 0.4);  // a 1 m sheet pinned along one edge's ends hangs ~0.5 m below
}

TEST(Simulator, AnExplodingRunStopsWithStepTimeAndQuantity) {
  const ClothMesh mesh = square(21);
  SimSettings settings;
  Simulator probe(mesh, fabric(1000.0), {}, settings);
  settings.time_step = fixed_time_step(3.0 * probe.critical_time_step());
  Simulator sim(mesh, fabric(1000.0), resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), settings);
  try {
    sim.advance(1.0);
    FAIL() << "a step three times the critical one should explode";
  } catch (const DivergenceError& e) {
    EXPECT_GT(e.step(), 0);
    EXPECT_GT(e.time_s(), 0.0);
    EXPECT_NE(std::string(e.what()).find("simulation diverged at step"), std::string::npos) << e.what();
    EXPECT_NE(e.quantity().find("vertex"), std::string::npos) << e.what();
  }
}

TEST(Simulator, StableJustBelowTheEstimatedCriticalStep) {
  const ClothMesh mesh = square(21);
  SimSettings settings;
  settings.time_step_safety = 0.95;
  Simulator sim(mesh, fabric(1000.0), resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh), settings);
  EXPECT_NO_THROW(sim.advance(1.0));
  EXPECT_LT(sim.diagnostics().max_strain, 0.2);
}

// A 30 cm square dropped from 1 cm onto a plane tilted by θ = 20°, parallel to it, free: how far
// its centre of mass has moved down the slope after `t_end` seconds with friction μ.
double slide_down_a_slope(double friction, double t_end) {
  const double theta = 20.0 * base::kPi / 180.0;
  const Vec3 normal(std::sin(theta), 0.0, std::cos(theta));
  const Vec3 downhill(std::cos(theta), 0.0, -std::sin(theta));
  GridSpec grid;
  grid.size_u_m = grid.size_v_m = 0.3;
  grid.nu = grid.nv = 13;
  grid.warp_axis = downhill;  // warp × weft = normal: the cloth lies parallel to the plane
  grid.weft_axis = Vec3::UnitY();
  grid.origin = -0.15 * (downhill + Vec3::UnitY()) + 0.01 * normal;
  SimSettings settings;
  settings.air_damping_1_s = 0.0;
  settings.obstacles = {PlaneObstacle{Vec3::Zero(), normal}};
  settings.collision_friction = friction;
  Simulator sim(make_grid(grid), fabric(200.0), {}, settings);
  const auto com = [&]() -> Vec3 {
    return (sim.masses_kg().transpose() * sim.state().x).transpose() / sim.masses_kg().sum();
  };
  const Vec3 start = com();
  sim.advance(t_end);
  for (Index i = 0; i < sim.mesh().vertex_count(); ++i)  // on the plane, never through it
    EXPECT_GE(sim.state().x.row(i).dot(normal.transpose()), settings.collision_thickness_m - 1e-9);
  return (com() - start).dot(downhill);
}

// Coulomb's law on a 20° slope (tan 20° = 0.364): without friction the cloth slides as a block
// would, s = ½ g sin θ t²; with μ = 0.2 it slides at g (sin θ − μ cos θ); with μ = 0.6 it stays.
TEST(Simulator, ClothOnASlopeSlidesWithoutFrictionAndStaysWithFrictionAboveTanTheta) {
  const double t_end = 1.0, g = 9.81, theta = 20.0 * base::kPi / 180.0;
  const double frictionless = slide_down_a_slope(0.0, t_end);
  const double kinetic = slide_down_a_slope(0.2, t_end);
  const double sticking = slide_down_a_slope(0.6, t_end);
  std::printf("slide down a 20 deg slope in %.1f s: mu 0 %.4f m, mu 0.2 %.4f m, mu 0.6 %.5f m\n",
              t_end, frictionless, kinetic, sticking);
  // Measured: 1.678 m and 0.758 m against 1.678 m and 0.756 m; 2.9 mm.
  EXPECT_NEAR(frictionless, 0.5 * g * std::sin(theta) * t_end * t_end, 0.03);
  EXPECT_NEAR(kinetic, 0.5 * g * (std::sin(theta) - 0.2 * std::cos(theta)) * t_end * t_end, 0.03);
  // Only the fall onto the plane moves it along the slope: 1 cm / cos θ · sin θ = 3.6 mm at most.
  EXPECT_LT(std::abs(sticking), 0.0037);
  EXPECT_LT(std::abs(sticking), 0.01 * frictionless);
}

// Implicit Euler takes the grid's bending into its matrix when explicit bending would be
// unstable at its step (h ω > 2 with the safety factor, ω over the bending), or when asked.
TEST(Simulator, BendingEntersTheImplicitStepWhereExplicitBendingWouldBeUnstable) {
  const auto bending_explicit = [](const ClothMesh& mesh, Integrator integrator,
                                   BendingInStep choice) {
    SimSettings s;
    s.integrator = integrator;
    s.bending_in_step = choice;
    const Simulator sim(mesh, fabric(1e3), {}, s);
    return std::any_of(sim.system().terms.begin(), sim.system().terms.end(), [](const auto& t) {
      return t->has_stiffness() && !t->stiffness_in_time_step();
    });
  };
  const ClothMesh coarse = square(16, 1.0);  // h² ω² ≈ 0.02 at h = 1/120 s
  const ClothMesh fine = square(64, 0.25);   // h² ω² ≈ 450
  EXPECT_TRUE(bending_explicit(coarse, Integrator::implicit_euler, BendingInStep::automatic));
  EXPECT_FALSE(bending_explicit(fine, Integrator::implicit_euler, BendingInStep::automatic));
  EXPECT_TRUE(bending_explicit(fine, Integrator::implicit_euler, BendingInStep::explicit_forces));
  EXPECT_FALSE(bending_explicit(coarse, Integrator::implicit_euler, BendingInStep::implicit));
  // The explicit integrators have no matrix: their step follows the critical step instead.
  EXPECT_TRUE(bending_explicit(fine, Integrator::symplectic_euler, BendingInStep::automatic));
  // --explain says which: on the integrate line, or after the bending stencils.
  SimSettings implicit;
  implicit.integrator = Integrator::implicit_euler;
  const auto explained = [&](const ClothMesh& mesh) {
    std::string all;
    for (const std::string& line : Simulator(mesh, fabric(1e3), {}, implicit).explain())
      all += line + "\n";
    return all;
  };
  const std::string coarse_text = explained(coarse), fine_text = explained(fine);
  // The limit it prints is the one it uses: far above the step at 16², none at 64².
  const double coarse_limit_s = Simulator(coarse, fabric(1e3), {}, implicit).explicit_stable_time_step();
  EXPECT_GT(coarse_limit_s, 5.0 * implicit.implicit_default_step_s);
  std::ostringstream stated;
  stated << ", bending explicit (stable at h ≤ " << 1e3 * coarse_limit_s << " ms)";
  EXPECT_NE(coarse_text.find(stated.str()), std::string::npos) << coarse_text;
  EXPECT_EQ(Simulator(fine, fabric(1e3), {}, implicit).explicit_stable_time_step(),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(coarse_text.find("(stiffness in the step's matrix)"), std::string::npos) << coarse_text;
  EXPECT_EQ(fine_text.find(", bending explicit"), std::string::npos) << fine_text;
  EXPECT_NE(fine_text.find("bending stencils (stiffness in the step's matrix)"), std::string::npos)
      << fine_text;
}

}  // namespace
}  // namespace weft::sim
