#pragma once
// The time integrators a simulation can use, and their names in scene files
// (simulation.integrator; docs/models.md § Integrator has the update formulas).

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/enum_names.h"

namespace weft::sim {

enum class Integrator {
  symplectic_euler,    // v ← v + h a(x, v), x ← x + h v            (explicit, order 1)
  implicit_euler,      // one Newton step of backward Euler         (implicit_euler.h)
  explicit_euler,      // x ← x + h v, v ← v + h a(x, v), both from the old state (order 1)
  rk4,                 // classic 4-stage Runge–Kutta on (x, v)     (order 4)
  velocity_verlet,     // kick–drift–kick                           (order 2)
  central_difference,  // seed 002 eqs. 20–22, staggered velocities (order 2)
  dynamic_relaxation,  // static equilibrium in pseudo-time: fictitious masses, kinetic damping
                       // (dynamic_relaxation.h); not a physical-time integrator
};

inline constexpr std::array<Integrator, 7> all_integrators{
    Integrator::symplectic_euler, Integrator::implicit_euler,
    Integrator::explicit_euler,   Integrator::rk4,
    Integrator::velocity_verlet,  Integrator::central_difference,
    Integrator::dynamic_relaxation};

// False for dynamic relaxation, whose steps are iterations toward the static equilibrium, not
// motion in time: stability maps and time-accuracy tests skip it.
inline constexpr bool integrates_physical_time(Integrator integrator) {
  return integrator != Integrator::dynamic_relaxation;
}

// True for the integrators whose step is bounded by the critical step (their step is fixed
// from the mesh's stiffness): all but implicit Euler and dynamic relaxation.
inline constexpr bool is_explicit(Integrator integrator) {
  return integrator != Integrator::implicit_euler &&
         integrator != Integrator::dynamic_relaxation;
}

// all_integrators without dynamic relaxation, in the same order.
inline std::vector<Integrator> physical_time_integrators() {
  std::vector<Integrator> result;
  for (Integrator i : all_integrators)
    if (integrates_physical_time(i)) result.push_back(i);
  return result;
}

// The scene-file names of the integrators, in all_integrators' order.
inline constexpr base::EnumNames<Integrator, 7> integrator_names{{
    {Integrator::symplectic_euler, "symplectic_euler"},
    {Integrator::implicit_euler, "implicit_euler"},
    {Integrator::explicit_euler, "explicit_euler"},
    {Integrator::rk4, "rk4"},
    {Integrator::velocity_verlet, "velocity_verlet"},
    {Integrator::central_difference, "central_difference"},
    {Integrator::dynamic_relaxation, "dynamic_relaxation"}}};

// The scene-file name of an integrator.
inline const char* integrator_name(Integrator integrator) {
  return base::enum_name(integrator_names, integrator);
}

}  // namespace weft::sim
