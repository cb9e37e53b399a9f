#pragma once
// Stability of the time integrators near rest (`weft stability`).
//
// Near a rest state x₀ without gravity the equations of motion linearise to
//   M ü + α M u̇ + K u = 0,   u = x − x₀,   K = −∂f/∂x at x₀ (N/m),
// with lumped masses M and mass-proportional damping α. Mass damping keeps the modes of
// M⁻¹K decoupled: each is a scalar oscillator q̈ = −ω² q − α q̇ with ω² an eigenvalue of M⁻¹K,
// so an integrator is stable on the whole system when it is stable on its fastest mode,
// ω_max = √λ_max(M⁻¹K). This file gives the three pieces of a stability map:
//   1. λ_max(M⁻¹K) from the forces alone (Lanczos on Hessian-vector products by central
//      differences), for any force model;
//   2. the critical step each integrator is predicted to have at ω_max;
//   3. a blow-up test (run from a small seeded perturbation of the rest state, watch the
//      displacement grow) and a bisection for the observed critical step.
// The standard cloth of `weft stability` is here too, so that the tests check what the
// command plots.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "sim/grid.h"
#include "sim/integrators/integrator.h"
#include "sim/integrators/time_integrator.h"
#include "sim/mass_spring.h"
#include "sim/material/material.h"
#include "sim/types.h"

