#pragma once
// An adaptive time step for inextensible cloth (implicit Euler followed by fast projection), so
// that a user need not guess `time_step`: each step's length follows what the last one cost.
//
// What makes a step of fast projection expensive is its projection: each Newton iteration
// refills and usually refactorizes the constraint matrix, and the implicit solve's conjugate
// gradients need more iterations at longer steps too. So the step grows while its projection
// converges in at most one iteration, holds at two, and shrinks from three on (faster still
// when the projection misses its tolerance) — the count of iterations, not a timer, so the
// chosen steps are the same bits on every machine. A prediction far from the constraints
// (the flat start: the row below a pinned edge drops by g h²) is not projected at all: a step
// whose unconstrained prediction strains an edge beyond `max_prediction_strain` is undone and
// redone shorter — strain grows as h², so at h √(0.9 ε_max/ε) — at the cost of one
// unconstrained step. Steps land exactly on the end of each advance() (a frame): the remaining
// time is split into equal steps no longer than the planned one.
//
// Measured (docs/inextensibility.md, "Adaptive step"): a prediction strain alone is a poor
// guide — at 128² steps chosen from it cost more than the fixed 1/120 s — and projection
// iterations are what the fixed steps that pay best have in common (about one per step).

#include "sim/sim_settings.h"

namespace weft::sim {

class AdaptiveStep {
 public:
  // Throws std::invalid_argument naming the setting when 0 < min ≤ max and ε* > 0 do not hold.
  explicit AdaptiveStep(const AdaptiveStepSettings& settings);

  // The length of the next step, at most `remaining_s`: the remaining time split into equal
  // steps no longer than the controller's next step.
  double next_step(double remaining_s) const;
  // Whether a step of h_s whose prediction had the largest strain `strain` is to be redone
  // shorter (then the planned step is shortened; otherwise it is left as it is).
  bool reject(double h_s, double strain);
  // After a step of h_s whose projection took `iterations` Newton iterations and met its
  // tolerance or not: plans the next step's length.
  void accept(double h_s, int iterations, bool converged);
  const AdaptiveStepSettings& settings() const { return m_settings; }
  double planned_step_s() const { return m_next_s; }
  void set_planned_step_s(double h_s) { m_next_s = h_s; }  // a checkpoint's

 private:
  AdaptiveStepSettings m_settings;
  double m_next_s;
};

}  // namespace weft::sim
