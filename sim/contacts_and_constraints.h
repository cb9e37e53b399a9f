#pragma once
// The "contacts and constraints" phase of a step, after the unconstrained integration: the
// obstacles (posed at the step's end, with friction against their motion), the cloth against
// itself, and the inextensibility projection, which carries its tension into the next step's
// forces (a CarriedTensionTerm of the System).
//
// With a projection, push-out and projection alternate (block Gauss–Seidel over contacts and
// constraints), ending with a projection so that the step meets the tolerance; vertices may end
// up to the residual of the last push-out inside the collision thickness. A single push-out
// after the projection undid it where the cloth lies on an obstacle (measured on the
// inextensible sphere drape: 30 % strain). Friction acts in the first push-out only: later ones
// would drag contact vertices back toward their start positions.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sim/collision/impact_zones.h"
#include "sim/constraints/carried_tension.h"
#include "sim/constraints/projection.h"
#include "sim/diagnostics.h"
#include "sim/grid.h"
#include "sim/sim_settings.h"
#include "sim/system.h"

namespace weft::sim {

class ContactsAndConstraints {
 public:
  // inv_mass: #V, 0 at pins and unused vertices (the System's).
  ContactsAndConstraints(const ClothMesh& mesh, const Eigen::VectorXd& inv_mass,
                         const SimSettings& settings);
  ~ContactsAndConstraints();

  // The carried tension force term (null unless fast projection carries tension).
  std::shared_ptr<const ForceTerm> tension_term() const { return m_tension; }

  // Moves the obstacles to their poses at t1 and records each one's rigid motion t0 → t1,
  // which carries friction's start positions along (sim/collision/obstacle_motion.h).
  void pose_obstacles(double t0_s, double t1_s);
  // Corrects the positions x (#V×3, m) that a step of h_s seconds from x_start reached:
  // push-outs and projections, timed as Phase::collide and Phase::project, counted in stats.
  // True when x was changed (a projection ran or a contact moved a vertex). The failsafe
  // (impact zones) runs last over the paths from failsafe_from (the positions at the start of
  // its window of steps; x_start for one step); none: not at this step.
  bool resolve(const Matrix3X& x_start, Matrix3X& x, double h_s, PhaseTimers& timers,
               StepStatistics& stats, const Matrix3X* failsafe_from);

  // The vertices of x (#V×3, m; free ones, inv_mass > 0) within resting_reach × the collision
  // thickness of an obstacle's surface, each with the outward normal of the nearest obstacle:
  // the candidates for the implicit solve's resting contacts (System::contacts), which keeps
  // those that free flight would move into the obstacle. Empty when an obstacle moves (their
  // surfaces' velocities are not modelled in the solve yet) or there are none.
  void resting_contacts(const Matrix3X& x, std::vector<ObstacleContact>& out) const;
  // A vertex the push-out left on the offset surface is at 1 × the thickness (up to rounding);
  // the margin takes in the small drift of one that slides over a convex surface.
  static constexpr double resting_reach = 1.1;

  // `weft run --explain`'s "project:" and "collide:" lines.
  std::string explain_project() const;
  std::string explain_collide() const;
  const ConstraintProjector* projector() const { return m_projector.get(); }
  const SelfCollision* self_collision() const { return m_self.get(); }
  const ImpactZones* impact_zones() const { return m_zones.get(); }
  // What the phase carries from one step to the next, for a checkpoint: the carried tension,
  // the projector's and self-collision's memory. The obstacles' poses and motions are not: each
  // step poses them anew at its times before it uses them.
  void save_state(StateWriter& out) const;
  void restore_state(StateReader& in);

 private:
  ProjectionResult project(Matrix3X& x, double h_s);  // one projection; carries its tension
  bool collide(const Matrix3X& x_start, Matrix3X& x, bool with_friction, StepStatistics& stats);
  // The failsafe after the last correction: rigid impact zones over x_start → x.
  void failsafe(const Matrix3X& x_start, Matrix3X& x, StepStatistics& stats);
  // The inverse masses with every vertex of the impact zones so far held (0), as the pins are.
  Eigen::VectorXd zones_held() const;
  // The edges with a free end (held: inverse masses, 0 in a zone or at a pin) beyond fast
  // projection's tolerance at x; none for other projections.
  std::vector<std::array<Index, 2>> stretched_edges(const Eigen::VectorXd& held,
                                                    const Matrix3X& x) const;
  ImpactZoneCounts absorb_stretched(const Matrix3X& x_start, Matrix3X& x, ImpactZoneCounts counts);
  static void record(const ProjectionResult& r, StepStatistics& stats);  // a step's, summed
  static constexpr int kContactRounds = 2;  // push-outs between projections, per step
  static constexpr int kHeldRounds = 10;    // projections with the impact zones held, per step
  // Their projections stop, unconverged, when a step the line search shortened leaves Σ C²
  // above this fraction of its value before (ProjectionSettings::stall_fraction): where the
  // held zones leave no shape within the tolerance, the zones take in the stretched edges
  // instead of the iterations crawling on.
  static constexpr double kHeldStallFraction = 0.9;

  const ClothMesh& m_mesh;        // the owner's
  const SimSettings& m_settings;  // the owner's
  const Eigen::VectorXd& m_inv_mass;  // the owner's System's
  std::unique_ptr<ConstraintProjector> m_projector;
  std::shared_ptr<CarriedTensionTerm> m_tension;  // when fast projection carries tension
  std::unique_ptr<SelfCollision> m_self;          // when settings.self_collision.enabled
  std::unique_ptr<ImpactZones> m_zones;           // with m_self, unless impact_zones is off
  std::unique_ptr<ConstraintProjector> m_held_projector;  // the zones' (failsafe), made at need
  // The continuous-collision thickness of the impact zones, a fraction of self-collision's.
  static constexpr double impact_zone_fraction = 0.1;
  std::vector<Obstacle> m_posed_obstacles;        // where the obstacles are at the step's end
  std::vector<RigidPose> m_obstacle_step_motions;  // each one's motion over the step; empty: none
};

}  // namespace weft::sim