namespace weft::analysis {

// Adds the internal forces at positions x (#V×3, m) to f (#V×3, N).
using InternalForces = std::function<void(const sim::Matrix3X& x, sim::Matrix3X& f)>;

// --- 1. the largest eigenvalue of M⁻¹K ------------------------------------------------------

struct EigenvalueSettings {
  // Largest displacement of a vertex in a finite-difference probe, m: ≪ the edge length (the
  // truncation error is O((ε/l)²)) and ≫ 1e-16 × the coordinates (round-off O(1e-16 l/ε)).
  double fd_step_m = 1e-6;
  int max_iterations = 300;          // Lanczos steps (capped at the number of free DOFs)
  double relative_tolerance = 1e-9;  // stop when the Ritz residual ≤ this × the Ritz value
  std::uint64_t seed = 1;            // of the random start vector
};

struct LargestEigenvalue {
  double lambda_1_s2 = 0.0;    // λ_max(M⁻¹K) = ω_max², 1/s²
  double residual_1_s2 = 0.0;  // ‖S y − λ y‖ of the Ritz pair: an eigenvalue lies this close
  int iterations = 0;          // Lanczos steps (each two force evaluations)
  bool converged = false;
  double omega_rad_s() const;  // √λ, rad/s
};

// λ_max of M⁻¹K at positions x, over the free vertices (inv_mass > 0; pinned ones are held),
// with K = −∂f/∂x of `forces`. Works on the symmetric S = M^{-1/2} K M^{-1/2} (same
// eigenvalues; K is symmetric for forces that derive from an energy), by Lanczos with full
// reorthogonalisation; each product S q is a central difference of the forces along
// M^{-1/2} q, two force evaluations. Accuracy: the returned Ritz value is within
// residual_1_s2 of an eigenvalue of the finite-difference operator (≤ 1e-9 relative when
// converged) and the finite differences add O((ε/l)² + 1e-16 l/ε), about 1e-8 relative for
// cloth at the default ε (the tests find 1e-7 or better against k/m for one spring, the
// analytic spectrum of a chain and a dense eigen-solve of the FD Hessian). Lanczos finds the
// extreme eigenvalue from a random start unless the start misses its eigenvector entirely.
[[nodiscard]] LargestEigenvalue largest_eigenvalue_mass_stiffness(
    const InternalForces& forces, const sim::Matrix3X& x, const Eigen::VectorXd& mass_kg,
    const Eigen::VectorXd& inv_mass, const EigenvalueSettings& settings = {});

// --- 2. predicted critical steps ------------------------------------------------------------

enum class StepLimit {
  bounded,              // stable for h < h_s
  always_stable,        // implicit Euler: unconditionally stable
  always_unstable,      // explicit Euler without damping: unstable at every h
};

struct CriticalStep {
  StepLimit limit = StepLimit::bounded;
  double h_s = std::numeric_limits<double>::infinity();  // bounded only
};

// The largest stable step of `method` on the mode q̈ = −ω² q − α q̇ (ω = omega_rad_s > 0,
// α = damping_1_s ≥ 0), i.e. on a system whose fastest mode is ω (see the top of this file):
//   symplectic Euler      (√(α² + 4ω²) − α)/ω²   (= 2/ω undamped; from |tr| < 1 + det of its
//                         2×2 amplification matrix, det = 1 − hα, tr = 2 − hα − h²ω²)
//   velocity Verlet       2/ω    (undamped value; mass damping moves it by O(α/ω) relative)
//   central difference    2/ω    (exactly, with its centred damping: det = (1−αh/2)/(1+αh/2),
//                         tr = 1 + det − h²ω²/(1+αh/2), and |tr| < 1 + det ⟺ h²ω² < 4)
//   RK4                   2√2/ω  (undamped value: |R(iy)|² = 1 − y⁶/72 + y⁸/576 ≤ 1 ⟺ y ≤ 2√2)
//   explicit Euler        α/ω² when the mode is underdamped (α < 2ω), always_unstable when
//                         α = 0. Derivation: it multiplies the mode by R = 1 + hμ per step,
//                         μ the roots of μ² + αμ + ω² = 0; underdamped, Re μ = −α/2 and
//                         |μ|² = ω², so |R|² = 1 − hα + h²ω² < 1 ⟺ h < α/ω². Overdamped
//                         (α ≥ 2ω), μ is real and h < 2/|μ₋|, μ₋ = −α/2 − √(α²/4 − ω²).
//                         (On a whole system a slower overdamped mode is stricter, down to 2/α
//                         for ω → 0, when α² > 2ω_max²; cloth has α ≪ ω_max.)
//   implicit Euler        always_stable.
// Throws std::invalid_argument for ω ≤ 0 or α < 0.
CriticalStep predicted_critical_step(sim::Integrator method, double omega_rad_s,
                                     double damping_1_s = 0.0);

// --- 3. blow-up test and observed critical step ---------------------------------------------

// One step of an integrator on a fixed system: advances x (m) and v (m/s) by h_s. Returns
// false when the step failed (implicit Euler's linear solve), which counts as a blow-up.
using StepFunction = std::function<bool(sim::Matrix3X& x, sim::Matrix3X& v, double h_s)>;
// Makes a fresh stepper for each run (central difference remembers its previous step).
using StepperFactory = std::function<StepFunction()>;

// The integrator `method` on `system` (make_time_integrator; implicit Euler by a direct solve).
// dynamic_relaxation, which does not integrate physical time, is a bug (base::InternalError).
StepperFactory stepper_factory(sim::Integrator method, sim::System system);

struct BlowUpSettings {
  long steps = 1000;             // steps per run (fewer if it blows up first)
  double perturbation_m = 1e-7;  // each free coordinate starts displaced uniformly in [−a, a]
  // Blown up when the mass-weighted RMS displacement ‖u‖_M = √(Σ m_i |x_i − x₀_i|²) exceeds
  // this factor times its start value, or any position or velocity is not finite.
  double growth_factor = 1e3;
  std::uint64_t seed = 1;        // of the perturbation
};

struct BlowUpResult {
  bool stable = true;
  long steps_run = 0;
  double max_growth = 1.0;  // largest ‖u‖_M over the run / its start value (inf: non-finite)
};

// Runs `step` at h_s from x_rest (#V×3, m) plus a seeded perturbation of the free vertices
// (inv_mass > 0), starting at rest. Linear near rest when the perturbation times the growth
// factor stays ≪ the edge lengths (the defaults: 0.1 mm at most).
[[nodiscard]] BlowUpResult run_blow_up_test(const StepFunction& step, const sim::Matrix3X& x_rest,
                                            const Eigen::VectorXd& mass_kg,
                                            const Eigen::VectorXd& inv_mass, double h_s,
                                            const BlowUpSettings& settings = {});

struct CriticalStepSearch {
  bool bracketed = false;  // found a stable step below an unstable one
  double stable_h_s = 0.0;    // the largest step found stable
  double unstable_h_s = 0.0;  // the smallest step found to blow up
  int runs = 0;
  double h_s() const;  // √(stable · unstable): the observed critical step
};

// The observed critical step by bisection on log h: brackets it starting from [h/2, 2h]
// around the guess (widening by 4× up to 8 times), then halves the bracket until
// unstable/stable ≤ 1 + relative_tolerance. Assumes stability is monotone in h (true for
// the explicit integrators on a linear system).
[[nodiscard]] CriticalStepSearch find_critical_step(
    const StepperFactory& make_stepper, const sim::Matrix3X& x_rest, const Eigen::VectorXd& mass_kg,
    const Eigen::VectorXd& inv_mass, double guess_h_s, const BlowUpSettings& settings = {},
    double relative_tolerance = 1e-3);

// --- the standard cloth of `weft stability` -------------------------------------------------

// A 1 m × 1 m sheet of sim::Material (Kang & Yu wool) on an n × n grid, flat in the z = 0
// plane, pinned at the two corners of its v = 1 edge (as the default scene), every rigidity
// (stretch, shear, bending) multiplied by stiffness_scale; no gravity. Not movable: the
// steppers refer to its model.
class StabilityCloth {
 public:
  // Throws std::invalid_argument for n < 3 or stiffness_scale ≤ 0.
  StabilityCloth(sim::Index n, double stiffness_scale);
  StabilityCloth(const StabilityCloth&) = delete;
  StabilityCloth& operator=(const StabilityCloth&) = delete;

  const sim::ClothMesh& mesh() const { return m_mesh; }
  const sim::Material& material() const { return m_material; }
  const std::vector<sim::Index>& pinned() const { return m_pinned; }
  const sim::MassSpringModel& model() const { return *m_model; }
  const Eigen::VectorXd& mass_kg() const { return m_mass_kg; }
  const Eigen::VectorXd& inv_mass() const { return m_inv_mass; }  // 0 at the pins
  const sim::Matrix3X& rest_positions() const { return m_mesh.rest_positions; }
  InternalForces forces() const;  // the model's springs and bending
  // Its System (no gravity) with mass damping α.
  sim::System system(double damping_1_s) const;

  // λ_max(M⁻¹K) at rest.
  [[nodiscard]] LargestEigenvalue largest_eigenvalue(const EigenvalueSettings& s = {}) const;
  // A fresh stepper of `method` (implicit Euler included) with mass damping α.
  StepperFactory stepper_factory(sim::Integrator method, double damping_1_s) const;

 private:
  sim::ClothMesh m_mesh;
  sim::Material m_material;
  std::vector<sim::Index> m_pinned;
  std::unique_ptr<sim::MassSpringModel> m_model;
  Eigen::VectorXd m_mass_kg, m_inv_mass;
};

}  // namespace weft::analysis
