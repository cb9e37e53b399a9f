#pragma once
// The physical system an integrator steps (sim/integrators/time_integrator.h): lumped masses,
// gravity, mass-proportional damping and a list of force terms — springs, bending, membranes,
// carried constraint tension (ForceTerm) and air drag (VelocityForceTerm) — with pins as
// vertices of inverse mass 0.
//   M ẍ = f(x) + f_v(x, ẋ, t) + M (g − α ẋ)
// Integrators read it and never change it; the Simulator builds it once (sim/simulator.cpp)
// and keeps it, updating only the carried tension between steps.

#include <vector>

#include "sim/diagnostics.h"
#include "sim/force_term.h"
#include "sim/types.h"

namespace weft::sim {

// A vertex resting on an obstacle at the start of a step: within the collision thickness of
// its surface (where the collide phase leaves it) and, in free flight over the step, moving
// into it (ContactsAndConstraints::resting_contacts). The implicit solve holds its velocity
// along `normal` at zero (sim/integrators/implicit_euler.h): the obstacle's normal force acts
// within the solve, as Baraff & Witkin 1998 §5 constrain a vertex in contact.
struct ObstacleContact {
  Index vertex = 0;
  Vec3 normal = Vec3::UnitZ();  // unit, out of the obstacle
};

struct System {
  Eigen::VectorXd mass_kg;   // #V lumped masses, kg
  Eigen::VectorXd inv_mass;  // #V, 1/kg; 0 for pinned (and unused, massless) vertices
  Vec3 gravity_m_s2 = Vec3::Zero();
  double damping_1_s = 0.0;  // α ≥ 0: f = −α m v at every vertex (seed 002 eq. 27)
  ForceTerms terms;                   // position-dependent: f(x) = −∇E(x)
  // The resting contacts of the next step (the Simulator sets them before each step when
  // simulation.resting_contacts is on; only implicit Euler reads them).
  std::vector<ObstacleContact> contacts;
  VelocityForceTerms velocity_terms;  // f_v(x, v, t): drag and wind
  // Optional: force evaluations are timed as Phase::forces here (the Simulator's timers).
  PhaseTimers* timers = nullptr;

  Index vertex_count() const { return static_cast<Index>(mass_kg.size()); }
  // f += Σ f(x) over the terms, in order, N.
  void add_forces(const Matrix3X& x, Matrix3X& f) const;
  // f += Σ f_v(x, v, t) over the velocity-dependent terms, N.
  void add_velocity_forces(const Matrix3X& x, const Matrix3X& v, double time_s, Matrix3X& f) const;
  bool has_velocity_forces() const { return !velocity_terms.empty(); }
  // Σ E(x) over the terms, J.
  double energy(const Matrix3X& x) const;
  // #V upper bounds on the block rows of the rest stiffness at the terms' current state, N/m
  // (ForceTerm::add_stiffness_row_bound): ω_max² ≤ max_i bound_i / m_i (Gershgorin).
  Eigen::VectorXd stiffness_row_bound() const;
  // Mismatched sizes or a negative damping are bugs: WEFT_CHECK (base::InternalError).
  void check() const;
};

}  // namespace weft::sim
