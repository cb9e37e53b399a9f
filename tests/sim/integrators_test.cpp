// The explicit integrators (sim/integrators/explicit_steppers.h) against analytic solutions:
// free fall, the order of convergence and the energy behaviour on a linear oscillator, and the
// stability limits hω ≤ 2 (symplectic Euler, velocity Verlet, central difference), hω ≤ 2√2
// (RK4) and none (explicit Euler) — on a single spring, and on a cloth against the largest
// eigenvalue of its M⁻¹K. Each run through the Simulator checks the integrator's wiring.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "base/constants.h"
#include "sim/energies/spring.h"
#include "sim/integrators/explicit_steppers.h"
#include "sim/integrators/implicit_euler.h"
#include "sim/mass_spring.h"
#include "sim/pins.h"
#include "sim/simulator.h"
#include "tests/sim/test_cloth.h"

namespace weft::sim {
namespace {

using test_cloth::fabric;
using test_cloth::square;

const std::vector<Integrator> kExplicit{Integrator::symplectic_euler, Integrator::explicit_euler,
                                        Integrator::rk4, Integrator::velocity_verlet,
                                        Integrator::central_difference};

// A linear oscillator: vertex 1 (mass m) on a spring (k, rest length L) to vertex 0, pinned at
// the origin, moving along x without gravity or damping: u = x − L obeys ü = −ω² u, ω² = k/m,
// exactly (the spring's force is −k u along its own axis while u > −L).
struct Oscillator {
  static constexpr double kMass = 0.1, kRest = 1.0, kAmplitude = 0.1;  // kg, m, m
  double omega;                                                        // rad/s
  double k() const { return kMass * omega * omega; }
  double period() const { return 2.0 * base::kPi / omega; }

