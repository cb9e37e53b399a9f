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

enum class Phase { forces, integrate, project, collide, check, count };

inline constexpr std::array<std::string_view, static_cast<int>(Phase::count)> phase_names{
    "forces", "integrate", "project", "collide", "check"};

// Accumulated wall time per phase, seconds.
class PhaseTimers {
 public:
  template <class F>
  auto time(Phase phase, F&& work) {
    struct Stop {
      PhaseTimers* timers;
      Phase phase;
      base::Stopwatch watch;
      ~Stop() { timers->m_seconds[static_cast<int>(phase)] += watch.seconds(); }
    } stop{this, phase, base::Stopwatch()};
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
};

}  // namespace weft::sim
