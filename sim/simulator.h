#pragma once
// The time stepper: Simulator::step() is a list of named, timed phases.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/diagnostics.h"
#include "sim/grid.h"
#include "sim/material.h"
#include "sim/mass_spring.h"
#include "sim/state.h"

namespace weft::sim {

enum class Integrator { symplectic_euler };

struct SimSettings {
  Integrator integrator = Integrator::symplectic_euler;
  Vec3 gravity_m_s2{0.0, 0.0, -9.81};
  double air_damping_1_s = 0.5;        // mass-proportional damping α: f = −α m v (seed 002 eq. 27)
  std::optional<double> time_step_s;   // empty: automatic, from the critical step
  // Automatic step = safety × the critical step estimated from a Gershgorin bound on the
  // largest eigenvalue of M⁻¹K (an upper bound, so 1.0 is still stable at rest; measured: the
  // default scene is stable up to 1.2 and explodes at 1.5).
  double time_step_safety = 0.8;
  // Divergence guard: a non-finite position or velocity, or any vertex faster than this (an
  // explosion, not physics: free fall reaches 100 m/s only after 10 s).
  double max_speed_m_s = 200.0;
};

// Thrown when the simulation diverges; carries where and what.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(long step, double time_s, std::string quantity);
  long step() const { return m_step; }
  double time_s() const { return m_time_s; }
  const std::string& quantity() const { return m_quantity; }

 private:
  long m_step;
  double m_time_s;
  std::string m_quantity;
};

class Simulator {
 public:
  Simulator(ClothMesh mesh, const Material& material, std::vector<Index> pinned,
            const SimSettings& settings);

  // Advances by exactly dt_s, in substeps of at most time_step(). Throws DivergenceError.
  void advance(double dt_s);
  // One step of h seconds: predict → forces → integrate → diagnostics.
  void step(double h_s);

  const State& state() const { return m_state; }
  const ClothMesh& mesh() const { return m_mesh; }
  const MassSpringModel& model() const { return m_model; }
  const Eigen::VectorXd& masses_kg() const { return m_mass_kg; }
  double time_step() const { return m_time_step_s; }
  double critical_time_step() const { return m_critical_step_s; }
  long steps_taken() const { return m_steps; }
  Diagnostics diagnostics() const;
  const PhaseTimers& timers() const { return m_timers; }

 private:
  void compute_forces();
  void integrate(double h_s);
  void check_finite() const;

  ClothMesh m_mesh;
  MassSpringModel m_model;
  SimSettings m_settings;
  std::vector<Index> m_pinned;
  Eigen::VectorXd m_mass_kg;       // #V lumped masses
  Eigen::VectorXd m_inv_mass;      // #V, 0 for pinned vertices
  State m_state;
  Matrix3X m_forces;               // #V×3 scratch, N
  double m_critical_step_s = 0.0;
  double m_time_step_s = 0.0;
  long m_steps = 0;
  PhaseTimers m_timers;
};

}  // namespace weft::sim
