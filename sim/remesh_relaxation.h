#pragma once
// Relaxing a remeshed cloth's new vertices (docs/remeshing.md "Relaxing the new
// vertices"). A remesh keeps its old boundary vertices and pins and interpolates every other
// vertex from the old mesh; where the cloth folds more sharply than the old mesh resolved, no
// interpolation knows where the surface is, so the new vertices come out strained against the
// stiff membrane, and the dynamics would turn that energy into motion. This moves them, with
// the held vertices still, towards the minimum of the cloth model's own elastic energy (the
// System's force terms: membrane and bending; no gravity, no damping, no velocity terms):
// damped Newton steps, each one implicit Euler step from rest of the elastic terms alone,
//   (M + h² K) Δx = h² f(x),   K = −∂f/∂x (PSD-projected),
// taken only as far as it lowers the energy (halved up to kMaxHalvings times, else stopped).
// M/h² keeps each step local (a proximal term) and K makes it Newton's where the cloth is stiff.
// Velocities are not touched. Single-threaded up to the linear solve, which is deterministic.

#include <functional>
#include <vector>

#include "sim/integrators/time_integrator.h"
#include "sim/system.h"
#include "sim/types.h"

namespace weft::sim {

struct RelaxationReport {
  double energy_before_J = 0.0;  // the elastic energy at the start
  double energy_after_J = 0.0;   // and at the end (never more)
  int steps = 0;                 // accepted steps
};

// Moves the vertices with free[i] != 0 (and a mass) of x (#V×3) by at most `iterations` steps
// of h_s seconds as above; the others stay bit for bit. `system` gives the masses and terms.
// `constrain`, when given, is applied to each trial position before its energy is taken (the
// obstacles' push-out: a projected Newton step).
RelaxationReport relax_vertices(const System& system, const std::vector<char>& free,
                                Matrix3X& x, int iterations, double h_s,
                                const ImplicitSolveSettings& solve,
                                const std::function<void(Matrix3X&)>& constrain = {});

}  // namespace weft::sim
