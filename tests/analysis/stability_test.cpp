// Stability near rest (analysis/stability.h): the largest eigenvalue of M⁻¹K against analytic values
// (one spring: k/m; a fixed–fixed chain: 4k/m sin²(nπ/2(n+1))) and a dense eigen-solve, and the
// observed critical steps of the integrators against their predictions — one spring, damped
// explicit Euler, and the standard cloth of `weft stability`.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <vector>

#include "base/constants.h"
#include "sim/energies/spring.h"
#include "sim/mass_spring.h"
#include "sim/simulator.h"
#include "analysis/stability.h"

namespace weft::analysis {
namespace {

// Masses m on springs k (rest length L) along x: vertex 0 pinned at the origin, then `free`
// vertices, then (fixed_far_end) one more pinned vertex. Only the axial motion is stiff at rest
// (the springs carry no tension), so the nonzero eigenvalues of M⁻¹K are those of the 1-D chain.
struct Chain {
  static constexpr double kMass = 0.02, kStiffness = 50.0, kRest = 0.1;  // kg, N/m, m
  sim::Index free = 1;
  bool fixed_far_end = false;

  sim::Index vertices() const { return free + (fixed_far_end ? 2 : 1); }
  sim::Matrix3X rest() const {
    sim::Matrix3X x = sim::Matrix3X::Zero(vertices(), 3);
    for (sim::Index i = 0; i < vertices(); ++i) x(i, 0) = kRest * i;
    return x;
  }
  Eigen::VectorXd mass() const { return Eigen::VectorXd::Constant(vertices(), kMass); }
  Eigen::VectorXd inv_mass() const {
    Eigen::VectorXd inv = Eigen::VectorXd::Constant(vertices(), 1.0 / kMass);
    inv[0] = 0.0;
    if (fixed_far_end) inv[vertices() - 1] = 0.0;
    return inv;
  }
  InternalForces forces() const {
    const sim::Index n = vertices();
    return [n](const sim::Matrix3X& x, sim::Matrix3X& f) {
      for (sim::Index i = 0; i + 1 < n; ++i) {
        const sim::Vec3 grad = sim::spring_gradient_b(x.row(i), x.row(i + 1), kRest, kStiffness);
        f.row(i) += grad.transpose();
        f.row(i + 1) -= grad.transpose();
      }
    };
  }
  sim::System system(double damping_1_s) const {
    std::vector<sim::Spring> springs;
    for (sim::Index i = 0; i + 1 < vertices(); ++i)
      springs.push_back({i, i + 1, kRest, kStiffness, sim::SpringKind::warp});
    sim::System s;
    s.terms.push_back(std::make_shared<sim::SpringTerm>(std::move(springs)));
    s.mass_kg = mass();
    s.inv_mass = inv_mass();
    s.damping_1_s = damping_1_s;
    return s;
  }
  double omega_spring() const { return std::sqrt(kStiffness / kMass); }  // √(k/m), rad/s
};

double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// Observed critical step of `method` on the chain, and its ratio to `predicted_h_s`.
double observed_over_predicted(const Chain& chain, sim::Integrator method, double damping_1_s,
                               double predicted_h_s, const BlowUpSettings& settings = {}) {
  const CriticalStepSearch search =
      find_critical_step(stepper_factory(method, chain.system(damping_1_s)),
                         chain.rest(), chain.mass(), chain.inv_mass(), predicted_h_s, settings);
  EXPECT_TRUE(search.bracketed) << sim::integrator_name(method);
  const double ratio = search.h_s() / predicted_h_s;
  std::printf("%-18s alpha %8.3f 1/s: predicted %.5e s, observed %.5e s, ratio %.4f (%d runs)\n",
              sim::integrator_name(method), damping_1_s, predicted_h_s, search.h_s(), ratio,
              search.runs);
  return ratio;
}

// --- the eigenvalue routine -----------------------------------------------------------------

TEST(LargestEigenvalue, SingleSpringGivesKOverM) {
  const Chain spring;
  const LargestEigenvalue e = largest_eigenvalue_mass_stiffness(
      spring.forces(), spring.rest(), spring.mass(), spring.inv_mass());
  std::printf("one spring: lambda %.12e, k/m %.12e\n", e.lambda_1_s2, Chain::kStiffness / Chain::kMass);
  EXPECT_TRUE(e.converged);
  EXPECT_LT(relative_error(e.lambda_1_s2, Chain::kStiffness / Chain::kMass), 1e-7)
      << e.lambda_1_s2 << " vs k/m = " << Chain::kStiffness / Chain::kMass;
}

// n equal masses between two walls: λ_j = (4k/m) sin²(jπ / 2(n+1)), j = 1..n; the top two
// differ by only 1.4 % at n = 24, which power iteration would need hundreds of steps to split.
TEST(LargestEigenvalue, FixedChainMatchesItsAnalyticSpectrum) {
  Chain chain;
  chain.free = 24;
  chain.fixed_far_end = true;
  const double n = chain.free;
  const double exact = 4.0 * Chain::kStiffness / Chain::kMass *
                       std::pow(std::sin(n * base::kPi / (2.0 * (n + 1.0))), 2);
  const LargestEigenvalue e = largest_eigenvalue_mass_stiffness(
      chain.forces(), chain.rest(), chain.mass(), chain.inv_mass());
  std::printf("chain of %d: lambda %.10e, exact %.10e, %d Lanczos steps\n", chain.free,
              e.lambda_1_s2, exact, e.iterations);
  EXPECT_TRUE(e.converged);
  EXPECT_LT(relative_error(e.lambda_1_s2, exact), 1e-7);
}

// The standard cloth at 6×6: Lanczos against a dense eigen-solve of M^{-1/2} K M^{-1/2} built
// column by column from central differences of the forces, and below the Gershgorin bound.
TEST(LargestEigenvalue, AgreesWithADenseEigenSolveOnASmallCloth) {
  const StabilityCloth cloth(6, 1.0);
  const sim::Matrix3X& x0 = cloth.rest_positions();
  const Eigen::VectorXd& m = cloth.mass_kg();
  std::vector<sim::Index> free;
  for (sim::Index i = 0; i < x0.rows(); ++i)
    if (cloth.inv_mass()[i] > 0.0) free.push_back(i);
  const sim::Index dofs = 3 * static_cast<sim::Index>(free.size());
  Eigen::MatrixXd S(dofs, dofs);
  const double eps = 1e-6;  // m
  for (sim::Index c = 0; c < dofs; ++c) {
    const sim::Index vc = free[c / 3];
    sim::Matrix3X plus = x0, minus = x0;
    plus(vc, c % 3) += eps;
    minus(vc, c % 3) -= eps;
    sim::Matrix3X f_plus = sim::Matrix3X::Zero(x0.rows(), 3), f_minus = f_plus;
    cloth.model().add_forces(plus, f_plus);
    cloth.model().add_forces(minus, f_minus);
    for (sim::Index r = 0; r < dofs; ++r) {
      const sim::Index vr = free[r / 3];
      S(r, c) = -(f_plus(vr, r % 3) - f_minus(vr, r % 3)) / (2.0 * eps) / std::sqrt(m[vr] * m[vc]);
    }
  }
  S = 0.5 * (S + S.transpose()).eval();
  const double dense = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly)
                           .eigenvalues()
                           .maxCoeff();
  const LargestEigenvalue e = cloth.largest_eigenvalue();
  const double gershgorin_step =
      sim::Simulator(cloth.mesh(), cloth.material(), cloth.pinned(), sim::SimSettings{})
          .critical_time_step();
  const double gershgorin_lambda = 4.0 / (gershgorin_step * gershgorin_step);  // (2/h)²
  std::printf("6x6 wool: Lanczos %.10e (%d steps), dense %.10e, Gershgorin %.4e 1/s^2\n",
              e.lambda_1_s2, e.iterations, dense, gershgorin_lambda);
  EXPECT_TRUE(e.converged);
  EXPECT_LT(relative_error(e.lambda_1_s2, dense), 1e-6);
  EXPECT_GE(gershgorin_lambda, e.lambda_1_s2);
}

// --- predicted against observed critical steps ----------------------------------------------

TEST(PredictedCriticalStep, KindsAndArguments) {
  EXPECT_EQ(predicted_critical_step(sim::Integrator::explicit_euler, 10.0).limit,
            StepLimit::always_unstable);
  EXPECT_EQ(predicted_critical_step(sim::Integrator::implicit_euler, 10.0, 1.0).limit,
            StepLimit::always_stable);
  EXPECT_DOUBLE_EQ(predicted_critical_step(sim::Integrator::rk4, 10.0).h_s, 0.2 * std::sqrt(2.0));
  EXPECT_THROW((void)predicted_critical_step(sim::Integrator::rk4, 0.0), std::invalid_argument);
  EXPECT_THROW((void)predicted_critical_step(sim::Integrator::explicit_euler, 1.0, -1.0),
               std::invalid_argument);
}

// One spring: 2√(m/k) (RK4 2√2·√(m/k)) from the computed eigenvalue. Near the limit a mode
// grows by |R| − 1 ∝ √(hω − 2) per step (symplectic Euler), so 1000 steps locate it to 0.1 %.
TEST(CriticalStep, SingleSpringBlowsUpAtThePredictedStep) {
  const Chain spring;
  const double omega = largest_eigenvalue_mass_stiffness(spring.forces(), spring.rest(),
                                                         spring.mass(), spring.inv_mass())
                           .omega_rad_s();
  EXPECT_LT(relative_error(omega, spring.omega_spring()), 1e-7);
  for (sim::Integrator method :
       {sim::Integrator::symplectic_euler, sim::Integrator::rk4, sim::Integrator::velocity_verlet,
        sim::Integrator::central_difference}) {
    const double predicted = predicted_critical_step(method, omega).h_s;
    const double analytic = (method == sim::Integrator::rk4 ? 2.0 * std::sqrt(2.0) : 2.0) /
                            spring.omega_spring();  // 2√(m/k), RK4 2√2·√(m/k)
    EXPECT_LT(relative_error(predicted, analytic), 1e-7);
    const double ratio = observed_over_predicted(spring, method, 0.0, predicted);
    EXPECT_NEAR(ratio, 1.0, 0.02) << sim::integrator_name(method);  // the issue asks for 30 %
  }
  // With damping α = ω/2: symplectic Euler's limit moves to (√(α² + 4ω²) − α)/ω² = 0.78 × 2/ω;
  // central difference's (centred damping) stays 2/ω.
  const double alpha = 0.5 * omega;
  for (sim::Integrator method :
       {sim::Integrator::symplectic_euler, sim::Integrator::central_difference}) {
    const double predicted = predicted_critical_step(method, omega, alpha).h_s;
    EXPECT_NEAR(observed_over_predicted(spring, method, alpha, predicted), 1.0, 0.02)
        << sim::integrator_name(method);
  }
}

// A vertex held by three springs along x, y and z to pinned anchors: M⁻¹K = (k/m) I at rest,
// so every mode has ω = √(k/m) (a single spring also has transverse modes with ω = 0, whose
// explicit-Euler limit with damping is 2/α).
struct Tripod {
  static constexpr double kMass = Chain::kMass, kStiffness = Chain::kStiffness, kRest = Chain::kRest;
  sim::Matrix3X rest() const {
    sim::Matrix3X x = sim::Matrix3X::Zero(4, 3);
    for (int axis = 0; axis < 3; ++axis) x(axis + 1, axis) = kRest;
    return x;
  }
  Eigen::VectorXd mass() const { return Eigen::VectorXd::Constant(4, kMass); }
  Eigen::VectorXd inv_mass() const { return Eigen::Vector4d(1.0 / kMass, 0.0, 0.0, 0.0); }
  sim::System system(double damping_1_s) const {
    std::vector<sim::Spring> springs;  // anchor a to the vertex b = 0
    for (sim::Index anchor = 1; anchor < 4; ++anchor)
      springs.push_back({anchor, 0, kRest, kStiffness, sim::SpringKind::warp});
    sim::System s;
    s.terms.push_back(std::make_shared<sim::SpringTerm>(std::move(springs)));
    s.mass_kg = mass();
    s.inv_mass = inv_mass();
    s.damping_1_s = damping_1_s;
    return s;
  }
};

// Explicit Euler multiplies a mode by |R|² = 1 − hα + h²ω² per step: unstable at every step
// undamped (here hω = 0.1, |R|² = 1.01); with damping α = ω/2 stable below α/ω², where a mode
// grows by only ≈ (α²/ω²)(h/h_c − 1)/2 per step, hence 5000-step runs. Overdamped (α = 3ω, on
// the tripod) the limit is 2/|μ₋|, μ₋ = −α/2 − √(α²/4 − ω²).
TEST(CriticalStep, ExplicitEulerNeedsDampingAndThenBlowsUpAtAlphaOverOmegaSquared) {
  const Chain spring;
  const double omega = spring.omega_spring();
  BlowUpSettings long_run;
  long_run.steps = 5000;
  const BlowUpResult undamped =
      run_blow_up_test(stepper_factory(sim::Integrator::explicit_euler, spring.system(0.0))(),
                       spring.rest(), spring.mass(), spring.inv_mass(), 0.1 / omega, long_run);
  EXPECT_FALSE(undamped.stable) << "max growth " << undamped.max_growth;

  const double alpha = 0.5 * omega;
  const double predicted =
      predicted_critical_step(sim::Integrator::explicit_euler, omega, alpha).h_s;
  EXPECT_DOUBLE_EQ(predicted, alpha / (omega * omega));
  EXPECT_NEAR(
      observed_over_predicted(spring, sim::Integrator::explicit_euler, alpha, predicted, long_run),
      1.0, 0.02);

  const Tripod tripod;
  const double overdamped = 3.0 * omega;
  const double predicted_overdamped =
      predicted_critical_step(sim::Integrator::explicit_euler, omega, overdamped).h_s;
  EXPECT_DOUBLE_EQ(predicted_overdamped,
                   2.0 / (0.5 * overdamped + std::sqrt(0.25 * overdamped * overdamped - omega * omega)));
  const CriticalStepSearch search = find_critical_step(
      stepper_factory(sim::Integrator::explicit_euler, tripod.system(overdamped)), tripod.rest(),
      tripod.mass(), tripod.inv_mass(), predicted_overdamped);
  ASSERT_TRUE(search.bracketed);
  std::printf("explicit_euler     overdamped tripod: predicted %.5e s, observed %.5e s\n",
              predicted_overdamped, search.h_s());
  EXPECT_NEAR(search.h_s() / predicted_overdamped, 1.0, 0.02);
}

// The standard cloth (12×12 wool, two corners pinned, no gravity): each explicit integrator
// blows up within 30 % of the step predicted from the computed λ_max(M⁻¹K) (measured: within
// 2 %, asserted within 5 %), and the Gershgorin step (ω from an upper bound of λ_max) is on the safe side.
// Explicit Euler runs with α = ω_max (its limit is then 1/ω_max).
TEST(CriticalStep, StandardClothBlowsUpAtThePredictedStep) {
  const StabilityCloth cloth(12, 1.0);
  const double omega = cloth.largest_eigenvalue().omega_rad_s();
  const double gershgorin_omega =
      2.0 / sim::Simulator(cloth.mesh(), cloth.material(), cloth.pinned(), sim::SimSettings{})
                .critical_time_step();
  std::printf("12x12 wool: omega_max %.6e rad/s, Gershgorin %.6e rad/s\n", omega,
              gershgorin_omega);
  for (sim::Integrator method :
       {sim::Integrator::symplectic_euler, sim::Integrator::explicit_euler, sim::Integrator::rk4,
        sim::Integrator::velocity_verlet, sim::Integrator::central_difference}) {
    const double alpha = method == sim::Integrator::explicit_euler ? omega : 0.0;
    const double predicted = predicted_critical_step(method, omega, alpha).h_s;
    const CriticalStepSearch search =
        find_critical_step(cloth.stepper_factory(method, alpha), cloth.rest_positions(),
                           cloth.mass_kg(), cloth.inv_mass(), predicted, BlowUpSettings{}, 1e-2);
    ASSERT_TRUE(search.bracketed) << sim::integrator_name(method);
    const double gershgorin = predicted_critical_step(method, gershgorin_omega, alpha).h_s;
    std::printf("%-18s predicted %.4e s, observed %.4e s (ratio %.4f), Gershgorin %.4e s\n",
                sim::integrator_name(method), predicted, search.h_s(), search.h_s() / predicted,
                gershgorin);
    EXPECT_NEAR(search.h_s() / predicted, 1.0, 0.05)
        << sim::integrator_name(method);  // issue: 30 %
    EXPECT_LE(gershgorin, search.stable_h_s) << sim::integrator_name(method);
  }
}

// Implicit Euler has no step limit: stable at 10× and 100× the explicit 2/ω_max on the cloth.
TEST(CriticalStep, ImplicitEulerIsStableFarBeyondTheExplicitLimit) {
  const StabilityCloth cloth(8, 10.0);
  const double explicit_limit = 2.0 / cloth.largest_eigenvalue().omega_rad_s();
  BlowUpSettings settings;
  settings.steps = 40;
  for (double factor : {10.0, 100.0}) {
    const BlowUpResult r = run_blow_up_test(
        cloth.stepper_factory(sim::Integrator::implicit_euler, 0.0)(), cloth.rest_positions(),
        cloth.mass_kg(), cloth.inv_mass(), factor * explicit_limit, settings);
    EXPECT_TRUE(r.stable) << factor << "x: growth " << r.max_growth;
    EXPECT_LE(r.max_growth, 2.0) << factor << "x";
  }
}

}  // namespace
}  // namespace weft::analysis
