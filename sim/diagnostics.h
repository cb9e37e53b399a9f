#pragma once
// Per-frame measurements of a simulation, and the time spent in each phase of a step.

#include <array>
#include <string_view>

#include "base/timer.h"

namespace weft::sim {

struct Diagnostics {
  double time_s = 0.0;
  double kinetic_energy_J = 0.0;
  double elastic_energy_J = 0.0;
  double gravity_energy_J = 0.0;    // −Σ m g·x, relative to the origin
  double max_strain = 0.0;          // largest |length/rest − 1| over warp and weft edges
  double mean_strain = 0.0;         // mean |length/rest − 1| over warp and weft edges
  double max_speed_m_s = 0.0;
  double total_energy_J() const { return kinetic_energy_J + elastic_energy_J + gravity_energy_J; }
};

// The phases of Simulator::step() (forces: the force evaluations inside integrate).
// What the steps since the last Simulator::take_step_statistics() did.
struct StepStatistics {
  long steps = 0;
  long projection_iterations = 0;     // summed over steps
  long projection_factorizations = 0; // numeric factorizations of fast projection's matrix
  long projection_reuse_iterations = 0;  // its CG iterations on a reused factorization
  int max_projection_iterations = 0;  // in any one step
  long unconverged_steps = 0;         // steps whose projection missed its tolerance
  double worst_projected_strain = 0.0;
  double solve_s = 0.0;               // linear solves (implicit Euler and fast projection)
  long failed_implicit_solves = 0;
  long cg_iterations = 0;             // implicit Euler by conjugate gradients, summed over steps
  long max_self_contacts = 0;         // self-collision contacts in any one step
  long max_impact_zone_vertices = 0;  // vertices in self-collision's impact zones, any one step
  long unresolved_impact_steps = 0;   // steps whose impact zones hit their pass limit
  double min_step_s = 0.0, max_step_s = 0.0;  // the shortest and longest step (0: none taken)
  long rejected_steps = 0;  // adaptive steps redone shorter (sim/adaptive_step.h)
  long remeshes = 0;        // adaptive remeshing steps (simulation.remesh)
  double remesh_energy_J = 0.0;  // the total energy's change by those remeshes (transfer, push-out and relaxation)
  // The largest remesh criterion max |κ|h² at the indicator checks, metres (0: none checked).
  double max_remesh_indicator_m = 0.0;
  // With simulation.remesh.coarsen: the largest refinement excess at those checks relative to
  // its value just after the last remesh (remesh when it passes coarsen; 0: none checked).
  double max_remesh_excess = 0.0;
  long coarsenings = 0;  // of the remeshes, those the coarsening criterion asked for
};

enum class Phase {
  forces, integrate, project, collide, check, pins, obstacles, filter, remesh, count
};

inline constexpr std::array<std::string_view, static_cast<int>(Phase::count)> phase_names{
    "forces", "integrate", "project", "collide", "check", "pins", "obstacles", "filter", "remesh"};

// Accumulated wall time per phase, seconds. Exclusive: time spent in a phase timed inside
// another (forces inside integrate) counts for the inner phase only.
class PhaseTimers {
 public:
  template <class F>
  auto time(Phase phase, F&& work) {
    struct Stop {
      PhaseTimers* timers;
      Phase phase;
      int outer;
      base::Stopwatch watch;
      ~Stop() {
        const double s = watch.seconds();
        timers->m_seconds[static_cast<int>(phase)] += s;
        if (outer >= 0) timers->m_seconds[outer] -= s;
        timers->m_running = outer;
      }
    } stop{this, phase, m_running, base::Stopwatch()};
    m_running = static_cast<int>(phase);
    return work();
  }
  double seconds(Phase phase) const { return m_seconds[static_cast<int>(phase)]; }
  double total_seconds() const {
    double t = 0.0;
    for (double s : m_seconds) t += s;
    return t;
  }

 private:
  std::array<double, static_cast<int>(Phase::count)> m_seconds{};
  int m_running = -1;  // the phase being timed, −1: none
};

}  // namespace weft::sim
