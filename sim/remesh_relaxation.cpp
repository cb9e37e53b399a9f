#include "sim/remesh_relaxation.h"

#include <string>

#include "base/check.h"
#include "sim/integrators/implicit_euler.h"
#include "sim/state.h"

namespace weft::sim {

namespace {

constexpr int kMaxHalvings = 4;  // a step that does not lower the energy is halved this often

// The system the relaxation steps: the same masses and elastic terms, the held vertices pinned,
// nothing else (no gravity, damping, drag or contacts).
System relaxation_system(const System& system, const std::vector<char>& free) {
  System relax;
  relax.mass_kg = system.mass_kg;
  relax.inv_mass = system.inv_mass;
  for (Index i = 0; i < system.vertex_count(); ++i)
    if (!free[static_cast<std::size_t>(i)]) relax.inv_mass[i] = 0.0;
  relax.terms = system.terms;
  return relax;
}

}  // namespace

RelaxationReport relax_vertices(const System& system, const std::vector<char>& free,
                                Matrix3X& x, int iterations, double h_s,
                                const ImplicitSolveSettings& solve,
                                const std::function<void(Matrix3X&)>& constrain) {
  WEFT_CHECK(
      static_cast<Index>(free.size()) == system.vertex_count() && x.rows() == system.vertex_count(),
      "relax_vertices: " + std::to_string(free.size()) + " flags and " + std::to_string(x.rows()) +
          " positions for " + std::to_string(system.vertex_count()) + " vertices");
  RelaxationReport report;
  report.energy_before_J = report.energy_after_J = system.energy(x);
  if (iterations <= 0) return report;
  bool any_free = false;
  for (Index i = 0; i < system.vertex_count() && !any_free; ++i)
    any_free = free[static_cast<std::size_t>(i)] && system.inv_mass[i] > 0.0;
  if (!any_free) return report;
  const System relax = relaxation_system(system, free);
  ImplicitEuler newton(relax, solve);
  State state;
  state.v = Matrix3X::Zero(x.rows(), 3);
  double energy = report.energy_after_J;
  for (int k = 0; k < iterations; ++k) {
    state.x = x;
    state.v.setZero();
    if (!newton.step(relax, state, h_s).solved) break;
    const Matrix3X dx = state.x - x;
    bool lowered = false;
    double scale = 1.0;
    for (int halving = 0; halving <= kMaxHalvings && !lowered; ++halving, scale *= 0.5) {
      Matrix3X trial = x + scale * dx;
      if (constrain) constrain(trial);
      const double e = relax.energy(trial);
      if (e < energy) {
        x = trial;
        energy = e;
        lowered = true;
      }
    }
    if (!lowered) break;
    ++report.steps;
  }
  report.energy_after_J = energy;
  return report;
}

}  // namespace weft::sim
