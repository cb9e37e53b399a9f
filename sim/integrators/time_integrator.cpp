#include "sim/integrators/time_integrator.h"

#include <utility>

#include "sim/integrators/dynamic_relaxation.h"
#include "sim/integrators/explicit_steppers.h"
#include "sim/integrators/implicit_euler.h"

namespace weft::sim {

StepReport TimeIntegrator::step(const System& system, Matrix3X& x, Matrix3X& v, double h_s,
                                double time_s) {
  State state;
  state.x.swap(x);  // no copies: the matrices move in and back out
  state.v.swap(v);
  state.time_s = time_s;
  struct SwapBack {
    State& state;
    Matrix3X& x;
    Matrix3X& v;
    ~SwapBack() {
      x.swap(state.x);
      v.swap(state.v);
    }
  } swap_back{state, x, v};
  return step(system, state, h_s);
}

std::unique_ptr<TimeIntegrator> make_time_integrator(Integrator method, const System& system,
                                                     const IntegratorSettings& settings) {
  switch (method) {
    case Integrator::implicit_euler:
      return std::make_unique<ImplicitEuler>(system, settings.implicit_solve);
    case Integrator::dynamic_relaxation:
      return std::make_unique<DynamicRelaxation>(system, settings.relaxation_max_step_s);
    default:
      return std::make_unique<ExplicitStepper>(method, system);
  }
}

}  // namespace weft::sim