  System system() const {
    System s;
    s.terms.push_back(std::make_shared<SpringTerm>(
        std::vector<Spring>{{0, 1, kRest, k(), SpringKind::warp}}));
    s.mass_kg = Eigen::Vector2d(1.0, kMass);
    s.inv_mass = Eigen::Vector2d(0.0, 1.0 / kMass);
    return s;
  }
  // Released from u = kAmplitude at rest: u(t) = A cos ωt.
  static Matrix3X start() {
    Matrix3X x = Matrix3X::Zero(2, 3);
    x(1, 0) = kRest + kAmplitude;
    return x;
  }
  // ½ m v² + ½ k u², J.
  double energy(const Matrix3X& x, const Matrix3X& v) const {
    const double u = x(1, 0) - kRest;
    return 0.5 * kMass * v.row(1).squaredNorm() + 0.5 * k() * u * u;
  }
};

// Runs `steps` steps of h from the oscillator's start and returns |u − A cos ωt| at the end.
double oscillator_position_error(const Oscillator& osc, Integrator method, double h, long steps) {
  const System system = osc.system();
  ExplicitStepper stepper(method, system);
  Matrix3X x = Oscillator::start(), v = Matrix3X::Zero(2, 3);
  for (long n = 0; n < steps; ++n) stepper.step(system, x, v, h);
  const double t = h * static_cast<double>(steps);
  return std::abs(x(1, 0) - Oscillator::kRest - Oscillator::kAmplitude * std::cos(osc.omega * t));
}

// --- (a) free fall and order of convergence -------------------------------------------------

// A free particle under gravity, thrown with v0: x(t) = x0 + v0 t + g t²/2, v(t) = v0 + g t.
// The second- and fourth-order methods integrate a constant acceleration exactly (to round-off);
// the two Euler methods are off by exactly ±g t h/2 in position (symplectic Euler moves with
// the new velocity, explicit Euler with the old one) and exact in velocity. Central difference
// carries the half-step velocity v(t − h/2).
TEST(ExplicitIntegrators, FreeFallMatchesTheAnalyticTrajectory) {
  const Vec3 g(0.0, 0.0, -9.81), x0(0.2, -0.1, 3.0), v0(0.3, -0.2, 1.5);
  const double h = 0.01, t = 0.5;
  const long steps = 50;
  for (Integrator method : kExplicit) {
    System s;
    s.mass_kg = Eigen::VectorXd::Constant(1, 0.3);
    s.inv_mass = s.mass_kg.cwiseInverse();
    s.gravity_m_s2 = g;
    ExplicitStepper stepper(method, s);
    Matrix3X x = x0.transpose(), v = v0.transpose();
    for (long n = 0; n < steps; ++n) stepper.step(s, x, v, h);
    double offset = 0.0;  // the position error in units of g t h / 2
    if (method == Integrator::symplectic_euler) offset = 1.0;
    if (method == Integrator::explicit_euler) offset = -1.0;
    const Vec3 expected_x = x0 + v0 * t + 0.5 * g * t * t + offset * 0.5 * g * t * h;
    const Vec3 expected_v = v0 + g * (method == Integrator::central_difference ? t - 0.5 * h : t);
    EXPECT_LT((Vec3(x.row(0)) - expected_x).norm(), 1e-12) << integrator_name(method);
    EXPECT_LT((Vec3(v.row(0)) - expected_v).norm(), 1e-12) << integrator_name(method);
  }
}

// Every integrator through the Simulator: an unpinned cloth falls freely (no spring stretched,
// so only gravity acts) onto the same trajectory, x0 + g t²/2 with the Euler methods' ±g t h/2
// (implicit Euler's velocity recurrence is symplectic Euler's in free fall); a pinned one keeps
// its pins exactly in place.
TEST(ExplicitIntegrators, EveryIntegratorFallsFreelyInTheSimulatorAndKeepsItsPins) {
  const double h = 2e-3, t = 0.2;
  for (Integrator method : all_integrators) {
    if (!integrates_physical_time(method)) continue;  // dynamic relaxation: no trajectory
    SimSettings settings;
    settings.integrator = method;
    settings.air_damping_1_s = 0.0;
    settings.time_step = fixed_time_step(h);
    Simulator sim(square(5), fabric(300.0), {}, settings);
    sim.advance(t);
    const Vec3 g = settings.gravity_m_s2;
    double offset = 0.0;
    if (method == Integrator::symplectic_euler || method == Integrator::implicit_euler) offset = 1;
    if (method == Integrator::explicit_euler) offset = -1.0;
    for (Index i = 0; i < sim.mesh().vertex_count(); ++i) {
      const Vec3 expected =
          Vec3(sim.mesh().rest_positions.row(i)) + 0.5 * g * t * t + offset * 0.5 * g * t * h;
      EXPECT_LT((Vec3(sim.state().x.row(i)) - expected).norm(), 1e-9)
          << integrator_name(method) << " vertex " << i;
    }

    const ClothMesh mesh = square(7, 0.3);
    const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
    settings.air_damping_1_s = 0.5;
    settings.time_step = {};  // automatic
    Simulator hanging(mesh, fabric(300.0), pins, settings);
    hanging.advance(0.02);  // explicit Euler diverges soon after (its energy grows at any h)
    for (Index p : pins) {
      EXPECT_EQ(Vec3(hanging.state().x.row(p)), Vec3(mesh.rest_positions.row(p)))
          << integrator_name(method);
      EXPECT_EQ(Vec3(hanging.state().v.row(p)), Vec3::Zero()) << integrator_name(method);
    }
    EXPECT_LT(hanging.state().x.col(2).minCoeff(), 1.999) << integrator_name(method);  // moved
  }
}

// The global error at t = 1 s for h, h/2 and h/4 shrinks as h^p: explicit and symplectic Euler
// p = 1, velocity Verlet and central difference p = 2, RK4 p = 4. ω t = 4π + π/4 at t = 1 s,
// so that phase and amplitude errors both show in the position (sin ωt = cos ωt). Each method's
// h keeps it in its asymptotic range and RK4's error above round-off.
TEST(ExplicitIntegrators, OscillatorErrorConvergesAtTheExpectedOrder) {
  const Oscillator osc{4.0 * base::kPi + 0.25 * base::kPi};  // 13.35 rad/s
  struct Case {
    Integrator method;
    long steps;  // for the coarsest h = 1 s / steps
    double order;
  };
  const Case cases[] = {{Integrator::explicit_euler, 1000, 1.0},
                        {Integrator::symplectic_euler, 250, 1.0},
                        {Integrator::velocity_verlet, 100, 2.0},
                        {Integrator::central_difference, 100, 2.0},
                        {Integrator::rk4, 100, 4.0}};
  for (const Case& c : cases) {
    double errors[3];
    for (int r = 0; r < 3; ++r) {
      const long steps = c.steps << r;
      errors[r] = oscillator_position_error(osc, c.method, 1.0 / static_cast<double>(steps), steps);
    }
    const double p1 = std::log2(errors[0] / errors[1]), p2 = std::log2(errors[1] / errors[2]);
    std::printf("%-18s h = 1/%ld s: errors %.3e %.3e %.3e m, orders %.3f %.3f\n",
                integrator_name(c.method), c.steps, errors[0], errors[1], errors[2], p1, p2);
    EXPECT_NEAR(p1, c.order, 0.3) << integrator_name(c.method);
    EXPECT_NEAR(p2, c.order, 0.3) << integrator_name(c.method);
  }
}

// --- (b) energy on the undamped oscillator ---------------------------------------------------

// Relative energy error |E/E0 − 1| at each of 100 periods × 50 steps (h = T/50, hω = 0.126).
std::vector<double> energy_errors(Integrator method) {
  const Oscillator osc{2.0 * base::kPi};  // T = 1 s
  const long steps = 5000;
  const double h = osc.period() / 50.0;
  const System system = osc.system();
  ExplicitStepper stepper(method, system);
  Matrix3X x = Oscillator::start(), v = Matrix3X::Zero(2, 3);
  const double e0 = osc.energy(x, v);
  std::vector<double> errors;
  for (long n = 0; n < steps; ++n) {
    stepper.step(system, x, v, h);
    errors.push_back(std::abs(osc.energy(x, v) / e0 - 1.0));
  }
  return errors;
}

double max_over(const std::vector<double>& e, std::size_t begin, std::size_t end) {
  return *std::max_element(e.begin() + static_cast<std::ptrdiff_t>(begin),
                           e.begin() + static_cast<std::ptrdiff_t>(end));
}

// Symplectic Euler and velocity Verlet conserve a modified energy, so the error of the true
// one oscillates (O(hω) and O((hω)²)) without growing: its largest value in the last tenth of
// the run is that of the first tenth. Central difference moves its positions exactly as Verlet
// does, but its kinetic energy uses the half-step velocity: an O(hω) oscillation, also bounded.
TEST(ExplicitIntegrators, SymplecticMethodsKeepTheOscillatorsEnergyBounded) {
  for (Integrator method : {Integrator::symplectic_euler, Integrator::velocity_verlet,
                            Integrator::central_difference}) {
    const std::vector<double> e = energy_errors(method);
    const std::size_t tenth = e.size() / 10;
    const double first = max_over(e, 0, tenth), last = max_over(e, e.size() - tenth, e.size());
    std::printf("%-18s max relative energy error: first tenth %.3e, last tenth %.3e\n",
                integrator_name(method), first, last);
    EXPECT_LT(first, method == Integrator::velocity_verlet ? 0.01 : 0.1) << integrator_name(method);
    EXPECT_LT(last, 1.05 * first) << integrator_name(method);
  }
}

// RK4 is not symplectic: per step ω²u² + v² shrinks by |R(ihω)|² = 1 − (hω)⁶/72 + (hω)⁸/576,
// a slow, steady loss — about 2.7e-4 over 100 periods at h = T/50 (not below 1e-6: that would
// take h ≈ T/120). Explicit Euler gains the factor 1 + (hω)² every step, at any h.
TEST(ExplicitIntegrators, RungeKuttaDriftsSlowlyAndExplicitEulerGainsEnergy) {
  const double y = 2.0 * base::kPi / 50.0;  // hω
  const double rk4_factor = 1.0 - std::pow(y, 6) / 72.0 + std::pow(y, 8) / 576.0;
  const std::vector<double> rk4 = energy_errors(Integrator::rk4);
  const double predicted = 1.0 - std::pow(rk4_factor, static_cast<double>(rk4.size()));
  std::printf("rk4 relative energy loss over 100 periods at h = T/50: %.4e (predicted %.4e)\n",
              rk4.back(), predicted);
  EXPECT_NEAR(rk4.back(), predicted, 1e-3 * predicted);
  EXPECT_LT(rk4.back(), 3e-4);
  for (std::size_t n = 1; n < rk4.size(); n += 50)  // it only ever loses
    EXPECT_GE(rk4[n], rk4[n - 1] - 1e-14) << "step " << n;

  const std::vector<double> euler = energy_errors(Integrator::explicit_euler);
  const std::size_t tenth = euler.size() / 10;
  EXPECT_GT(max_over(euler, euler.size() - tenth, euler.size()), 1e6 * max_over(euler, 0, tenth));
  // E_n = E_0 (1 + (hω)²)^n exactly (½ m (v² + ω²u²) is the oscillator's energy).
  EXPECT_NEAR(std::log1p(euler[99]), 100.0 * std::log1p(y * y), 1e-9);
}

// Backward Euler, for comparison (sim/integrators/implicit_euler.h; its exact per-step factor
// 1/(1 + (hω)²) is checked in implicit_euler_test.cpp): the same oscillator — a 2×2 grid with
// one pinned edge, each free vertex on one warp spring — loses energy at every step.
TEST(ExplicitIntegrators, ImplicitEulerDecaysTheOscillatorsEnergy) {
  Material m;
  m.density_kg_m2 = 0.2;
  m.stretch_warp_N_m = m.stretch_weft_N_m = 1000.0;
  m.shear_N_m = m.bend_warp_Nm = m.bend_weft_Nm = 0.0;
  const ClothMesh mesh = square(2, 0.1, Vec3(0, 0, 1));
  const MassSpringModel model(mesh, m);
  const Eigen::VectorXd mass = m.density_kg_m2 * mesh.vertex_area_m2;
  Eigen::VectorXd inv_mass = mass.cwiseInverse();
  inv_mass[mesh.index(0, 0)] = inv_mass[mesh.index(0, 1)] = 0.0;
  System system;
  system.mass_kg = mass;
  system.inv_mass = inv_mass;
  system.terms = model.terms();
  ImplicitEuler implicit(system, ImplicitSolveSettings{});
  const Index free = mesh.index(1, 0);
  const double omega2 = model.springs().front().k_N_m / mass[free];
  const double h = 2.0 * base::kPi / std::sqrt(omega2) / 50.0;
  Matrix3X x = mesh.rest_positions, v = Matrix3X::Zero(4, 3);
  x(free, 0) += 0.01;
  x(mesh.index(1, 1), 0) += 0.01;
  const auto energy = [&] {
    const double u = x(free, 0) - mesh.rest_positions(free, 0);
    return omega2 * u * u + v(free, 0) * v(free, 0);
  };
  const double e0 = energy();
  double previous = e0;
  for (int n = 0; n < 500; ++n) {  // 10 periods
    ASSERT_TRUE(implicit.step(system, x, v, h).solved);  // and x += h v
    ASSERT_LT(energy(), previous) << "step " << n;
    previous = energy();
  }
  std::printf("implicit_euler energy after 10 periods at h = T/50: %.3e of the initial\n",
              previous / e0);
  EXPECT_LT(previous, 1e-3 * e0);
}

// --- (c) stability limits --------------------------------------------------------------------

// The largest E/E0 within 1000 steps of h = factor × critical on the oscillator.
double energy_growth(Integrator method, double h_omega) {
  const Oscillator osc{10.0};
  const System system = osc.system();
  ExplicitStepper stepper(method, system);
  const double h = h_omega / osc.omega;
  Matrix3X x = Oscillator::start(), v = Matrix3X::Zero(2, 3);
  const double e0 = osc.energy(x, v);
  double worst = 1.0;
  for (int n = 0; n < 1000 && worst < 1e12; ++n) {
    stepper.step(system, x, v, h);
    worst = std::max(worst, osc.energy(x, v) / e0);
  }
  return worst;
}

// hω_crit: 2 for symplectic Euler, velocity Verlet and central difference, 2√2 for RK4. Stable
// at 0.9× and explosive (energy × 1e6 within 1000 steps) at 1.3×. Stable still lets the energy
// swing along the conserved modified energy: for symplectic Euler started at rest E/E0 reaches
// 1/(1 − hω/2) = 10 at hω = 1.8 (measured 10.000); Verlet stays at or below E0, central
// difference (half-step kinetic energy) reaches 1.9, RK4 decays. Explicit Euler explodes even
// at hω = 0.2.
TEST(ExplicitIntegrators, StabilityLimitsOnASingleSpring) {
  for (Integrator method : kExplicit) {
    if (method == Integrator::explicit_euler) {
      const double growth = energy_growth(method, 0.2);
      std::printf("%-18s at h omega = 0.2: energy x %.3e\n", integrator_name(method), growth);
      EXPECT_GT(growth, 1e6);
      continue;
    }
    const double critical = method == Integrator::rk4 ? 2.0 * std::sqrt(2.0) : 2.0;
    const double below = energy_growth(method, 0.9 * critical);
    const double above = energy_growth(method, 1.3 * critical);
    std::printf("%-18s h omega critical %.4f: max E/E0 %.3f at 0.9x, %.3e at 1.3x\n",
                integrator_name(method), critical, below, above);
    EXPECT_LT(below, 10.0 * (1.0 + 1e-9)) << integrator_name(method);
    EXPECT_GT(above, 1e6) << integrator_name(method);
  }
}

// A cloth's stability limit is 2/ω_max with ω_max² the largest eigenvalue of M⁻¹K over the free
// vertices. On the wool of sim::Material at 8×8 (1 m, hung from two corners), K is built by
// central differences of the model's forces at rest and ω_max² taken from the symmetric
// M^{-1/2} K M^{-1/2}. (simulator_test checks the Simulator's Gershgorin estimate, which lies
// below this exact step: 0.77 of it here.) Symplectic Euler is stable at 0.9× the exact step
// and blows up within a second at 1.1× and 1.3×.
TEST(ExplicitIntegrators, ClothBlowsUpJustAboveTheStepOfItsLargestEigenvalue) {
  const ClothMesh mesh = square(8);
  const Material wool;
  const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  const MassSpringModel model(mesh, wool);
  const Eigen::VectorXd mass = wool.density_kg_m2 * mesh.vertex_area_m2;
  std::vector<Index> free;
  for (Index i = 0; i < mesh.vertex_count(); ++i)
    if (std::find(pins.begin(), pins.end(), i) == pins.end()) free.push_back(i);

  const Index dofs = 3 * static_cast<Index>(free.size());
  Eigen::MatrixXd S(dofs, dofs);  // M^{-1/2} K M^{-1/2} on the free DOFs, 1/s²
  const double eps = 1e-6;        // m
  for (Index c = 0; c < dofs; ++c) {
    const Index vc = free[c / 3];
    Matrix3X plus = mesh.rest_positions, minus = mesh.rest_positions;
    plus(vc, c % 3) += eps;
    minus(vc, c % 3) -= eps;
    Matrix3X f_plus = Matrix3X::Zero(plus.rows(), 3), f_minus = f_plus;
    model.add_forces(plus, f_plus);
    model.add_forces(minus, f_minus);
    for (Index r = 0; r < dofs; ++r) {  // K = −∂f/∂x
      const Index vr = free[r / 3];
      S(r, c) =
          -(f_plus(vr, r % 3) - f_minus(vr, r % 3)) / (2.0 * eps) / std::sqrt(mass[vr] * mass[vc]);
    }
  }
  S = 0.5 * (S + S.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S, Eigen::EigenvaluesOnly);
  const double exact_step = 2.0 / std::sqrt(eig.eigenvalues().maxCoeff());

  SimSettings settings;
  const double gershgorin_step = Simulator(mesh, wool, pins, settings).critical_time_step();
  std::printf(
      "8x8 wool: critical step %.4e s from the largest eigenvalue, %.4e s Gershgorin "
      "(%.3f of it)\n",
      exact_step, gershgorin_step, gershgorin_step / exact_step);
  EXPECT_LE(gershgorin_step, exact_step * (1.0 + 1e-6));

  const auto survives = [&](double factor) {
    SimSettings s = settings;
    s.time_step = fixed_time_step(factor * exact_step);
    Simulator sim(mesh, wool, pins, s);
    try {
      sim.advance(1.0);
    } catch (const DivergenceError&) {
      return false;
    }
    return sim.diagnostics().max_strain < 0.5;
  };
  // Measured: stable up to 1.000 of the exact step, diverged from 1.025 (within the second).
  EXPECT_TRUE(survives(0.9));
  EXPECT_FALSE(survives(1.1));
  EXPECT_FALSE(survives(1.3));
}

}  // namespace
}  // namespace weft::sim
