#pragma once
// Dynamic relaxation (DR): the static equilibrium f(x) + M g = 0 of a cloth (a drape at rest),
// found by an explicit pseudo-dynamic iteration whose inertia is fictitious. Only the final
// state means anything; the path to it is not physical motion.
//
// The iteration is central difference (seed 002 eqs. 20–22) on M̃ ẍ = R(x) = f(x) + M g, with
// the residual (out-of-balance force) R, N: the load stays the physical weight M g, only the
// inertia is scaled to the fictitious masses M̃:
//   v_{n+½} = v_{n−½} + h M̃⁻¹ R(x_n),   x_{n+1} = x_n + h v_{n+½}       1 force evaluation
// (Day 1965, "An introduction to dynamic relaxation", The Engineer 219; Underwood 1983,
// "Dynamic relaxation", ch. 5 of Belytschko & Hughes (eds.), Computational Methods for
// Transient Analysis; Barnes 1999, "Form finding and analysis of tension structures by dynamic
// relaxation", Int. J. Space Structures 14(2).)
//
// Mass scaling. Central difference is stable for h ω_max ≤ 2, and ω_max² = λ_max(M̃⁻¹K) is at
// most max_i bound_i / m̃_i by Gershgorin, with bound_i ≥ Σ_j |K_ij| the row bound of the
// stiffness (N/m, System::stiffness_row_bound: each ForceTerm's add_stiffness_row_bound). So
//   m̃_i = s · (h² / 4) · bound_i,   s = mass_safety ≥ 1,
// makes h stable at every vertex, whatever the physical masses (Underwood 1983's
// m_ii ≥ (h²/4) Σ_j |k_ij|; Rezaiee-Pajand & Alamatian 2010, "The dynamic relaxation method
// using new formulation for fictitious mass and damping", Structural Engineering and Mechanics
// 34(1), compare such choices). It also equalises every vertex's local
// frequency at about 2/(h √s), which is what speeds the relaxation of stiff, non-uniform meshes.
// The bound is taken at rest; s > 1 leaves room for the stiffness changing as the cloth deforms.
//
// Kinetic damping (Cundall 1976; Barnes 1999; Topping & Khan 1996, "Parallel finite element
// computations", ch. on DR). Without any viscous damping the total fictitious kinetic energy
// T = ½ Σ m̃_i |v_i|² rises while x moves toward a minimum of the potential energy along its
// path. When T_{n+½} < T_{n−½} the peak has passed: x is set back to the estimated peak
// position x* = x_n − (h/2) v_{n−½} (the midpoint of x_{n−1} and x_n, where the largest
// velocity was measured; the standard x* = x_{n+1} − (3/2) h v_{n+½} + (h²/2) M̃⁻¹ R_n is the same
// point), every velocity is zeroed, and the next step restarts with a half kick
// v_{½} = (h/2) M̃⁻¹ R(x*). Air damping (System::damping_1_s) is not used; velocity-dependent
// forces (System::velocity_terms: air drag, wind) are evaluated at zero velocity, i.e. the
// steady load of the wind on a cloth at rest.
//
// Convergence is reported as the residual norm relative to the load, ‖R‖ / ‖M g‖ over the free
// vertices (pins carry reactions, which are not out of balance), and the fictitious kinetic
// energy. Contact forces of obstacles (a push-out after the step, not a force) are not part of
// R: a drape resting on an obstacle keeps a residual of the order of the weight it rests there.
//
// Pinned vertices (inverse mass 0) get no kick; they move by h v like in the other steppers
// (v = 0 for fixed pins) and are not set back at a kinetic-energy peak.

#include <Eigen/Core>

#include "sim/integrators/time_integrator.h"
#include "sim/types.h"

namespace weft::sim {

// m̃_i = mass_safety · (h_s² / 4) · row_bound_i, kg, for #V row bounds (N/m). A vertex with a
// zero bound (no stiffness: nothing limits its step) keeps its physical mass. Mismatched sizes,
// h_s ≤ 0, mass_safety < 1 or a negative bound are bugs (base::InternalError).
Eigen::VectorXd fictitious_masses_kg(const Eigen::VectorXd& row_bound_N_m,
                                     const Eigen::VectorXd& mass_kg, double h_s,
                                     double mass_safety);

// ½ Σ m_i |v_i|² over the vertices with inv_mass > 0, J (with fictitious masses: pseudo-J).
double free_kinetic_energy_J(const Eigen::VectorXd& mass_kg, const Eigen::VectorXd& inv_mass,
                             const Matrix3X& v);

// ‖R‖ / ‖M g‖ over the vertices with inv_mass > 0 (Frobenius norms of the #V×3 blocks); the
// absolute ‖R‖ in N when there is no load (g = 0 or no free vertex).
double relative_residual(const Matrix3X& residual_N, const Eigen::VectorXd& mass_kg,
                         const Eigen::VectorXd& inv_mass, const Vec3& gravity_m_s2);

struct RelaxationSettings {
  double mass_safety = 1.5;  // s in m̃_i = s (h²/4) bound_i; ≥ 1
};

// Where the relaxation stands after a step.
struct RelaxationStatus {
  long iterations = 0;         // steps (= internal-force evaluations) so far
  long kinetic_peaks = 0;      // kinetic-damping resets so far
  bool reset = false;          // this step was a kinetic-damping reset (v is now 0)
  double residual = 0.0;       // ‖R(x_n)‖ / ‖M g‖ at the start of the last step
  double kinetic_energy_J = 0.0;  // fictitious ½ Σ m̃ |v|² after the last step
};

class DynamicRelaxation final : public TimeIntegrator {
 public:
  // `system` gives the forces, the physical masses (the load M g), the pins (inv_mass 0),
  // gravity and the stiffness row bounds (System::stiffness_row_bound at construction); the
  // fictitious masses are made stable for every step up to h_max_s. Misuse is a bug
  // (base::InternalError).
  DynamicRelaxation(const System& system, double h_max_s, RelaxationSettings settings = {});

  // One iteration on positions state.x (m) and half-step velocities state.v (m per
  // pseudo-second), #V×3, with 0 < h_s ≤ h_max_s. v may have been changed since the last step
  // (the Simulator's velocity filter after collisions); the kinetic energy before the step is
  // taken from it. The report's kinetic_reset is status().reset.
  using TimeIntegrator::step;
  StepReport step(const System& system, State& state, double h_s) override;
  Integrator method() const override { return Integrator::dynamic_relaxation; }
  void save_state(StateWriter& out) const override;
  void restore_state(StateReader& in) override;

  // Steps with h_max_s until the relative residual is ≤ tolerance or max_iterations were run.
  const RelaxationStatus& relax(const System& system, Matrix3X& x, Matrix3X& v, double tolerance,
                                long max_iterations);

  const Eigen::VectorXd& fictitious_mass_kg() const { return m_fictitious_mass_kg; }
  const RelaxationStatus& status() const { return m_status; }
  double max_step_s() const { return m_h_max_s; }

 private:
  RelaxationSettings m_settings;
  double m_h_max_s;
  Eigen::VectorXd m_fictitious_mass_kg;  // #V, kg
  bool m_restart = true;                 // the next kick is a half kick (start, after a reset)
  RelaxationStatus m_status;
  Matrix3X m_residual;    // #V×3 scratch, N
  Matrix3X m_v_previous;  // #V×3 scratch: v_{n−½}
  Matrix3X m_zero_velocity;  // #V×3 zeros: velocity-dependent forces at rest
};

}  // namespace weft::sim
