#pragma once
// Backward (implicit) Euler, one Newton step per time step (Baraff & Witkin 1998): with
// K = −∂f/∂x of the System's force terms (sim/force_term.h; PSD-projected) and mass damping α,
//   (M (1 + h α) + h² K) Δv = h (f(x_n) + f_v(x_n, v_n, t_n) − α M v_n − h K v_n) + h M g,
//   v_{n+1} = v_n + Δv,   x_{n+1} = x_n + h v_{n+1}.
// A term without stiffness (the mass-spring model's angular bending: small, see
// docs/models.md) enters the right-hand side only; the velocity-dependent terms (air drag)
// likewise, taken explicitly at (x_n, v_n). Pair terms (springs, carried constraint tension:
// a tension k > 0 adds the stiffness k I) are assembled by their 3×3 block, the other terms by
// their element matrices. Pinned vertices (inv_mass = 0) keep v = 0. The sparsity pattern of
// the system matrix is fixed by the system's terms and pins and analysed once.

#include <memory>

#include "sim/integrators/time_integrator.h"
#include "sim/types.h"

namespace weft::sim {

class ImplicitEuler final : public TimeIntegrator {
 public:
  // The pattern comes from `system` (its terms' elements and its pins): step that system.
  ImplicitEuler(const System& system, const ImplicitSolveSettings& solve);
  ~ImplicitEuler() override;
  // Replaces state.v by v_{n+1} and state.x by x_n + h v_{n+1}; when the solve fails
  // (report.solved false) v is kept and x moves by h v_n.
  using TimeIntegrator::step;
  StepReport step(const System& system, State& state, double h_s) override;
  Integrator method() const override { return Integrator::implicit_euler; }
  void save_state(StateWriter& out) const override;
  void restore_state(StateReader& in) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace weft::sim
