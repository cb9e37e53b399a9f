#pragma once
// Explicit time steppers for lumped-mass dynamics with gravity and mass-proportional air
// damping (seed 002 eq. 27):
//   M ẍ = F(x, ẋ) = f(x) + f_v(x, ẋ, t) + M (g − α ẋ),     a(x, v) = M⁻¹ F(x, v),
// where f(x) are the System's force terms (springs, bending, membranes, carried constraint
// tension) and f_v its velocity-dependent ones (air drag, at the step's start time t). Pinned vertices have inverse mass 0: their
// acceleration is 0, so, started at rest, they never move. With step h:
//
//   symplectic Euler    v ← v + h a(x, v),  x ← x + h v                         1 force eval
//   explicit Euler      x ← x + h v_n,  v ← v_n + h a(x_n, v_n) (both from the old state)
//                                                                                1 force eval
//   RK4                 the classic 4-stage Runge–Kutta on y = (x, v), ẏ = (v, a(x, v))
//                                                                                4 force evals
//   velocity Verlet     v½ = v + ½h a(x_n, v_n),  x ← x + h v½,  v ← v½ + ½h a(x_{n+1}, v½)
//                       (kick–drift–kick; the second kick's damping uses the half-step
//                       velocity v½, which keeps it explicit; exact Verlet when α = 0)
//                                                                                2 force evals
//   central difference  v_{n+½} = ((1 − α h/2) v_{n−½} + h M⁻¹(f(x_n) + M g)) / (1 + α h/2),
//                       x_{n+1} = x_n + h v_{n+½}                                1 force eval
//
// Central difference is seed 002's explicit scheme (Zhou & Sze, eqs. 20–22: D̈_n from the
// forces at D_n, Ḋ_{n+½} = Ḋ_{n−½} + Δt D̈_n, D_{n+1} = D_n + Δt Ḋ_{n+½}). The paper lags the
// damping force half a step (its eq. 19, "asynchronous damping": F_damp(Ḋ_{n−½})); weft centres
// it, −α M (v_{n−½} + v_{n+½})/2, which stays explicit because M is diagonal and keeps the
// scheme second order with damping. Its velocities are staggered: on entry v holds v_{n−½}, on
// return v_{n+½} = (x_{n+1} − x_n)/h. The first step (and every step after a change of h) kicks
// by the mean of the previous and the current step, h̄ = (h_prev + h)/2, with h_prev = 0 at the
// start: v_{½} from the synchronous initial v_0 by a half kick (Belytschko's start).
//
// Stability on an undamped linear oscillator ẍ = −ω² x (amplification factor |R(ihω)| ≤ 1):
// symplectic Euler, velocity Verlet and central difference for hω ≤ 2; RK4 for hω ≤ 2√2
// (|R(iy)|² = 1 − y⁶/72 + y⁸/576; 2.785 is its bound on the negative real axis, not this one);
// explicit Euler never (|1 + ihω|² = 1 + h²ω²: the energy grows at every h).

#include "sim/integrators/time_integrator.h"
#include "sim/types.h"

namespace weft::sim {

class ExplicitStepper final : public TimeIntegrator {
 public:
  // implicit_euler, dynamic_relaxation or an inconsistent system is a bug (base::InternalError).
  ExplicitStepper(Integrator method, const System& system);

  // Central difference: state.v is the half-step velocity (see above).
  using TimeIntegrator::step;
  StepReport step(const System& system, State& state, double h_s) override;

  Integrator method() const override { return m_method; }
  void save_state(StateWriter& out) const override;
  void restore_state(StateReader& in) override;
  // Internal-force evaluations per step: 1, or 2 (velocity Verlet), or 4 (RK4).
  int force_evaluations_per_step() const;

 private:
  // F = f(x) + f_v(x, v, t) + M (g − α v) with damping α, N.
  void total_forces(const System& system, const Matrix3X& x, const Matrix3X& v, double time_s,
                    double damping_1_s, Matrix3X& F);
  // v += (h M⁻¹) F on the free vertices.
  static void kick(const System& system, double h_s, const Matrix3X& F, Matrix3X& v);
  void rk4_step(const System& system, State& state, double h_s);
  void central_difference_step(const System& system, State& state, double h_s);

  Integrator m_method;
  double m_previous_h_s = 0.0;                // central difference: 0 before the first step
  Matrix3X m_force;                           // #V×3 scratch, N
  Matrix3X m_x_stage, m_v_stage, m_dx, m_dv;  // RK4 and velocity Verlet scratch
};

}  // namespace weft::sim
