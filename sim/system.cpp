#include "sim/system.h"

#include <string>

#include "base/check.h"

namespace weft::sim {

void System::add_forces(const Matrix3X& x, Matrix3X& f) const {
  const auto add = [&] {
    for (const auto& term : terms) term->add_forces(x, f);
  };
  if (timers) {
    timers->time(Phase::forces, add);
  } else {
    add();
  }
}

void System::add_velocity_forces(const Matrix3X& x, const Matrix3X& v, double time_s,
                                 Matrix3X& f) const {
  const auto add = [&] {
    for (const auto& term : velocity_terms) term->add_forces(x, v, time_s, f);
  };
  if (timers) {
    timers->time(Phase::forces, add);
  } else {
    add();
  }
}

double System::energy(const Matrix3X& x) const {
  double e = 0.0;
  for (const auto& term : terms) e += term->energy(x);
  return e;
}

Eigen::VectorXd System::stiffness_row_bound() const {
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(vertex_count());
  for (const auto& term : terms) term->add_stiffness_row_bound(bound);
  return bound;
}

void System::check() const {
  // Misuse is a bug in the caller, checked in release builds too.
  WEFT_CHECK(mass_kg.size() == inv_mass.size(),
             "System: " + std::to_string(mass_kg.size()) + " masses but " +
                 std::to_string(inv_mass.size()) + " inverse masses");
  WEFT_CHECK(damping_1_s >= 0.0,
             "System: negative damping " + std::to_string(damping_1_s) + " 1/s");
}

}  // namespace weft::sim
